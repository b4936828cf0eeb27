// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-clean/main.cpp
 * @brief  Builds the maps of an .ini (a hif::CHeightIntervalMap among them) from a rawlog, a
 *         .simplemap or a DynamicMap benchmark folder, and writes the cleaned static map, the
 *         removed points, per-scan SemanticKITTI predictions, the serialized map and a JSON
 *         summary.
 */
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <cmath>
#include <deque>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <utility>

#include "Outputs.h"
#include "PoseCheck.h"
#include "ScanSource.h"
#include "Summary.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/apps/Cli.h"
#include "hif/apps/Config.h"
#include "hif/apps/Heap.h"
#include "hif/apps/RunFiles.h"
#include "hif/apps/Staged.h"

namespace fs = std::filesystem;

namespace
{
const std::string kTag = "[hif-clean]";

/** The shipped configuration for the mode and input: kitti-online.ini online, dynamicmap.ini
 *  for a DynamicMap folder, else kitti.ini. */
std::string defaultConfig(bool online, bool dynamicmap)
{
    return hif::apps::shippedConfig(online ? "kitti-online.ini"
                                           : (dynamicmap ? "dynamicmap.ini" : "kitti.ini"));
}

struct Cli
{
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
        "clouds in the sensor frame (NNNNNN.pcd or NNNNNN.ply) with poses.txt (the sensor's "
        "pose in the world for each, KITTI or TUM format), as LiDAR SLAM systems write them",
        true,
        "",
        "in.rawlog|in.simplemap|folder",
        cmd};
    TCLAP::ValueArg<std::string> poses{
        "",
        "poses",
        "The trajectory of a folder of clouds (-i), when it is not the folder's poses.txt: "
        "one line per cloud, the sensor's pose in the world, KITTI format (a 3x4 matrix, 12 "
        "numbers) or TUM format (time x y z qx qy qz qw); e.g. KISS-ICP's *_poses_kitti.txt",
        false,
        "",
        "poses.txt",
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
        "Threads for insertion and classification (overrides the .ini's threads; the result "
        "is the same for any count)",
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
};

/** What a run works with: its input, its maps and where its results go. */
struct Run
{
    std::string input, poses, out_dir, cfg_file, section;
    bool online = false, hold_scans = false, show_progress = true;
    std::unique_ptr<hif::apps::ScanSource> source;
    std::string dm_output;  ///< <folder>/hif_output.pcd for a DynamicMap folder, else empty
    /** The outputs, written aside and put in place when complete. */
    std::unique_ptr<hif::apps::StagedFolder> staged;
    std::unique_ptr<hif::apps::StagedFile> staged_dm;
    std::unique_ptr<hif::apps::StagedFile> staged_rawlog;  ///< --rawlog-out
    mrpt::maps::CMultiMetricMap maps;
    hif::CHeightIntervalMap::Ptr hif_map;
    SensorReport sensor;  ///< the sensor model: where it came from, what contradicted it
    hif::apps::PoseCheck pose_check;  ///< whether the poses align the first scans
    bool poses_doubted = false;
};

/** What hif-clean writes into its output folder (and replaces, with --overwrite). */
const std::vector<std::string> kOutputNames{
    "summary.json", "map.hifmap",  "static_map.ply", "static_map.pcd", "removed.ply",
    "removed.pcd",  "predictions", "map.png",        "map.3Dscene",    "classes.ply"};

/** Checks the command line, opens the input, creates the maps; refuses to replace earlier
 *  results unless asked, and any output that is an input or another output of the run. */
void setUp(Cli& cli, Run& run)
{
    run.input = cli.input.getValue();
    run.out_dir = hif::apps::cleanDir(cli.output.getValue());
    run.online = cli.online.getValue();
    run.hold_scans = cli.hold_scans.getValue();
    run.show_progress = !cli.quiet.getValue();
    run.section = cli.section.getValue();
    if (run.hold_scans && run.online)
        throw std::runtime_error("--hold-scans applies to offline mode only (not --online)");
    if (cli.threads.isSet()) hif::apps::flagInRange(cli.threads.getValue(), "--threads", 1, 1024);

    run.poses = cli.poses.getValue();
    run.source = hif::apps::openScanSource(run.input, {}, true, run.poses);
    run.cfg_file = cli.config.isSet() ? cli.config.getValue()
                                      : defaultConfig(run.online, run.source->isDynamicMapFolder());
    hif::apps::checkConfigFile(run.cfg_file);
    if (run.source->isDynamicMapFolder())
        run.dm_output = hif::apps::cleanDir(run.input) + "/hif_output.pcd";

    // No output may be an input or another output of this run, with or without --overwrite.
    hif::apps::RunFiles files;
    hif::apps::describeInputs(run.input, files, run.poses);
    files.input(run.cfg_file, "the config");
    for (const std::string& n : kOutputNames)
        files.output(run.out_dir + "/" + n, "the " + n + " of -o", n == "predictions");
    if (!run.dm_output.empty()) files.output(run.dm_output, "the DynamicMap result");
    if (cli.rawlog_out.isSet()) files.output(cli.rawlog_out.getValue(), "--rawlog-out");

    // Earlier results are replaced only when asked, and only once the new ones are complete.
    const bool overwrite = cli.overwrite.getValue();
    run.staged = std::make_unique<hif::apps::StagedFolder>(run.out_dir, kOutputNames, overwrite,
                                                           "--overwrite");
    if (!run.dm_output.empty())
        run.staged_dm = std::make_unique<hif::apps::StagedFile>(run.dm_output, overwrite,
                                                                "the DynamicMap result");
    if (cli.rawlog_out.isSet())
        run.staged_rawlog = std::make_unique<hif::apps::StagedFile>(cli.rawlog_out.getValue(),
                                                                    overwrite, "--rawlog-out");

    // Maps from the .ini, through MRPT's own machinery.
    mrpt::config::CConfigFile cfg(run.cfg_file);
    hif::apps::checkMapCounts(cfg, run.section, run.cfg_file);
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, run.section);
    run.maps.setListOfMaps(inits);
    run.hif_map = run.maps.mapByClass<hif::CHeightIntervalMap>();
    if (!run.hif_map)
        throw std::runtime_error(
            "config '" + run.cfg_file + "', section [" + run.section +
            "] defines no CHeightIntervalMap (set CHeightIntervalMap_count=1)");
    // Online or offline is the map's: the run follows it.
    if (run.hif_map->params().online != run.online)
        throw std::runtime_error(
            "config '" + run.cfg_file + "' makes an " +
            (run.online ? "offline map (online=false), but --online classifies each scan as it "
                          "comes: use an online config (share/hif/config/kitti-online.ini, the "
                          "default with --online)"
                        : "online map (online=true), but without --online every scan is "
                          "inserted before any is classified: add --online, or use an offline "
                          "config (share/hif/config/kitti.ini, the default)"));
    if (cli.threads.isSet())
    {
        run.hif_map->insertionOptions.threads = static_cast<uint64_t>(cli.threads.getValue());
        run.hif_map->applyOptions();
    }
}

void printHeader(const Run& run)
{
    std::cout << kTag << " input  : " << run.input
              << (run.poses.empty() ? "" : " at the poses of " + run.poses) << "\n"
              << kTag << " config : " << run.cfg_file << " [" << run.section << "], "
              << run.maps.maps.size() << " map(s)\n"
              << kTag << " mode   : "
              << (run.online ? "online (each scan classified with the past only)"
                             : "offline (all scans inserted, then every point classified)")
              << "\n"
              << kTag << " output : " << run.out_dir << "\n";
    if (const auto& m = run.hif_map->grid().sensorModel())
        std::cout << kTag << " sensor : " << m->describe() << " (given in the config)\n";
    for (const std::string& w : run.source->warnings())
        std::cout << kTag << " warning: " << w << "\n";
}

/** Refuses a scan whose pose is not finite (NaN or inf in a rawlog's pose): every point of it
 *  would be invalid, and the scan silently lost. */
void checkPose(const Run& run, const hif::apps::Scan& scan, std::size_t k)
{
    const auto& p = scan.robot_pose;
    for (const double v : {p.x(), p.y(), p.z(), p.yaw(), p.pitch(), p.roll()})
        if (!std::isfinite(v))
        {
            std::ostringstream msg;
            msg << "scan " << k << " of '" << run.input << "' has a pose that is not finite ("
                << p.asString() << ")";
            throw std::runtime_error(msg.str());
        }
}

/** Refuses a scan with points outside the map's grid (a pose or an origin far off): they could
 *  be neither kept nor judged. */
void checkInsideGrid(const Run& run, std::size_t scan)
{
    const hif::InsertStats& st = run.hif_map->lastInsertStats();
    if (st.points_outside_grid == 0) return;
    const hif::GridGeometry& g = run.hif_map->geometry();
    std::ostringstream msg;
    msg << "scan " << scan << " of '" << run.input << "': " << st.points_outside_grid
        << " of its points lie outside the map's grid (more than 2^31 pillars of " << g.pillar_size
        << " m, or 2^31 height cells of " << g.height_resolution << " m, from the origin ("
        << g.origin_x << ", " << g.origin_y
        << ")): check the scan's pose, or origin_x and origin_y in '" << run.cfg_file << "'";
    throw std::runtime_error(msg.str());
}

/** Prints the sensor model when the map estimated it from scan `k`, and a warning when scan
 *  `k` contradicted it (the first few; all are counted in summary.json). */
void reportSensor(Run& run, std::size_t k)
{
    const hif::InsertStats& st = run.hif_map->lastInsertStats();
    SensorReport& r = run.sensor;
    if (st.sensor_estimated)
    {
        r.estimated_from_scan = k;
        std::cout << kTag << " sensor : " << run.hif_map->grid().sensorModel()->describe()
                  << " (estimated from scan " << k << ")\n";
    }
    if (st.sensor_checked) ++r.checks;
    if (st.sensor_contradiction.empty()) return;
    constexpr std::size_t kShown = 3;
    if (r.contradictions.size() < kShown)
        std::cout << kTag << " warning: scan " << k << " does not look like the sensor "
                  << (r.estimated_from_scan
                          ? "of scan " + std::to_string(*r.estimated_from_scan) +
                                " (are the scans from one LiDAR?)"
                          : std::string("given in the config (is it this LiDAR's?)"))
                  << ": " << st.sensor_contradiction << "\n";
    r.contradictions.push_back("scan " + std::to_string(k) + ": " + st.sensor_contradiction);
}

/** Points of a scan when its type says so without converting it (a point cloud), else 0. */
std::size_t pointsOf(const mrpt::obs::CObservation& obs)
{
    const auto* pc = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&obs);
    return pc && pc->pointcloud ? pc->pointcloud->size() : 0;
}

/** Pass 1: every scan inserted (and, online, classified right after). Returns the scans held
 *  for pass 2 with --hold-scans. */
std::vector<hif::apps::Scan> insertAll(Run& run, Outputs& out, Timings& t)
{
    std::vector<hif::apps::Scan> held;
    hif::apps::Progress progress(kTag, run.online ? "inserting+classifying" : "inserting",
                                 run.source->knownSize(), run.show_progress);
    hif::apps::Scan scan;
    while (run.source->next(scan))
    {
        scan.obs->load();
        checkPose(run, scan, t.scans);
        const auto t0 = Clock::now();
        run.maps.insertObservation(*scan.obs, scan.robot_pose);
        const double ms = msSince(t0);
        checkInsideGrid(run, t.scans);
        reportSensor(run, t.scans);
        if (!run.pose_check.done())
            if (const auto doubt = run.pose_check.add(scan))
            {
                std::cout << kTag << " warning: " << *doubt << std::endl;
                run.poses_doubted = true;
            }
        t.insert_ms.push_back(ms);
        t.points += pointsOf(*scan.obs);
        if (run.online)
        {
            out.classifyAndWrite(*run.hif_map, scan, t.scans);
            t.scan_ms.push_back(ms + out.classify_ms.back());
        }
        else
            t.scan_ms.push_back(ms);
        if (run.hold_scans)
            held.push_back(scan);
        else
            scan.obs->unload();
        ++t.scans;
        progress.update(t.scans);
    }
    progress.finish();
    if (t.scans == 0) throw std::runtime_error("input '" + run.input + "' holds no scans");
    return held;
}

/** Pass 2 (offline): every point of every scan classified against the final map, and, with
 *  the free-space test on, by the free_space_window scans on each side of it: the scans are
 *  read again and given to the map's test in their order, and scan k is classified once scan k
 *  + free_space_window is in (read ahead and held until then). */
void classifyAll(Run& run, std::vector<hif::apps::Scan>& held, Outputs& out, std::size_t scans)
{
    hif::apps::Progress progress(kTag, "classifying", scans, run.show_progress);
    const std::size_t w = run.hif_map->params().free_space_window;
    std::deque<hif::apps::Scan> ahead;  // read, not yet classified
    std::size_t next = 0;               // the next scan to read
    if (!run.hold_scans) run.source->rewind();
    for (std::size_t k = 0; k < scans; ++k)
    {
        while (next < scans && next <= k + w)
        {
            hif::apps::Scan s;
            if (run.hold_scans)
                s = std::move(held[next]);  // released once classified
            else if (!run.source->next(s))
                throw std::runtime_error("input '" + run.input + "' held " + std::to_string(scans) +
                                         " scans when first read, " + std::to_string(next) +
                                         " now");
            s.obs->load();
            if (w > 0) run.hif_map->addToFreeSpaceTest(*s.obs, s.robot_pose);
            ahead.push_back(std::move(s));
            ++next;
        }
        out.classifyAndWrite(*run.hif_map, ahead.front(), k);
        if (!run.hold_scans) ahead.front().obs->unload();
        ahead.pop_front();
        progress.update(k + 1);
    }
    progress.finish();
}

int runClean(Cli& cli)
{
    const auto t_start = Clock::now();
    Run run;
    setUp(cli, run);
    printHeader(run);

    const std::string dir = run.staged->path();
    const std::string& format = cli.format.getValue();
    std::vector<std::string> extensions;
    if (format != "pcd") extensions.push_back(".ply");
    if (format != "ply") extensions.push_back(".pcd");
    std::vector<std::string> static_files, removed_files;
    for (const std::string& ext : extensions)
    {
        static_files.push_back(dir + "/static_map" + ext);
        removed_files.push_back(dir + "/removed" + ext);
    }
    std::vector<std::string> voxel_files;
    if (cli.voxel.isSet())
    {
        const double v = cli.voxel.getValue();
        if (!(v >= 0.001 && v <= 100.0))
            throw std::runtime_error("--voxel " + std::to_string(v) +
                                     ": give the voxel's side in metres, from 0.001 to 100");
        voxel_files = std::exchange(static_files, {});
    }
    if (run.staged_dm) static_files.push_back(run.staged_dm->path());  // the benchmark's
    std::optional<std::size_t> first_frame;
    if (cli.first_frame.isSet())
        first_frame = static_cast<std::size_t>(
            hif::apps::flagInRange(cli.first_frame.getValue(), "--first-frame", 0, 999999));
    Outputs out(dir, first_frame, std::move(static_files), std::move(removed_files));
    if (cli.voxel_memory.isSet() && voxel_files.empty())
        throw std::runtime_error("--voxel-memory goes with --voxel");
    const auto voxel_mib = static_cast<std::size_t>(
        hif::apps::flagInRange(cli.voxel_memory.getValue(), "--voxel-memory", 1, 1 << 20));
    if (!voxel_files.empty())
        out.mergeKept(cli.voxel.getValue(), std::move(voxel_files), voxel_mib << 20);
    if (!cli.no_png.getValue()) out.drawPicture();
    if (cli.rawlog_compress.isSet() && !run.staged_rawlog)
        throw std::runtime_error("--rawlog-compress goes with --rawlog-out");
    const int level = static_cast<int>(
        hif::apps::flagInRange(cli.rawlog_compress.getValue(), "--rawlog-compress", 0, 9));
    if (run.staged_rawlog)
        out.writeRawlog(run.staged_rawlog->path(), cli.rawlog_out.getValue(), level);
    if (cli.classes_ply.getValue()) out.writeClasses(dir + "/classes.ply");
    if (cli.scene.getValue()) out.collectRemoved();
    if (cli.scan_numbers.getValue()) out.writeScanNumbers();
    Timings t;
    t.setup_s = msSince(t_start) / 1000.0;
    auto t_pass = Clock::now();
    std::vector<hif::apps::Scan> held = insertAll(run, out, t);
    t.insert_pass_s = msSince(t_pass) / 1000.0;
    if (!run.online)
    {
        out.expectKept(t.points);  // most points are kept
        out.pictureCovers(*run.hif_map);
        t_pass = Clock::now();
        classifyAll(run, held, out, t.scans);
        t.classify_pass_s = msSince(t_pass) / 1000.0;
    }

    const auto t_files = Clock::now();
    hif::apps::returnFreeHeap();  // the scans' buffers, kept for reuse, go back now
    out.close();
    const std::size_t rawlog_scans = out.closeRawlog();
    run.hif_map->saveToFile(dir + "/map.hifmap");
    std::ostringstream title;
    title << "hif-clean " << fs::path(run.input).filename().string() << ": " << t.scans
          << " scans, " << out.points_kept << " points kept, " << out.points_removed
          << " removed (red)";
    const auto picture = out.writePicture(dir + "/map.png", title.str());
    if (cli.scene.getValue()) out.writeScene(*run.hif_map, dir + "/map.3Dscene");
    t.finish_s = msSince(t_files) / 1000.0;
    t.files_ms = msSince(t_files) + out.write_ms_total;
    t.total_s = msSince(t_start) / 1000.0;

    SummaryInfo info{
        run.input, run.cfg_file, run.online,      run.hold_scans,   run.source->skippedObjects(),
        picture,   run.sensor,   &run.pose_check, run.poses_doubted};
    writeSummary(dir + "/summary.json", info, *run.hif_map, out, t);
    run.staged->commit();
    if (run.staged_dm) run.staged_dm->commit();
    if (run.staged_rawlog)
    {
        run.staged_rawlog->commit();
        std::cout << kTag << " wrote " << cli.rawlog_out.getValue() << ": " << rawlog_scans
                  << " scans without their dynamic points" << std::endl;
    }
    std::vector<std::string> extra;
    if (cli.classes_ply.getValue()) extra.emplace_back("classes.ply");
    if (cli.scene.getValue()) extra.emplace_back("map.3Dscene");
    printReport(kTag, run.out_dir, format, run.dm_output, run.online, *run.hif_map, out, t, extra);
    if (out.drawsPicture() && !picture)
        std::cout << kTag << " map.png not drawn: no point could be drawn\n";
    if (picture && picture->points_outside > 0)
        std::cout << kTag << " map.png shows the map's main area: " << picture->points_outside
                  << " of " << picture->points
                  << " points lie apart from it (more than 100 m of empty ground away: stray "
                     "points, or poses far off) and are not drawn\n";
    return 0;
}
}  // namespace

int main(int argc, char** argv)
{
    hif::apps::keepScanBuffersInTheHeap();
    return hif::apps::cliMain<Cli>(kTag.c_str(), argc, argv, runClean);
}
