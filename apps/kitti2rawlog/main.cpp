// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   kitti2rawlog/main.cpp
 * @brief  kitti2rawlog's command line: a KITTI odometry sequence (SemanticKITTI layout) into
 *         an MRPT rawlog, or the DynamicMap benchmark layout; the work is
 *         hif::jobs::KittiToRawlog (apps/jobs).
 */
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <iostream>

#include "hif/apps/Cli.h"
#include "hif/jobs/KittiToRawlog.h"

namespace
{
struct Cli
{
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
};

int run(Cli& cli)
{
    hif::jobs::KittiToRawlogOptions o;
    o.input = cli.input.getValue();
    o.output = cli.output.getValue();
    if (cli.first.isSet()) o.first = cli.first.getValue();
    if (cli.last.isSet()) o.last = cli.last.getValue();
    o.external = cli.external.getValue();
    if (cli.compress.isSet()) o.compress_level = cli.compress.getValue();
    o.odometry = cli.odometry.getValue();
    if (cli.start_time.isSet()) o.start_time = cli.start_time.getValue();
    o.dynamicmap = cli.dynamicmap.getValue();
    o.overwrite = cli.overwrite.getValue();
    o.show_progress = !cli.quiet.getValue();
    hif::jobs::KittiToRawlog(o).run(std::cout);
    return 0;
}
}  // namespace

int main(int argc, char** argv)
{
    return hif::apps::cliMain<Cli>(hif::jobs::KittiToRawlog::kTag, argc, argv, run);
}
