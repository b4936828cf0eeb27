// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ini_only.cpp
 * @brief  Consumer of an installed hif that names no hif symbol, as MRPT's own tools do: it
 *         creates its maps from an .ini, and links hif::hif_mrpt. The HIF map must be there.
 */
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/maps/CMultiMetricMap.h>

#include <iostream>
#include <string>

int main()
{
    const mrpt::config::CConfigFileMemory ini(
        "[map]\nCHeightIntervalMap_count=1\n"
        "[map_CHeightIntervalMap_00_creationOpts]\npillar_size=1.0\n");
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(ini, "map");
    const mrpt::maps::CMultiMetricMap maps(inits);
    if (maps.maps.size() != 1)
    {
        std::cerr << "ini_only: " << maps.maps.size() << " maps created from the .ini, not 1\n";
        return 1;
    }
    const std::string cls = maps.maps[0]->GetRuntimeClass()->className;
    std::cout << "ini_only: created a " << cls << "\n";
    return cls == "hif::CHeightIntervalMap" ? 0 : 1;
}
