// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-icp-slam/main.cpp
 * @brief  hif-icp-slam: 3D LiDAR ICP-SLAM on MRPT whose map HIF keeps clean; the work is
 *         hif::jobs::IcpSlam (apps/jobs), its flags hif::jobs::IcpSlamCommandLine.
 */
#include "hif/apps/Cli.h"
#include "hif/jobs/IcpSlamCommandLine.h"

int main(int argc, char** argv)
{
    return hif::apps::cliMain<hif::jobs::IcpSlamCommandLine>(argc, argv);
}
