// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KittiToRawlogCommandLine.h
 * @brief  kitti2rawlog's command line: its flags (TCLAP), read into hif::jobs::KittiToRawlog's
 * options. The app runs it (hif::apps::cliMain()), the tests run it in process
 *         (hif::apps::runCommandLine()).
 */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

#include "hif/jobs/KittiToRawlog.h"

namespace hif::jobs
{
/** kitti2rawlog's flags, parsed by `cmd`. */
struct KittiToRawlogCommandLine
{
    using Job = KittiToRawlog;

    TCLAP::CmdLine cmd{
        "kitti2rawlog: converts a KITTI odometry sequence (velodyne/*.bin, poses.txt, "
        "calib.txt, times.txt, optional labels/*.label) into an MRPT rawlog. Each scan becomes "
        "a CObservationComment 'kitti frame N' (its number in the sequence), with --odometry a "
        "CObservationOdometry, a "
        "CObservationRobotPose (sensor label 'GROUND_TRUTH': the LiDAR pose in the world, "
        "inv(Tr) * P_i * Tr) and a CObservationPointCloud (sensor label 'LIDAR', a "
        "CPointsMapXYZI in the LiDAR frame, points in file order).",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> input{
        "i", "input", "KITTI sequence folder (e.g. .../sequences/08)", true, "", "folder", cmd};
    TCLAP::ValueArg<std::string> output{
        "o",  "output", "Output rawlog file (with --dynamicmap: output folder)",
        true, "",       "out.rawlog|folder",
        cmd};
    TCLAP::ValueArg<long long> first{"",  "first", "First scan to convert (default: 0)", false, 0,
                                     "N", cmd};
    TCLAP::ValueArg<long long> last{
        "", "last", "Last scan to convert, inclusive (default: the last one)", false, -1, "M", cmd};
    TCLAP::SwitchArg external{
        "", "external",
        "Do not copy the points: each observation refers to its KITTI .bin file by absolute "
        "path (MRPT lazy-load, ExternalStorageFormat::KittiBinFile); the rawlog is then tiny "
        "but needs the sequence folder to stay where it is",
        cmd};
    TCLAP::ValueArg<int> compress{"z",
                                  "compress-level",
                                  "gzip compression level 1-9 of the rawlog; 0 writes it "
                                  "uncompressed (default: 0, the fastest to read)",
                                  false,
                                  0,
                                  "0-9",
                                  cmd};
    TCLAP::SwitchArg dynamicmap{
        "", "dynamicmap",
        "Write the DynamicMap benchmark layout instead of a rawlog: <output>/pcd/NNNNNN.pcd "
        "(binary PCD, x y z intensity in the world frame, the LiDAR pose in VIEWPOINT), what "
        "that benchmark's methods (DUFOMap, OctoMap, ...) and hif-clean read",
        cmd};
    TCLAP::SwitchArg odometry{
        "", "odometry",
        "Also write each scan's LiDAR pose as a CObservationOdometry (sensor label "
        "'GROUND_TRUTH_ODOMETRY': x, y and heading of the same ground-truth pose, not a wheel "
        "odometry), before its CObservationRobotPose: RawLogViewer's 'map from odometry' then "
        "follows the trajectory (hif-clean reads the 3D "
        "CObservationRobotPose and passes the odometry by)",
        cmd};
    TCLAP::ValueArg<double> start_time{
        "",
        "start-time",
        "Time of the sequence's first time in times.txt, seconds since 1970-01-01 UTC (e.g. "
        "$(date -u -d '2011-09-30 12:40:00' +%s)): every scan's time stamp becomes it plus "
        "its times.txt time (default: 0, so a KITTI sequence's stamps start in 1970, as its "
        "times.txt counts from the sequence's start)",
        false,
        0.0,
        "seconds",
        cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite", "Replace the output if it exists", cmd};
    TCLAP::SwitchArg quiet{"q", "quiet", "No progress bar", cmd};

    /** The job's options, from the flags `cmd` parsed. */
    [[nodiscard]] KittiToRawlogOptions options()
    {
        KittiToRawlogOptions o;
        o.input = input.getValue();
        o.output = output.getValue();
        if (first.isSet()) o.first = first.getValue();
        if (last.isSet()) o.last = last.getValue();
        o.external = external.getValue();
        if (compress.isSet()) o.compress_level = compress.getValue();
        o.odometry = odometry.getValue();
        if (start_time.isSet()) o.start_time = start_time.getValue();
        o.dynamicmap = dynamicmap.getValue();
        o.overwrite = overwrite.getValue();
        o.show_progress = !quiet.getValue();
        return o;
    }
};

}  // namespace hif::jobs
