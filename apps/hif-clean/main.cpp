// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-clean/main.cpp
 * @brief  hif-clean: moving objects removed from a LiDAR sequence (the cleaned static map, the
 *         removed points, per-scan predictions, the map and a summary); the work is
 *         hif::jobs::Clean (apps/jobs), its flags hif::jobs::CleanCommandLine.
 */
#include "hif/apps/Cli.h"
#include "hif/apps/Heap.h"
#include "hif/jobs/CleanCommandLine.h"

int main(int argc, char** argv)
{
    hif::apps::keepScanBuffersInTheHeap();
    return hif::apps::cliMain<hif::jobs::CleanCommandLine>(argc, argv);
}
