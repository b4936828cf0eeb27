// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   main.cpp
 * @brief  Consumer of an installed hif: map from an .ini through CMultiMetricMap, scans in,
 *         isStatic/classify out. Exits non-zero if anything is off.
 */
#include <hif/CHeightIntervalMap.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <iostream>

int main()
{
    const mrpt::config::CConfigFileMemory ini(R"(
[map]
CHeightIntervalMap_count=1
[map_CHeightIntervalMap_00_creationOpts]
pillar_size=1.0
[map_CHeightIntervalMap_00_insertOpts]
alpha=0.6
beta=0.45
)");
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(ini, "map");
    mrpt::maps::CMultiMetricMap multi(inits);
    const auto map = multi.mapByClass<hif::CHeightIntervalMap>();
    if (!map)
    {
        std::cerr << "consumer: no hif::CHeightIntervalMap created from the .ini\n";
        return 1;
    }
    // A ground point every scan; an object at 1 m only in the first scan, which later scans
    // see through (their beam toward it returns from twice as far).
    for (int scan = 0; scan < 6; ++scan)
    {
        auto pts = mrpt::maps::CSimplePointsMap::Create();
        pts->insertPoint(10.5f, 0.5f, 0.0f);
        if (scan == 0)
            pts->insertPoint(10.5f, 0.5f, 1.0f);
        else
            pts->insertPoint(21.0f, 1.0f, 2.0f);
        auto obs = mrpt::obs::CObservationPointCloud::Create();
        obs->pointcloud = pts;
        multi.insertObservation(*obs);
    }
    mrpt::maps::CSimplePointsMap query;
    query.insertPoint(10.5f, 0.5f, 0.0f);
    query.insertPoint(10.5f, 0.5f, 1.0f);
    std::vector<uint8_t> dyn;
    map->classify(query, dyn);
    const bool ok = map->isStatic({10.5, 0.5, 0.0}) && !map->isStatic({10.5, 0.5, 1.0}) &&
                    dyn == std::vector<uint8_t>{0, 1};
    std::cout << "consumer: " << map->asString() << (ok ? " -- OK" : " -- WRONG") << "\n";
    return ok ? 0 : 1;
}
