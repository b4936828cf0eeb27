// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-synthetic-kitti/main.cpp
 * @brief  hif-synthetic-kitti: a synthetic LiDAR sequence in the SemanticKITTI layout with
 *         exact labels; the work is hif::jobs::SyntheticKitti (apps/jobs), its flags
 *         hif::jobs::SyntheticKittiCommandLine.
 */
#include "hif/apps/Cli.h"
#include "hif/jobs/SyntheticKittiCommandLine.h"

int main(int argc, char** argv)
{
    return hif::apps::cliMain<hif::jobs::SyntheticKittiCommandLine>(argc, argv);
}
