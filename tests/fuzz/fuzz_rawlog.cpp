// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   fuzz_rawlog.cpp
 * @brief  libFuzzer target: hif-clean's rawlog reader and the map behind it. The input drives
 *         a sequence of MRPT objects as a rawlog may hold them (robot poses with any values,
 *         NaN included; frame comments, well formed or not; point-cloud scans with any
 *         coordinates and sensor poses; sensory frames mixing them; a truncated tail), written
 *         with MRPT's serialization. hif-clean's RawlogSource reads them back, and each scan is
 *         inserted and classified: every input is read and cleaned or rejected with an
 *         exception, never a crash.
 *
 * The objects are built rather than the file's bytes mutated: MRPT 2.5.8's own deserializers
 * allocate whatever count a corrupt file states (CPointsMapXYZI::serializeFrom resizes to it
 * before reading), which a byte-level fuzzer reports at once as a multi-GB allocation. That is
 * MRPT's code; here the reader that hif owns is fuzzed.
 */
#include <fuzzer/FuzzedDataProvider.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <exception>

#include "FuzzFiles.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/apps/ScanSource.h"

namespace
{
using namespace mrpt::obs;

mrpt::poses::CPose3D pose(FuzzedDataProvider& in)
{
    double v[6];
    for (double& d : v)
        d = in.ConsumeBool() ? in.ConsumeFloatingPointInRange(-50.0, 50.0)
                             : in.ConsumeFloatingPoint<double>();
    return mrpt::poses::CPose3D(v[0], v[1], v[2], v[3], v[4], v[5]);
}

CObservation::Ptr scan(FuzzedDataProvider& in)
{
    auto cloud = mrpt::maps::CPointsMapXYZI::Create();
    const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 64);
    for (std::size_t k = 0; k < n && in.remaining_bytes() > 0; ++k)
    {
        float xyz[3];
        for (float& c : xyz)
            c = in.ConsumeBool() ? in.ConsumeFloatingPointInRange(-60.f, 60.f)
                                 : in.ConsumeFloatingPoint<float>();
        cloud->insertPointFast(xyz[0], xyz[1], xyz[2]);
    }
    auto obs = CObservationPointCloud::Create();
    obs->pointcloud = cloud;
    if (in.ConsumeBool()) obs->sensorPose = pose(in);
    return obs;
}

CObservation::Ptr observation(FuzzedDataProvider& in)
{
    switch (in.ConsumeIntegralInRange(0, 2))
    {
        case 0:
        {
            auto rp = CObservationRobotPose::Create();
            rp->pose.mean = pose(in);
            return rp;
        }
        case 1:
        {
            auto c = CObservationComment::Create();
            c->text = in.ConsumeBool() ? "kitti frame " + in.ConsumeRandomLengthString(24)
                                       : in.ConsumeRandomLengthString(64);
            return c;
        }
        default:
            return scan(in);
    }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size)
{
    FuzzedDataProvider in(data, size);
    const auto file = hif::fuzz::workDir() / "input.rawlog";
    {
        mrpt::io::CFileOutputStream out(file.string());
        auto arch = mrpt::serialization::archiveFrom(out);
        for (int k = 0; k < 24 && in.remaining_bytes() > 0; ++k)
        {
            if (in.ConsumeIntegralInRange(0, 3) == 0)
            {
                CSensoryFrame sf;
                const int m = in.ConsumeIntegralInRange(0, 3);
                for (int j = 0; j < m; ++j) sf.insert(observation(in));
                arch << sf;
            }
            else
                arch << *observation(in);
        }
        // Whatever is left: a truncated or garbage tail.
        const std::string tail = in.ConsumeBytesAsString(in.remaining_bytes());
        out.Write(tail.data(), tail.size());
    }
    try
    {
        auto source = hif::apps::openRawlog(file.string());
        hif::CHeightIntervalMap map;
        hif::apps::Scan s;
        std::vector<uint8_t> dynamic;
        while (source->next(s))
        {
            map.insertObservation(*s.obs, s.robot_pose);
            (void)map.classify(*s.obs, s.robot_pose, dynamic);
        }
    }
    catch (const std::exception&)
    {
    }
    return 0;
}
