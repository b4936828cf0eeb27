// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Clean.cpp
 * @brief  A sequence cleaned: set-up (options, input, config, outputs staged), pass 1 (insert;
 *         online also classify), pass 2 (offline: classify with the free-space test's window),
 *         then the files, the summary and the report.
 */
#include "hif/jobs/Clean.h"

#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>
#include <sstream>
#include <utility>

#include "clean/Outputs.h"
#include "clean/PoseCheck.h"
#include "clean/Summary.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/IniSection.h"
#include "hif/apps/Cli.h"
#include "hif/apps/Config.h"
#include "hif/apps/Heap.h"
#include "hif/apps/RunFiles.h"
#include "hif/apps/ScanSource.h"
#include "hif/apps/Staged.h"
#include "hif/apps/Worker.h"
#include "hif/io/Trajectory.h"

namespace fs = std::filesystem;

namespace hif::jobs
{
namespace
{

/** The shipped configuration for the mode and input: kitti-online.ini online, dynamicmap.ini
 *  for a DynamicMap folder, else kitti.ini. */
std::string defaultConfig(bool online, bool dynamicmap)
{
    return hif::apps::shippedConfig(online ? "kitti-online.ini"
                                           : (dynamicmap ? "dynamicmap.ini" : "kitti.ini"));
}

/** What a run works with: its input, its maps and where its results go. */
struct Run
{
    std::string input, out_dir, cfg_file, section;
    hif::apps::FolderPoses poses;  ///< --poses, --extrinsic and --world-frame
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

/** The line of the log for `grid`'s sensor model (it has one); for a sensor without rings,
 *  also the prior that follows from it and how far to trust the result. */
void describeSensor(const hif::PillarGrid& grid, const std::string& source, std::ostream& log)
{
    const hif::SensorModel& m = *grid.sensorModel();
    log << Clean::kTag << " sensor : " << m.describe() << " (" << source << ")\n";
    if (m.hasRings()) return;
    char prior[128];
    std::snprintf(prior, sizeof prior, "new pillars start from p_empty %.2f (p_empty_init %.2f)",
                  grid.pEmptyInit(), grid.params().p_empty_init);
    log << Clean::kTag
        << " note   : a sensor without rings samples a surface at new heights in every scan, so "
           "a height seen once is no sign that it moved: "
        << prior
        << ". It removes fewer movers and more static points than a spinning LiDAR "
           "(doc/sensors.md, \"What does not work well yet\"): check removed.* before using "
           "the static map\n";
}

/** Checks the command line, opens the input, creates the maps; refuses to replace earlier
 *  results unless asked, and any output that is an input or another output of the run. */
void setUp(const CleanOptions& o, Run& run)
{
    run.input = o.input;
    run.out_dir = hif::apps::cleanDir(o.output);
    run.online = o.online;
    run.hold_scans = o.hold_scans;
    run.show_progress = o.show_progress;
    run.section = o.section;
    if (run.hold_scans && run.online)
        throw std::runtime_error("--hold-scans applies to offline mode only (not --online)");
    if (o.threads) hif::apps::flagInRange(*o.threads, "--threads", 1, 1024);

    run.poses.trajectory = o.poses;
    if (!o.extrinsic.empty()) run.poses.extrinsic = hif::io::parseExtrinsic(o.extrinsic);
    run.poses.world_frame = o.world_frame;
    run.source = hif::apps::openScanSource(run.input, {}, true, run.poses);
    run.cfg_file =
        o.config ? *o.config : defaultConfig(run.online, run.source->isDynamicMapFolder());
    hif::apps::checkConfigFile(run.cfg_file);
    if (run.source->isDynamicMapFolder())
        run.dm_output = hif::apps::cleanDir(run.input) + "/hif_output.pcd";

    // No output may be an input or another output of this run, with or without --overwrite.
    hif::apps::RunFiles files;
    hif::apps::describeInputs(run.input, files, run.poses.trajectory);
    files.input(run.cfg_file, "the config");
    for (const std::string& n : kOutputNames)
        files.output(run.out_dir + "/" + n, "the " + n + " of -o", n == "predictions");
    if (!run.dm_output.empty()) files.output(run.dm_output, "the DynamicMap result");
    if (o.rawlog_out) files.output(*o.rawlog_out, "--rawlog-out");

    // Earlier results are replaced only when asked, and only once the new ones are complete.
    const bool overwrite = o.overwrite;
    run.staged = std::make_unique<hif::apps::StagedFolder>(run.out_dir, kOutputNames, overwrite,
                                                           "--overwrite");
    if (!run.dm_output.empty())
        run.staged_dm = std::make_unique<hif::apps::StagedFile>(run.dm_output, overwrite,
                                                                "the DynamicMap result");
    if (o.rawlog_out)
        run.staged_rawlog =
            std::make_unique<hif::apps::StagedFile>(*o.rawlog_out, overwrite, "--rawlog-out");

    // Maps from the .ini, through MRPT's own machinery.
    const hif::ConfigText cfg(run.cfg_file);  // read once, by every loader below
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
    // --threads, else the .ini's threads, else one per hardware thread of this machine.
    if (const auto threads = hif::apps::mapThreads(cfg, run.section, o.threads))
    {
        run.hif_map->insertionOptions.threads = *threads;
        run.hif_map->applyOptions();
    }
}

/** A pose as --extrinsic takes it: "x y z qx qy qz qw". */
std::string describePose(const Eigen::Isometry3d& T)
{
    std::ostringstream s;
    const char* sep = "";
    for (const double v : hif::io::xyzQxyzw(T)) s << std::exchange(sep, " ") << v;
    return s.str();
}

void printHeader(const Run& run, std::ostream& log)
{
    log << Clean::kTag << " input  : " << run.input
        << (run.poses.trajectory.empty() ? "" : " at the poses of " + run.poses.trajectory)
        << (run.poses.extrinsic
                ? ", the LiDAR at (" + describePose(*run.poses.extrinsic) + ") in their frame"
                : "")
        << (run.poses.world_frame ? ", the clouds in the world frame" : "") << "\n"
        << Clean::kTag << " config : " << run.cfg_file << " [" << run.section << "], "
        << run.maps.maps.size() << " map(s)\n"
        << Clean::kTag << " mode   : "
        << (run.online ? "online (each scan classified with the past only)"
                       : "offline (all scans inserted, then every point classified)")
        << ", " << run.hif_map->insertionOptions.threads
        << (run.hif_map->insertionOptions.threads == 1 ? " thread" : " threads") << "\n"
        << Clean::kTag << " output : " << run.out_dir << "\n";
    if (run.hif_map->grid().sensorModel())
        describeSensor(run.hif_map->grid(), "given in the config", log);
    for (const std::string& w : run.source->warnings())
        log << Clean::kTag << " warning: " << w << "\n";
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
void reportSensor(Run& run, std::size_t k, std::ostream& log)
{
    const hif::InsertStats& st = run.hif_map->lastInsertStats();
    SensorReport& r = run.sensor;
    if (st.sensor_estimated)
    {
        const std::string how = r.estimated_from_scan
                                    ? "estimated again from scan " + std::to_string(k) + ": scan " +
                                          std::to_string(*r.estimated_from_scan) +
                                          " saw only part of it"
                                    : "estimated from scan " + std::to_string(k);
        r.estimated_from_scan = k;
        describeSensor(run.hif_map->grid(), how, log);
    }
    if (st.sensor_checked) ++r.checks;
    if (st.sensor_contradiction.empty()) return;
    constexpr std::size_t kShown = 3;
    if (r.contradictions.size() < kShown)
        log << Clean::kTag << " warning: scan " << k << " does not look like the sensor "
            << (r.estimated_from_scan ? "of scan " + std::to_string(*r.estimated_from_scan) +
                                            " (are the scans from one LiDAR?)"
                                      : std::string("given in the config (is it this LiDAR's?)"))
            << ": " << st.sensor_contradiction << "\n";
    r.contradictions.push_back("scan " + std::to_string(k) + ": " + st.sensor_contradiction);
}

/** Prints the pose check's warning, if it gave one. */
void warnOfPoses(Run& run, const std::optional<std::string>& doubt, std::ostream& log)
{
    if (!doubt) return;
    log << Clean::kTag << " warning: " << *doubt << std::endl;
    run.poses_doubted = true;
}

/** Points of a scan when its type says so without converting it (a point cloud), else 0. */
std::size_t pointsOf(const mrpt::obs::CObservation& obs)
{
    const auto* pc = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&obs);
    return pc && pc->pointcloud ? pc->pointcloud->size() : 0;
}

/** Pass 1: every scan inserted (and, online, classified right after). Returns the scans held
 *  for pass 2 with --hold-scans. */
std::vector<hif::apps::Scan> insertAll(Run& run, Outputs& out, Timings& t, std::ostream& log)
{
    std::vector<hif::apps::Scan> held;
    hif::apps::Progress progress(Clean::kTag, run.online ? "inserting+classifying" : "inserting",
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
        reportSensor(run, t.scans, log);
        if (!run.pose_check.done()) warnOfPoses(run, run.pose_check.add(scan), log);
        t.insert_ms.push_back(ms);
        t.points += pointsOf(*scan.obs);
        if (run.online)
        {
            // Unloaded once its files are written, if not held.
            out.classifyAndWrite(*run.hif_map, scan, t.scans, !run.hold_scans);
            t.scan_ms.push_back(ms + out.classify_ms.back());
        }
        else
            t.scan_ms.push_back(ms);
        if (run.hold_scans)
            held.push_back(scan);
        else if (!run.online)
            scan.obs->unload();
        ++t.scans;
        progress.update(t.scans);
    }
    progress.finish();
    if (t.scans == 0) throw std::runtime_error("input '" + run.input + "' holds no scans");
    warnOfPoses(run, run.pose_check.finish(), log);  // a run shorter than the check
    return held;
}

/** Pass 2 (offline): every point of every scan classified against the final map, and, with
 *  the free-space test on, by the free_space_window scans on each side of it: the scans are
 *  given to the map's test in their order, and scan k is classified once scan k +
 *  free_space_window is in. The input is read again for the test, each scan dropped once its
 *  image is made, and once more, free_space_window scans behind, to classify: holding the scans
 *  in between would cost as many scans of memory, and reading a scan (on the readers' threads)
 *  costs less than classifying it. With --hold-scans, the scans come from memory. */
void classifyAll(Run& run, std::vector<hif::apps::Scan>& held, Outputs& out, std::size_t scans)
{
    hif::apps::Progress progress(Clean::kTag, "classifying", scans, run.show_progress);
    const std::size_t w = run.hif_map->params().free_space_window;
    std::unique_ptr<hif::apps::ScanSource> behind;  // the scans to classify, when read apart
    if (!run.hold_scans)
    {
        run.source->rewind();
        if (w > 0) behind = hif::apps::openScanSource(run.input, {}, true, run.poses);
    }
    auto read = [&](hif::apps::ScanSource& source, std::size_t k)
    {
        hif::apps::Scan s;
        if (!source.next(s))
            throw std::runtime_error("input '" + run.input + "' held " + std::to_string(scans) +
                                     " scans when first read, " + std::to_string(k) + " now");
        s.obs->load();
        return s;
    };
    // The free-space test takes the scans ahead of the one classified: each is read (from
    // run.source, or held) and its range image built on a thread of its own, one scan ahead,
    // while this one classifies.
    hif::FreeSpaceTest::ScanMaker maker;
    std::optional<hif::FreeSpaceTest::Scan> made;
    hif::apps::Worker maker_thread;  // last: its destructor waits for the job it holds
    auto make = [&](std::size_t n)
    {
        maker_thread.run(
            [&, n]
            {
                const hif::apps::Scan& s = run.hold_scans ? held[n] : read(*run.source, n);
                made = run.hif_map->makeFreeSpaceScan(*s.obs, s.robot_pose, maker);
                if (!run.hold_scans) s.obs->unload();
            });
    };
    std::size_t next = 0;  // the next scan to give to the free-space test
    if (w > 0 && scans > 0) make(0);
    for (std::size_t k = 0; k < scans; ++k)
    {
        for (; w > 0 && next < scans && next <= k + w; ++next)
        {
            maker_thread.wait();  // rethrows what reading or making it threw
            if (made) run.hif_map->addToFreeSpaceTest(std::move(*made));
            made.reset();
            if (next + 1 < scans) make(next + 1);
        }
        hif::apps::Scan s =
            run.hold_scans ? std::move(held[k]) : read(behind ? *behind : *run.source, k);
        out.classifyAndWrite(*run.hif_map, s, k, !run.hold_scans);
        progress.update(k + 1);
    }
    progress.finish();
}

}  // namespace

CleanResult Clean::run(std::ostream& log) const
{
    const CleanOptions& o = options_;
    const auto t_start = Clock::now();
    Run run;
    setUp(o, run);
    printHeader(run, log);

    const std::string dir = run.staged->path();
    const std::string& format = o.format;
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
    if (o.voxel)
    {
        const double v = *o.voxel;
        if (!(v >= 0.001 && v <= 100.0))
            throw std::runtime_error("--voxel " + std::to_string(v) +
                                     ": give the voxel's side in metres, from 0.001 to 100");
        voxel_files = std::exchange(static_files, {});
    }
    if (run.staged_dm) static_files.push_back(run.staged_dm->path());  // the benchmark's
    std::optional<std::size_t> first_frame;
    if (o.first_frame)
        first_frame = static_cast<std::size_t>(
            hif::apps::flagInRange(*o.first_frame, "--first-frame", 0, 999999));
    Outputs out(dir, first_frame, std::move(static_files), std::move(removed_files));
    if (o.voxel_memory && voxel_files.empty())
        throw std::runtime_error("--voxel-memory goes with --voxel");
    const auto voxel_mib = static_cast<std::size_t>(
        hif::apps::flagInRange(o.voxel_memory.value_or(64), "--voxel-memory", 1, 1 << 20));
    if (!voxel_files.empty()) out.mergeKept(*o.voxel, std::move(voxel_files), voxel_mib << 20);
    if (o.picture) out.drawPicture();
    if (o.rawlog_compress && !run.staged_rawlog)
        throw std::runtime_error("--rawlog-compress goes with --rawlog-out");
    const int level = static_cast<int>(
        hif::apps::flagInRange(o.rawlog_compress.value_or(0), "--rawlog-compress", 0, 9));
    if (run.staged_rawlog) out.writeRawlog(run.staged_rawlog->path(), *o.rawlog_out, level);
    if (o.classes_ply) out.writeClasses(dir + "/classes.ply");
    if (o.scene) out.collectRemoved();
    if (o.scan_numbers) out.writeScanNumbers();
    Timings t;
    t.setup_s = msSince(t_start) / 1000.0;
    auto t_pass = Clock::now();
    std::vector<hif::apps::Scan> held = insertAll(run, out, t, log);
    t.insert_pass_s = msSince(t_pass) / 1000.0;
    if (!run.online)
    {
        out.expectKept(t.points);  // most points are kept
        out.pictureCovers(*run.hif_map);
        // Insertion is done: its buffers go, and the heap's free pages with them, before the
        // second pass takes its own (the peak of the run is in that pass).
        run.hif_map->releaseScanBuffers();
        hif::apps::returnFreeHeap();
        t_pass = Clock::now();
        classifyAll(run, held, out, t.scans);
        t.classify_pass_s = msSince(t_pass) / 1000.0;
    }

    const auto t_files = Clock::now();
    // Once the last scan is written (and the rawlog closed), the scans' buffers, kept for
    // reuse, go back before the files and the picture are made.
    const Outputs::RawlogWritten rawlog = out.closeRawlog();
    run.hif_map->releaseScanBuffers();
    hif::apps::returnFreeHeap();
    // The map, serialized, is saved on a second thread while the clouds are
    // finished (the copies of their bodies) and the picture is drawn.
    auto saved =
        std::async(std::launch::async, [&] { run.hif_map->saveToFile(dir + "/map.hifmap"); });
    out.close();
    std::ostringstream title;
    title << "hif-clean " << fs::path(run.input).filename().string() << ": " << t.scans
          << " scans, " << out.points_kept << " points kept, " << out.points_removed
          << " removed (red)";
    const auto picture = out.writePicture(dir + "/map.png", title.str());
    saved.get();
    if (o.scene) out.writeScene(*run.hif_map, dir + "/map.3Dscene");
    t.finish_s = msSince(t_files) / 1000.0;
    t.files_ms = msSince(t_files) + out.write_ms_total;
    t.total_s = msSince(t_start) / 1000.0;

    SummaryInfo info;
    info.input = run.input;
    info.config = run.cfg_file;
    info.trajectory = hif::apps::inputTrajectory(run.input, run.poses.trajectory);
    info.extrinsic = run.poses.extrinsic;
    info.world_frame = run.poses.world_frame;
    info.online = run.online;
    info.held_scans = run.hold_scans;
    info.skipped_objects = run.source->skippedObjects();
    const auto left_out = run.source->leftOutScans();
    info.scans_left_out = left_out.scans;
    info.picture = picture;
    info.sensor = run.sensor;
    info.poses = &run.pose_check;
    info.poses_doubted = run.poses_doubted;
    writeSummary(dir + "/summary.json", info, *run.hif_map, out, t);
    run.staged->commit();
    if (run.staged_dm) run.staged_dm->commit();
    if (run.staged_rawlog)
    {
        run.staged_rawlog->commit();
        log << Clean::kTag << " wrote " << *o.rawlog_out << ": " << rawlog.scans
            << " scans without their dynamic points";
        if (rawlog.untimed > 0)
            log << "; the input gives no times, so " << rawlog.untimed << " of them have their "
                << "number for a time, in seconds (MRPT's tools need a time)";
        log << std::endl;
    }
    std::vector<std::string> extra;
    if (o.classes_ply) extra.emplace_back("classes.ply");
    if (o.scene) extra.emplace_back("map.3Dscene");
    printReport(log, Clean::kTag, run.out_dir, format, run.dm_output, run.online, *run.hif_map, out,
                t, extra);
    if (left_out.scans > 0) log << Clean::kTag << " warning: " << left_out.why << "\n";
    if (out.drawsPicture() && !picture)
        log << Clean::kTag << " map.png not drawn: no point could be drawn\n";
    if (picture && picture->points_outside > 0)
        log << Clean::kTag << " map.png shows the map's main area: " << picture->points_outside
            << " of " << picture->points
            << " points lie apart from it (more than 100 m of empty ground away: stray "
               "points, or poses far off) and are not drawn\n";
    return {run.out_dir,        t.scans,           out.points_in, out.points_kept,
            out.points_removed, out.points_invalid};
}

}  // namespace hif::jobs
