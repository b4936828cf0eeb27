// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   IcpSlamCommandLine.h
 * @brief  hif-icp-slam's command line: its flags (TCLAP), read into hif::jobs::IcpSlam's options.
 * The app runs it (hif::apps::cliMain()), the tests run it in process
 *         (hif::apps::runCommandLine()).
 */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

#include "hif/jobs/IcpSlam.h"

namespace hif::jobs
{
/** hif-icp-slam's flags, parsed by `cmd`. */
struct IcpSlamCommandLine
{
    using Job = IcpSlam;

    TCLAP::CmdLine cmd{
        "hif-icp-slam: 3D LiDAR ICP-SLAM on MRPT whose map HIF keeps clean. Estimates the "
        "6-DoF pose of every scan with mrpt::slam::CICP against a voxel map of the earlier "
        "scans, starting from a constant-velocity guess; HIF (online) classifies each scan "
        "at its estimated pose and its dynamic points are kept out of that map. Ground-truth "
        "poses in the input are used only to report the error. Writes poses_kitti.txt (KITTI "
        "odometry format, LiDAR poses in the frame of the first scan), slam_map.ply (the "
        "static points of every scan at its estimated pose), map.hifmap and summary.json.",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> input{
        "i",  "input", "A rawlog (poses optional), a .simplemap, or a KITTI sequence folder",
        true, "",      "in.rawlog|folder",
        cmd};
    TCLAP::ValueArg<std::string> output{
        "o", "output", "Output folder (created if needed)", true, "", "folder", cmd};
    TCLAP::ValueArg<std::string> config{
        "c",   "config", "Configuration (default: the shipped icp-slam-3d.ini)", false, "",
        "ini", cmd};
    TCLAP::ValueArg<std::string> labels{
        "",
        "labels",
        "SemanticKITTI labels folder (NNNNNN.label): count the moving points that entered the "
        "map ICP aligns against (default: <input>/labels for a KITTI folder)",
        false,
        "",
        "folder",
        cmd};
    TCLAP::SwitchArg no_hif{"", "no-hif",
                            "Every point enters the map ICP aligns against (no HIF): for "
                            "comparison",
                            cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite", "Replace earlier results in the output folder",
                               cmd};
    TCLAP::SwitchArg quiet{"q", "quiet", "No progress bar", cmd};

    /** The job's options, from the flags `cmd` parsed. */
    [[nodiscard]] IcpSlamOptions options()
    {
        IcpSlamOptions o;
        o.input = input.getValue();
        o.output = output.getValue();
        if (config.isSet()) o.config = config.getValue();
        o.labels = labels.getValue();
        o.use_hif = !no_hif.getValue();
        o.overwrite = overwrite.getValue();
        o.show_progress = !quiet.getValue();
        return o;
    }
};

}  // namespace hif::jobs
