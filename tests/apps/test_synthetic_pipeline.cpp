// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_synthetic_pipeline.cpp
 * @brief  The synthetic pipeline (generate, convert, clean offline and online, evaluate) with
 *         asserted scores and outputs: formats, threads, held scans, the 3D view, DynamicMap and
 *         KITTI folders, --rawlog-out, odometry, and clear errors on bad input.
 */
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/serialization/CArchive.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "app_checks.h"
#include "app_runner.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/apps/TopView.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "job_runner.h"
#include "synthetic_suite.h"

namespace fs = std::filesystem;
using nlohmann::json;

using hif::test::bytesOf;
using hif::test::clean;
using hif::test::evaluate;
using hif::test::synthesize;
using hif::test::toRawlog;
using Options = hif::jobs::CleanOptions;
using hif::test::expectError;
using hif::test::readJson;
using hif::test::runInProcess;
using hif::test::WorkDir;
using hif::test::workDir;

using hif::test::classesOf;
using hif::test::coloursOf;
using hif::test::noPicture;
using hif::test::packed;
using hif::test::plyVertexCount;
using hif::test::rawlogObjects;

/** Twenty synthetic scans and their rawlog, shared by the suite's tests. */
class SyntheticPipeline : public hif::test::SyntheticSuite<SyntheticPipeline>
{
public:
    static constexpr const char* kFolder = "synthetic";
    static constexpr long long kScans = 20;
    static constexpr const char* kRawlog = "scans.rawlog";
};

TEST_F(SyntheticPipeline, OfflineAndOnlineCleaningScoreAndWriteEverything)
{
    const hif::io::KittiSequence seq(root_ + "/seq");
    for (const std::string mode : {"offline", "online", "held"})
    {
        SCOPED_TRACE(mode);
        const std::string out = root_ + "/" + mode;
        // Offline with both cloud formats, the others with the default (PLY only).
        const auto r = clean(root_ + "/scans.rawlog", out,
                             [&](Options& o)
                             {
                                 o.online = mode == "online";
                                 o.hold_scans = mode == "held";
                                 if (mode == "offline") o.format = "both";
                             });
        ASSERT_EQ(r.code, 0) << r.output;
        // Offline, also the picture of the four outcomes.
        const auto e = evaluate(root_ + "/seq/labels", out + "/predictions",
                                [&](hif::jobs::EvaluateOptions& o)
                                {
                                    o.json = out + "/scores.json";
                                    if (mode != "offline") return;
                                    o.scans = root_ + "/seq/velodyne";
                                    o.png = out + "/outcomes.png";
                                    o.classes_ply = out + "/outcomes.ply";
                                });
        ASSERT_EQ(e.code, 0) << e.output;
        const json s = readJson(out + "/scores.json")["total"];
        // Measured (demo, 30 scans): offline SA 99.35 / DA 97.98, online SA 98.95 / DA 95.95.
        EXPECT_GE(s["SA"].get<double>(), mode == "online" ? 98.0 : 99.0);
        EXPECT_GE(s["DA"].get<double>(), mode == "online" ? 90.0 : 95.0);
        EXPECT_GT(s["dynamic_total"].get<int>(), 10000);

        const json sum = readJson(out + "/summary.json");
        EXPECT_EQ(sum["scans"], 20);
        EXPECT_EQ(sum["mode"], mode == "online" ? "online" : "offline");
        const auto in = sum["points_in"].get<std::size_t>();
        const auto kept = sum["points_kept"].get<std::size_t>();
        const auto removed = sum["points_removed"].get<std::size_t>();
        EXPECT_EQ(kept + removed, in);
        for (const char* k : {"scan_ms_median", "scan_ms_p90", "scan_ms_max", "peak_rss_mb"})
            EXPECT_GT(sum[k].get<double>(), 0.0) << k;
        EXPECT_LE(sum["scan_ms_median"].get<double>(), sum["scan_ms_p90"].get<double>());
        EXPECT_LE(sum["scan_ms_p90"].get<double>(), sum["scan_ms_max"].get<double>());

        // One prediction per scan, in scan order: one label per point of that scan.
        std::size_t labels = 0;
        for (std::size_t i = 0; i < 20; ++i)
        {
            const std::size_t n =
                hif::io::readLabels(out + "/predictions/" + hif::io::frameName(i) + ".label")
                    .size();
            EXPECT_EQ(n, seq.pointCount(i)) << "prediction " << i;
            labels += n;
        }
        EXPECT_EQ(labels, in);
        // The clouds hold exactly the kept and the removed points, in the formats asked for.
        EXPECT_EQ(plyVertexCount(out + "/static_map.ply"), kept);
        EXPECT_EQ(plyVertexCount(out + "/removed.ply"), removed);
        if (mode == "offline")
        {
            EXPECT_EQ(hif::io::readPcd(out + "/static_map.pcd").x.size(), kept);
            EXPECT_EQ(hif::io::readPcd(out + "/removed.pcd").x.size(), removed);
            // The same body after each header.
            const std::string ply = bytesOf(out + "/static_map.ply"),
                              pcd = bytesOf(out + "/static_map.pcd");
            EXPECT_EQ(ply.substr(ply.size() - kept * 16), pcd.substr(pcd.size() - kept * 16));
        }
        else
        {
            EXPECT_FALSE(fs::exists(out + "/static_map.pcd"));
            EXPECT_FALSE(fs::exists(out + "/removed.pcd"));
        }

        // The picture: a PNG at least 1200 px wide, grey kept points and red removed ones.
        const cv::Mat png = cv::imread(out + "/map.png");
        ASSERT_FALSE(png.empty());
        EXPECT_GE(png.cols, 1200);
        std::size_t red = 0, grey = 0;
        for (int row = 0; row < png.rows; ++row)
            for (int col = 0; col < png.cols; ++col)
            {
                const cv::Vec3b p = png.at<cv::Vec3b>(row, col);  // BGR
                red += p[2] > 200 && p[1] < 80 && p[0] < 80;
                grey += p[0] == p[1] && p[1] == p[2] && p[0] >= 70;
            }
        EXPECT_GT(red, 1000u);
        EXPECT_GT(grey, 50000u);
        if (mode == "offline")
        {
            // Same size as hif-clean's (the same points), stated by hif-eval.
            const cv::Mat outcomes = cv::imread(out + "/outcomes.png");
            ASSERT_FALSE(outcomes.empty());
            EXPECT_NE(e.output.find("outcomes.png (" + std::to_string(outcomes.cols) + " x " +
                                    std::to_string(outcomes.rows) + ")"),
                      std::string::npos)
                << e.output;
            EXPECT_GE(outcomes.cols, 1200);
            // The coloured PLY of the outcomes agrees with the scores.
            using V = hif::apps::TopView;
            const auto colours = coloursOf(out + "/outcomes.ply");
            EXPECT_EQ(
                colours.at(packed(V::kMissedMoving)),
                s["dynamic_total"].get<std::size_t>() - s["dynamic_removed"].get<std::size_t>());
            EXPECT_EQ(colours.at(packed(V::kWronglyRemoved)),
                      s["static_total"].get<std::size_t>() - s["static_kept"].get<std::size_t>());
            // Red is for removed moving points only; removed unlabelled ones have their own.
            const auto count = [&colours](V::Outcome o)
            {
                const auto it = colours.find(packed(o));
                return it == colours.end() ? std::size_t{0} : it->second;
            };
            EXPECT_EQ(count(V::kRemoved), s["dynamic_removed"].get<std::size_t>());
            EXPECT_EQ(count(V::kRemoved) + count(V::kWronglyRemoved) + count(V::kRemovedUnlabelled),
                      removed);
        }
        // The saved map loads back through MRPT's class factory, as the one that was used.
        mrpt::io::CFileGZInputStream f(out + "/map.hifmap");
        auto arch = mrpt::serialization::archiveFrom(f);
        const auto map = std::dynamic_pointer_cast<hif::CHeightIntervalMap>(arch.ReadObject());
        ASSERT_TRUE(map);
        EXPECT_EQ(map->pillarCount(), sum["pillars"].get<std::size_t>());
        EXPECT_EQ(map->intervalCount(), sum["intervals"].get<std::size_t>());
    }
}

// Two threads and scans held in memory change how the work is done, not its result: the same
// predictions, the same map, byte for byte.
TEST_F(SyntheticPipeline, ThreadsAndHeldScansGiveIdenticalResults)
{
    const std::string a = root_ + "/one_thread", b = root_ + "/two_threads_held";
    auto r = clean(root_ + "/scans.rawlog", a, [](Options& o) { o.threads = 1; });
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(root_ + "/scans.rawlog", b,
              [](Options& o)
              {
                  o.threads = 2;
                  o.hold_scans = true;
                  o.picture = false;
                  o.scene = true;
                  o.classes_ply = true;
              });
    ASSERT_EQ(r.code, 0) << r.output;
    // The last line says what was written, the files asked for too.
    EXPECT_NE(r.output.find("predictions/, map.hifmap, classes.ply, map.3Dscene, summary.json"),
              std::string::npos)
        << r.output;
    EXPECT_TRUE(fs::exists(a + "/map.png"));
    EXPECT_FALSE(fs::exists(b + "/map.png"));
    EXPECT_FALSE(fs::exists(a + "/map.3Dscene"));
    // The 3D view draws what the map decided: a box (10 triangles) for each static interval of
    // the saved map, none for the others, and each removed point in red.
    const json sb0 = readJson(b + "/summary.json");
    mrpt::opengl::COpenGLScene scene;
    ASSERT_TRUE(scene.loadFromFile(b + "/map.3Dscene"));
    const auto boxes = std::dynamic_pointer_cast<mrpt::opengl::CSetOfTriangles>(
        scene.getByName("hif::CHeightIntervalMap"));
    ASSERT_TRUE(boxes);
    hif::CHeightIntervalMap saved;
    saved.loadFromFile(b + "/map.hifmap");
    std::size_t static_intervals = 0;
    for (const auto& [idx, pillar] : saved.grid().sortedPillars())
        for (const hif::Interval& iv : pillar->intervals)
            static_intervals += saved.grid().isStaticLogOdds(iv.logodds);
    EXPECT_LT(static_intervals, saved.intervalCount());
    EXPECT_EQ(boxes->getTrianglesCount(), 10 * static_intervals);
    const auto removed = std::dynamic_pointer_cast<mrpt::opengl::CPointCloud>(
        scene.getByName("hif: removed points"));
    ASSERT_TRUE(removed);
    EXPECT_EQ(removed->size(),
              sb0["points_removed"].get<std::size_t>() - sb0["points_invalid"].get<std::size_t>());
    // Every point with its intensity, its class (0 kept, 1 removed) and its class's colour.
    double intensities = 0;
    const auto classes = classesOf(b + "/classes.ply", intensities);
    EXPECT_EQ(classes.size(), 2u);
    EXPECT_EQ(classes.at({packed(hif::apps::TopView::kRemoved), 1}),
              sb0["points_removed"].get<std::size_t>() - sb0["points_invalid"].get<std::size_t>());
    EXPECT_EQ(classes.at({packed(hif::apps::TopView::kKept), 0}),
              sb0["points_kept"].get<std::size_t>());
    double kept_and_removed = 0;
    for (const char* cloud : {"/static_map.ply", "/removed.ply"})
    {
        std::ifstream f(b + cloud, std::ios::binary);
        for (std::string line; std::getline(f, line) && line != "end_header";)
        {
        }
        for (float rec[4]; f.read(reinterpret_cast<char*>(rec), 16);) kept_and_removed += rec[3];
    }
    EXPECT_GT(intensities, 0.0);
    EXPECT_NEAR(intensities, kept_and_removed, 1e-9 * kept_and_removed);
    auto bytes = [](const std::string& file)
    {
        std::ifstream in(file, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), {});
    };
    for (int i = 0; i < 20; ++i)
    {
        const std::string f = "/predictions/" + hif::io::frameName(i) + ".label";
        ASSERT_EQ(bytes(a + f), bytes(b + f)) << f;
    }
    EXPECT_EQ(bytes(a + "/static_map.ply"), bytes(b + "/static_map.ply"));
    EXPECT_EQ(bytes(a + "/map.hifmap"), bytes(b + "/map.hifmap"));
    const json sa = readJson(a + "/summary.json"), sb = readJson(b + "/summary.json");
    EXPECT_EQ(sa["threads"], 1);
    EXPECT_EQ(sb["threads"], 2);
    EXPECT_EQ(sa["held_scans"], false);
    EXPECT_EQ(sb["held_scans"], true);
    // The map's own memory: more than its intervals' bytes, and far below the process's. It
    // counts vector capacities, which depend on how scratch buffers were swapped by each
    // thread, so two runs agree closely but not exactly.
    const auto map_bytes = sa["map_bytes"].get<double>();
    EXPECT_NEAR(sb["map_bytes"].get<double>(), map_bytes, 0.05 * map_bytes);
    EXPECT_GT(map_bytes, 12.0 * sa["intervals"].get<double>());
    EXPECT_LT(map_bytes, sa["peak_rss_mb"].get<double>() * 1024 * 1024);

    const std::string rawlog = root_ + "/scans.rawlog", x = root_ + "/x";
    r = clean(rawlog, x,
              [](Options& o)
              {
                  o.online = true;
                  o.hold_scans = true;
              });
    expectError(r, "--hold-scans applies to offline mode only");
    // Online or offline is the map's (its config's `online`): a run the other way is refused.
    r = clean(rawlog, x,
              [](Options& o)
              {
                  o.online = true;
                  o.config = HIF_SHARE_DIR "/config/kitti.ini";
              });
    expectError(r, "makes an offline map (online=false), but --online classifies each scan");
    r = clean(rawlog, x, [](Options& o) { o.config = HIF_SHARE_DIR "/config/kitti-online.ini"; });
    expectError(r, "makes an online map (online=true), but without --online");
    r = clean(rawlog, x, [](Options& o) { o.threads = 0; });
    expectError(r, "--threads 0 is not in [1, 1024]");
}

// The thread count: --threads, else the .ini's `threads`, else one per hardware thread of the
// machine (a batch run uses the cores it has; the outputs are the same for any count).
TEST_F(SyntheticPipeline, ThreadsComeFromTheCommandLineTheIniOrTheMachine)
{
    const std::string rawlog = root_ + "/scans.rawlog", out = root_ + "/threads";
    const std::string ini = root_ + "/one_thread.ini";
    {
        std::ifstream in(HIF_SHARE_DIR "/config/kitti.ini");
        std::stringstream ss;
        ss << in.rdbuf();
        std::string text = ss.str();
        const std::string section = "[map_CHeightIntervalMap_00_insertOpts]\n";
        const auto at = text.find(section);
        ASSERT_NE(at, std::string::npos);
        text.insert(at + section.size(), "threads=1\n");
        std::ofstream(ini) << text;
    }
    auto threadsOf = [&](auto&& options)
    {
        const auto r = clean(rawlog, out, options);
        EXPECT_EQ(r.code, 0) << r.output;
        return readJson(out + "/summary.json")["threads"].get<long long>();
    };
    const long long machine = std::max(1u, std::thread::hardware_concurrency());
    EXPECT_EQ(threadsOf([](Options& o) { o.overwrite = true; }), machine);
    EXPECT_EQ(threadsOf(
                  [&](Options& o)
                  {
                      o.overwrite = true;
                      o.config = ini;
                  }),
              1);
    EXPECT_EQ(threadsOf(
                  [&](Options& o)
                  {
                      o.overwrite = true;
                      o.config = ini;
                      o.threads = 3;
                  }),
              3);
}

TEST_F(SyntheticPipeline, RefusesToOverwriteAndNamesBadInput)
{
    // The rawlog exists: kitti2rawlog does not replace it unless told to.
    auto r = runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + root_ + "/scans.rawlog");
    expectError(r, "already exists; pass --overwrite");
    // A missing input is named.
    r = runInProcess("hif-clean", "-i " + root_ + "/nothing.rawlog -o " + root_ + "/x");
    expectError(r, "nothing.rawlog' does not exist");
    // A truncated rawlog is an error naming the file, not a silent partial map.
    {
        std::ifstream in(root_ + "/scans.rawlog", std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
        std::ofstream out(root_ + "/truncated.rawlog", std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2 + 7));
    }
    r = runInProcess("hif-clean", "-i " + root_ + "/truncated.rawlog -o " + root_ + "/trunc -q");
    expectError(r, "truncated.rawlog' is corrupt or truncated");
    // What MRPT found, without its exception frames.
    EXPECT_EQ(r.output.find("==== MRPT exception"), std::string::npos) << r.output;
    // A short pose file is named with the counts.
    const WorkDir work = workDir("short_poses");
    const std::string& bad = work.path();
    fs::copy(root_ + "/seq", bad, fs::copy_options::recursive);
    {
        std::ifstream in(bad + "/poses.txt");
        std::string first;
        std::getline(in, first);
        in.close();
        std::ofstream out(bad + "/poses.txt", std::ios::trunc);
        out << first << "\n";
    }
    r = runInProcess("kitti2rawlog", "-i " + bad + " -o " + bad + "/x.rawlog");
    expectError(r, "poses.txt' has 1 poses for 20 scans");
    EXPECT_FALSE(fs::exists(bad + "/x.rawlog"));
    // A bad config value is named with its section.
    {
        std::ifstream in(HIF_SHARE_DIR "/config/kitti.ini");
        std::stringstream ss;
        ss << in.rdbuf();
        std::string ini = ss.str();
        ini.replace(ini.find("alpha=0.6"), 9, "alpha=0.4");
        std::ofstream(bad + "/bad.ini") << ini;
    }
    r = runInProcess("hif-clean",
                     "-i " + root_ + "/scans.rawlog -o " + bad + "/out -c " + bad + "/bad.ini");
    expectError(r, "invalid alpha = 0.4");
}

TEST_F(SyntheticPipeline, DynamicMapFolderLayoutIsReadAndItsOutputWritten)
{
    // Build the benchmark's layout from the synthetic sequence: pcd/NNNNNN.pcd with world
    // points and the sensor pose in VIEWPOINT.
    const WorkDir work = workDir("dynamicmap");
    const std::string& dm = work.path();
    fs::create_directories(dm + "/pcd");
    const hif::io::KittiSequence seq(root_ + "/seq");
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        std::ifstream bin(seq.scanFile(i), std::ios::binary);
        std::vector<float> p(seq.pointCount(i) * 4);
        bin.read(reinterpret_cast<char*>(p.data()), static_cast<std::streamsize>(p.size() * 4));
        const Eigen::Isometry3d T = seq.pose(i);
        const Eigen::Quaterniond q(T.linear());
        std::ofstream f(dm + "/pcd/" + hif::io::frameName(i) + ".pcd");
        f << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
          << "WIDTH " << p.size() / 4 << "\nHEIGHT 1\nVIEWPOINT " << T.translation().x() << " "
          << T.translation().y() << " " << T.translation().z() << " " << q.w() << " " << q.x()
          << " " << q.y() << " " << q.z() << "\nPOINTS " << p.size() / 4 << "\nDATA ascii\n";
        for (std::size_t k = 0; k < p.size(); k += 4)
        {
            const Eigen::Vector3d w = T * Eigen::Vector3d(p[k], p[k + 1], p[k + 2]);
            f << w.x() << " " << w.y() << " " << w.z() << " " << p[k + 3] << "\n";
        }
    }
    const auto r = runInProcess("hif-clean", "-i " + dm + " -o " + dm + "/out -q");
    ASSERT_EQ(r.code, 0) << r.output;
    ASSERT_TRUE(fs::exists(dm + "/hif_output.pcd")) << r.output;
    const json sum = readJson(dm + "/out/summary.json");
    EXPECT_EQ(sum["scans"], 20);
    EXPECT_EQ(hif::io::readPcd(dm + "/hif_output.pcd").x.size(),
              sum["points_kept"].get<std::size_t>());
    const auto e =
        runInProcess("hif-eval", "--labels " + root_ + "/seq/labels --predictions " + dm +
                                     "/out/predictions --json " + dm + "/scores.json");
    ASSERT_EQ(e.code, 0) << e.output;
    const json s = readJson(dm + "/scores.json")["total"];
    EXPECT_GE(s["SA"].get<double>(), 99.0);
    EXPECT_GE(s["DA"].get<double>(), 95.0);
    // A second run does not replace the benchmark output without --overwrite.
    const auto again = runInProcess("hif-clean", "-i " + dm + " -o " + dm + "/out2 -q");
    expectError(again, "hif_output.pcd' already exists");
}

// A KITTI sequence folder is read directly, with the same result as its rawlog; and
// kitti2rawlog --dynamicmap writes the benchmark layout, which gives the same classes up to the
// float rounding of points stored in the world frame.
TEST_F(SyntheticPipeline, KittiAndDynamicMapFoldersGiveTheRawlogsResult)
{
    const std::string from_rawlog = root_ + "/ref_rawlog", from_folder = root_ + "/ref_folder";
    auto r = clean(root_ + "/scans.rawlog", from_rawlog);
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(root_ + "/seq", from_folder);
    ASSERT_EQ(r.code, 0) << r.output;
    for (const std::string f : {"/static_map.ply", "/removed.ply", "/map.hifmap"})
        EXPECT_EQ(bytesOf(from_rawlog + f), bytesOf(from_folder + f)) << f;
    for (int i = 0; i < 20; ++i)
    {
        const std::string f = "/predictions/" + hif::io::frameName(i) + ".label";
        ASSERT_EQ(bytesOf(from_rawlog + f), bytesOf(from_folder + f)) << f;
    }
    EXPECT_EQ(readJson(from_folder + "/summary.json")["input"], root_ + "/seq");

    const std::string dm = root_ + "/dm_from_kitti";
    fs::remove_all(dm);
    r = toRawlog(root_ + "/seq", dm,
                 [](hif::jobs::KittiToRawlogOptions& o)
                 {
                     o.dynamicmap = true;
                     o.last = 9;
                 });
    ASSERT_EQ(r.code, 0) << r.output;
    ASSERT_TRUE(fs::exists(dm + "/pcd/000009.pcd"));
    EXPECT_FALSE(fs::exists(dm + "/pcd/000010.pcd"));
    // World-frame points, the LiDAR pose in VIEWPOINT.
    const hif::io::KittiSequence seq(root_ + "/seq");
    const hif::io::PcdCloud c = hif::io::readPcd(dm + "/pcd/000007.pcd");
    const hif::io::Cloud raw = seq.readScan(7);
    ASSERT_EQ(c.size(), raw.size());
    EXPECT_TRUE(c.viewpoint.isApprox(seq.pose(7), 1e-9));
    const Eigen::Vector3d w = seq.pose(7) * Eigen::Vector3d(raw.x[5], raw.y[5], raw.z[5]);
    EXPECT_NEAR(c.x[5], w.x(), 1e-4);
    EXPECT_NEAR(c.z[5], w.z(), 1e-4);
    EXPECT_EQ(c.intensity[5], raw.intensity[5]);
    // Cleaned with the same config as the rawlog: the same classes but for float rounding
    // (measured: 151 of 629,853 points here; 9 of 4.9 M on KITTI 08).
    const std::string a = root_ + "/ref10_rawlog";
    r = toRawlog(root_ + "/seq", root_ + "/first10.rawlog",
                 [](hif::jobs::KittiToRawlogOptions& o)
                 {
                     o.last = 9;
                     o.overwrite = true;
                 });
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(root_ + "/first10.rawlog", a);
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(dm, dm + "/out", [](Options& o) { o.config = HIF_SHARE_DIR "/config/kitti.ini"; });
    ASSERT_EQ(r.code, 0) << r.output;
    std::size_t points = 0, differ = 0;
    for (int i = 0; i < 10; ++i)
    {
        const std::string f = "/predictions/" + hif::io::frameName(i) + ".label";
        const auto la = hif::io::readLabels(a + f), lb = hif::io::readLabels(dm + "/out" + f);
        ASSERT_EQ(la.size(), lb.size()) << f;
        points += la.size();
        for (std::size_t k = 0; k < la.size(); ++k) differ += la[k] != lb[k];
    }
    EXPECT_LT(differ, points / 1000) << differ << " of " << points << " points differ";
    // A folder that is neither layout is named as such; a bad --format is refused.
    fs::create_directories(root_ + "/neither");
    r = runInProcess("hif-clean", "-i " + root_ + "/neither -o " + root_ + "/neither/out");
    expectError(r, "is a folder with neither velodyne/, pcd/, poses.txt nor keyframes");
    r = runInProcess("hif-clean", "-i " + root_ + "/seq -o " + root_ + "/bad_format --format las");
    expectError(r, "--format");
    EXPECT_FALSE(fs::exists(root_ + "/bad_format"));
}

// A sensor mounted off the robot's origin, turned and tilted, on a robot that moves and turns:
// every kept point must land where it was in the world (robot pose (+) sensor pose), in the
// clouds hif-clean writes.

TEST_F(SyntheticPipeline, RawlogOutHoldsTheKeptPointsForMrptTools)
{
    const std::string d = root_ + "/rawlog_out";
    fs::remove_all(d);
    auto r = clean(root_ + "/seq", d + "/out",
                   [&](Options& o)
                   {
                       o.picture = false;
                       o.rawlog_out = d + "/clean.rawlog";
                   });
    ASSERT_EQ(r.code, 0) << r.output;
    const json first = readJson(d + "/out/summary.json");
    // Refused without --overwrite, like every output.
    r = clean(root_ + "/seq", d + "/out2", [&](Options& o) { o.rawlog_out = d + "/clean.rawlog"; });
    expectError(r, "clean.rawlog' already exists");
    // Read back: the same scans (numbered as before), and only the points that were kept.
    r = clean(d + "/clean.rawlog", d + "/again", noPicture);
    ASSERT_EQ(r.code, 0) << r.output;
    const json again = readJson(d + "/again/summary.json");
    EXPECT_EQ(again["scans"], first["scans"]);
    EXPECT_EQ(again["points_in"], first["points_kept"]);
    EXPECT_EQ(again["skipped_objects"], 0);
    EXPECT_TRUE(fs::exists(d + "/again/predictions/000019.label"));
    // Compressed on request (gzip, as kitti2rawlog -z), and read back the same.
    r = clean(root_ + "/seq", d + "/gz",
              [&](Options& o)
              {
                  o.picture = false;
                  o.rawlog_out = d + "/clean.rawlog.gz";
                  o.rawlog_compress = 6;
              });
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string gz = hif::test::bytesOf(d + "/clean.rawlog.gz");
    ASSERT_GT(gz.size(), 2u);
    EXPECT_EQ(uint8_t(gz[0]), 0x1f);
    EXPECT_EQ(uint8_t(gz[1]), 0x8b);
    EXPECT_LT(gz.size(), fs::file_size(d + "/clean.rawlog"));
    r = clean(d + "/clean.rawlog.gz", d + "/again_gz", noPicture);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readJson(d + "/again_gz/summary.json")["points_in"], first["points_kept"]);
    expectError(clean(root_ + "/seq", d + "/gz2", [](Options& o) { o.rawlog_compress = 6; }),
                "--rawlog-compress goes with --rawlog-out");
    expectError(clean(root_ + "/seq", d + "/gz3",
                      [&](Options& o)
                      {
                          o.rawlog_out = d + "/x.rawlog";
                          o.rawlog_compress = 12;
                      }),
                "--rawlog-compress 12 is not in [0, 9]");
    if (std::system("command -v rawlog-edit > /dev/null 2>&1") == 0)
    {
        const std::string cmd =
            "rawlog-edit --info -i " + d + "/clean.rawlog > " + d + "/info.txt 2>&1";
        ASSERT_EQ(std::system(cmd.c_str()), 0);
        const std::string info = hif::test::bytesOf(d + "/info.txt");
        EXPECT_NE(info.find("Overall number of objects         : 60"), std::string::npos) << info;
    }
}

// kitti2rawlog --odometry: the trajectory also as CObservationOdometry (x, y, heading of each
// scan's ground-truth pose), what RawLogViewer's map from odometry reads;
// --start-time: real time stamps. hif-clean passes the odometry by: the same result.
TEST_F(SyntheticPipeline, Kitti2rawlogWritesTheTrajectoryAsOdometryAndRealTimes)
{
    const std::string d = root_ + "/odometry";
    fs::remove_all(d);
    fs::create_directories(d);
    const double start = 1317386400.0;  // 2011-09-30 12:40:00 UTC
    auto r = runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + d +
                                              "/odo.rawlog -q --odometry "
                                              "--start-time 1317386400");
    ASSERT_EQ(r.code, 0) << r.output;
    const hif::io::KittiSequence seq(root_ + "/seq");
    std::vector<mrpt::obs::CObservationOdometry::Ptr> odometry;
    std::vector<mrpt::obs::CObservationRobotPose::Ptr> poses;
    std::vector<mrpt::Clock::time_point> scan_times;
    for (const auto& obj : rawlogObjects(d + "/odo.rawlog"))
    {
        if (auto o = std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(obj))
        {
            EXPECT_EQ(poses.size(), odometry.size()) << "the odometry comes before its pose";
            odometry.push_back(o);
        }
        if (auto p = std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(obj))
            poses.push_back(p);
        if (auto s = std::dynamic_pointer_cast<mrpt::obs::CObservationPointCloud>(obj))
            scan_times.push_back(s->timestamp);
    }
    ASSERT_EQ(odometry.size(), seq.size());
    ASSERT_EQ(poses.size(), seq.size());
    ASSERT_EQ(scan_times.size(), seq.size());
    double travelled = 0;
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const mrpt::poses::CPose3D& p = poses[i]->pose.mean;
        EXPECT_NEAR(odometry[i]->odometry.x(), p.x(), 1e-9);
        EXPECT_NEAR(odometry[i]->odometry.y(), p.y(), 1e-9);
        EXPECT_NEAR(odometry[i]->odometry.phi(), p.yaw(), 1e-9);
        EXPECT_EQ(odometry[i]->timestamp, scan_times[i]);
        EXPECT_NEAR(mrpt::Clock::toDouble(scan_times[i]), start + seq.time(i), 1e-6);
        if (i > 0) travelled += (odometry[i]->odometry - odometry[i - 1]->odometry).norm();
    }
    EXPECT_GT(travelled, 1.0);  // the sensor moves in the synthetic clip
    // hif-clean: the same points kept as from the rawlog without odometry, no object skipped.
    r = clean(d + "/odo.rawlog", d + "/clean", noPicture);
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(root_ + "/scans.rawlog", d + "/plain", noPicture);
    ASSERT_EQ(r.code, 0) << r.output;
    const json with = readJson(d + "/clean/summary.json");
    EXPECT_EQ(with["points_kept"], readJson(d + "/plain/summary.json")["points_kept"]);
    EXPECT_EQ(with["skipped_objects"], 0);
    expectError(runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + d +
                                                 "/x -q --dynamicmap "
                                                 "--odometry"),
                "--odometry and --start-time apply to rawlogs");
    expectError(runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + d +
                                                 "/y.rawlog -q "
                                                 "--start-time -5"),
                "--start-time");
}

// Rawlogs as other MRPT tools write them: sensory frames (actions, then a frame with the pose
// and a 3D range scan), observations with 2D laser scans, and Velodyne scans with their points.
// hif-clean cleans each, and its --rawlog-out keeps each scan's kind: the 3D and Velodyne scans
// keep their static points, the 2D scan marks the ranges of its dynamic points invalid.
