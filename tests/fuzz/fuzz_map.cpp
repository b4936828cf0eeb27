// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   fuzz_map.cpp
 * @brief  libFuzzer target: deserialization of a CHeightIntervalMap (the map.hifmap that
 *         hif-clean writes, uncompressed). A map that loads must be whole: queried and extended,
 *         it gives answers, never a crash.
 */
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>

#include <exception>

#include "hif/CHeightIntervalMap.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size)
{
    mrpt::io::CMemoryStream in;
    in.assignMemoryNotOwn(data, size);
    hif::CHeightIntervalMap map;
    try
    {
        auto arch = mrpt::serialization::archiveFrom(in);
        arch.ReadObject(&map);
    }
    catch (const std::exception&)
    {
        return 0;
    }
    // Points over the pillars the map holds and around them: classify, then insert.
    auto cloud = mrpt::maps::CSimplePointsMap::Create();
    for (float x = -6.f; x <= 6.f; x += 1.5f)
        for (float y = -6.f; y <= 6.f; y += 1.5f)
            for (float z = -2.f; z <= 3.f; z += 1.f) cloud->insertPoint(x, y, z);
    std::vector<uint8_t> dynamic;
    (void)map.classify(*cloud, dynamic);
    mrpt::obs::CObservationPointCloud obs;
    obs.pointcloud = cloud;
    map.insertObservation(obs, mrpt::poses::CPose3D());
    (void)map.classify(*cloud, dynamic);
    return 0;
}
