// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CleanCommandLine.h
 * @brief  hif-clean's command line: its flags (TCLAP), read into hif::jobs::Clean's options. The
 *         app runs it (hif::apps::cliMain()), the tests run it in process
 *         (hif::apps::runCommandLine()).
 */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

#include "hif/jobs/Clean.h"

namespace hif::jobs
{
/** hif-clean's flags, parsed by `cmd`. */
struct CleanCommandLine
{
    using Job = Clean;

    TCLAP::CmdLine cmd{
        "hif-clean: removes moving objects from a LiDAR sequence with Height Interval "
        "Filtering. Inserts every scan at its pose into the maps of an .ini (which must "
        "define a CHeightIntervalMap), classifies every point, and writes into the output "
        "folder: static_map and removed (world frame, x y z intensity; .ply, .pcd or both: "
        "--format), predictions/NNNNNN.label (9 = static, 251 = moving, one per input point "
        "in input order), map.hifmap (the serialized map) and summary.json.",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> input{
        "i",
        "input",
        "Input: an MRPT rawlog with a CObservationRobotPose before each scan (as kitti2rawlog "
        "writes), a .simplemap, a KITTI sequence folder (velodyne/, poses.txt, calib.txt; "
        "SemanticKITTI layout), a DynamicMap benchmark folder (pcd/NNNNNN.pcd), or a folder of "
        "clouds in the sensor frame (NNNNNN.pcd, .ply or KITTI's .bin) with poses.txt (the "
        "sensor's "
        "pose in the world for each, KITTI or TUM format), as LiDAR SLAM systems write them; "
        "clouds named by their time (1317022176.580342102.pcd, as a bag exported cloud by "
        "cloud) take the pose of their time in a TUM trajectory; hdl_graph_slam's saved "
        "keyframes (NNNNNN/data and cloud.pcd); or a rawlog without poses (as MRPT's "
        "rosbag2rawlog writes one from a ROS bag) with --poses",
        true,
        "",
        "in.rawlog|in.simplemap|folder",
        cmd};
    TCLAP::ValueArg<std::string> poses{
        "",
        "poses",
        "The trajectory of a folder of clouds (-i), when it is not the folder's poses.txt, or "
        "of a rawlog without poses: one line per cloud, the sensor's pose in the world, KITTI "
        "format (a 3x4 matrix, 12 numbers) or TUM format (time x y z qx qy qz qw); e.g. "
        "KISS-ICP's *_poses_kitti.txt. Clouds named by their time, and a rawlog's scans with a "
        "TUM trajectory, take the pose of their time, or one interpolated between the two "
        "around it (at most twice the trajectory's median spacing apart; a rawlog's scans "
        "without one are left out and counted)",
        false,
        "",
        "poses.txt",
        cmd};
    TCLAP::SwitchArg world_frame{
        "", "world-frame",
        "With a folder of clouds: the clouds are in the world frame (registered by the SLAM "
        "system, as FAST-LIO's /cloud_registered), not the sensor's; the trajectory (and "
        "--extrinsic) still says where the LiDAR was for each",
        cmd};
    TCLAP::ValueArg<std::string> extrinsic{
        "",
        "extrinsic",
        "With --poses or a folder's poses.txt: the LiDAR's pose in the frame of the "
        "trajectory's poses, when "
        "they are another sensor's (the IMU of a LiDAR-inertial SLAM system such as FAST-LIO or "
        "LIO-SAM): \"x y z qx qy qz qw\" or the 3x4 matrix row by row (12 numbers); each "
        "scan is then at pose x extrinsic (default: the poses are the LiDAR's)",
        false,
        "",
        "\"x y z qx qy qz qw\"",
        cmd};
    TCLAP::ValueArg<std::string> output{
        "o", "output", "Output folder (created if needed)", true, "", "folder", cmd};
    TCLAP::ValueArg<std::string> config{
        "c",
        "config",
        "Map definition .ini (default: the shipped share/hif/config/kitti.ini; "
        "kitti-online.ini with --online; dynamicmap.ini for a DynamicMap folder)",
        false,
        "",
        "config.ini",
        cmd};
    std::vector<std::string> formats{"ply", "pcd", "both"};
    TCLAP::ValuesConstraint<std::string> format_values{formats};
    TCLAP::ValueArg<std::string> format{
        "",
        "format",
        "Point-cloud format of static_map and removed: ply (binary, read by MRPT, PCL, "
        "CloudCompare, MeshLab, Open3D), pcd (binary) or both (default: ply). A DynamicMap "
        "folder's hif_output.pcd is written in any case",
        false,
        "ply",
        &format_values,
        cmd};
    TCLAP::SwitchArg no_png{"", "no-png",
                            "Do not draw map.png (the bird's-eye picture of kept and removed "
                            "points)",
                            cmd};
    TCLAP::ValueArg<std::string> rawlog_out{
        "",
        "rawlog-out",
        "Also write the scans without their dynamic points as an MRPT rawlog (observations: "
        "frame comment, CObservationRobotPose, the scan), for rawlog-edit, RawLogViewer or "
        "icp-slam",
        false,
        "",
        "clean.rawlog",
        cmd};
    TCLAP::ValueArg<long long> rawlog_compress{
        "",
        "rawlog-compress",
        "gzip compression level 1-9 of --rawlog-out's rawlog (as kitti2rawlog -z); 0 writes it "
        "uncompressed (default: 0, the fastest to read)",
        false,
        0,
        "0-9",
        cmd};
    TCLAP::ValueArg<double> voxel{
        "",
        "voxel",
        "Write static_map as a map at this resolution: the kept points merged per cubic voxel of "
        "this side in metres (x y z: their centroid, intensity: their mean, uint points: how many "
        "were merged), in bounded memory, so that a long sequence gives a map of its area's "
        "size; removed and a DynamicMap folder's hif_output.pcd keep every point (default: "
        "every kept point, as read)",
        false,
        0.0,
        "metres",
        cmd};
    TCLAP::ValueArg<long long> voxel_memory{
        "",
        "voxel-memory",
        "With --voxel: memory for the voxels around the sensor, MiB (the others wait on disk, "
        "next to the output, until the end; default: 64, some 900,000 voxels, a few hundred "
        "metres of street at 0.1 m)",
        false,
        64,
        "MiB",
        cmd};
    TCLAP::SwitchArg classes_ply{
        "", "classes-ply",
        "Also write classes.ply: every point (world frame) with its intensity, a colour by its "
        "class (kept light grey, removed red) and its class (uchar class: 0 kept, 1 removed)",
        cmd};
    TCLAP::SwitchArg scan_numbers{
        "", "scan-numbers",
        "Give every point of the clouds (static_map, removed, classes.ply) the number of its scan "
        "(uint scan, as its predictions file) and, where the input has times (KITTI times.txt, "
        "rawlog time stamps, a TUM trajectory), its scan's time (double time, seconds): for "
        "re-projecting the kept points or running again on a part",
        cmd};
    TCLAP::SwitchArg scene{"", "scene",
                           "Also write map.3Dscene, for MRPT's SceneViewer3D: what the map keeps "
                           "(its static intervals as boxes, coloured by height from blue to "
                           "yellow) and the removed points in red",
                           cmd};
    TCLAP::ValueArg<std::string> section{
        "",     "section", "Section of the .ini with the map list (default: map)", false, "map",
        "name", cmd};
    TCLAP::SwitchArg online{
        "", "online",
        "Classify each scan right after inserting it, with the map of the past only (what a "
        "SLAM system gets); default: offline, insert all scans then classify every point "
        "against the final map (two passes over the input)",
        cmd};
    TCLAP::ValueArg<long long> first_frame{
        "",
        "first-frame",
        "Number of the first prediction file, when the input does not number its scans "
        "(kitti2rawlog's rawlogs and DynamicMap folders do; default: 0)",
        false,
        0,
        "N",
        cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite",
                               "Replace earlier results in the output folder (and "
                               "hif_output.pcd in a DynamicMap folder)",
                               cmd};
    TCLAP::ValueArg<long long> threads{
        "t",
        "threads",
        "Threads for insertion and classification (default: the .ini's threads, else one per "
        "hardware thread of this machine; the result is the same for any count)",
        false,
        1,
        "N",
        cmd};
    TCLAP::SwitchArg hold_scans{
        "", "hold-scans",
        "Offline: keep every scan in memory after inserting it, and classify from memory "
        "instead of reading the input a second time (faster on slow storage; memory grows "
        "with the sequence)",
        cmd};
    TCLAP::SwitchArg quiet{"q", "quiet", "No progress bar", cmd};

    /** The job's options, from the flags `cmd` parsed. */
    [[nodiscard]] CleanOptions options()
    {
        CleanOptions o;
        o.input = input.getValue();
        o.poses = poses.getValue();
        o.extrinsic = extrinsic.getValue();
        o.world_frame = world_frame.getValue();
        o.output = output.getValue();
        if (config.isSet()) o.config = config.getValue();
        o.section = section.getValue();
        o.format = format.getValue();
        o.picture = !no_png.getValue();
        if (rawlog_out.isSet()) o.rawlog_out = rawlog_out.getValue();
        if (rawlog_compress.isSet()) o.rawlog_compress = rawlog_compress.getValue();
        if (voxel.isSet()) o.voxel = voxel.getValue();
        if (voxel_memory.isSet()) o.voxel_memory = voxel_memory.getValue();
        o.classes_ply = classes_ply.getValue();
        o.scan_numbers = scan_numbers.getValue();
        o.scene = scene.getValue();
        o.online = online.getValue();
        if (first_frame.isSet()) o.first_frame = first_frame.getValue();
        o.overwrite = overwrite.getValue();
        if (threads.isSet()) o.threads = threads.getValue();
        o.hold_scans = hold_scans.getValue();
        o.show_progress = !quiet.getValue();
        return o;
    }
};

}  // namespace hif::jobs
