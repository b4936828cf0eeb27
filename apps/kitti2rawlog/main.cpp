// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   kitti2rawlog/main.cpp
 * @brief  kitti2rawlog: a KITTI odometry sequence (SemanticKITTI layout) into an MRPT rawlog,
 *         or the DynamicMap benchmark layout; the work is hif::jobs::KittiToRawlog
 *         (apps/jobs), its flags hif::jobs::KittiToRawlogCommandLine.
 */
#include "hif/apps/Cli.h"
#include "hif/jobs/KittiToRawlogCommandLine.h"

int main(int argc, char** argv)
{
    return hif::apps::cliMain<hif::jobs::KittiToRawlogCommandLine>(argc, argv);
}
