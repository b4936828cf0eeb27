// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_apps.cpp
 * @brief  The apps end to end, run as a user runs them: hif-eval on a hand-counted example,
 *         the synthetic pipeline (generate, convert, clean offline and online, evaluate) with
 *         asserted scores and outputs, the DynamicMap folder layout, real KITTI 03 and 04 with
 *         asserted floors, and clear errors on bad input.
 */
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/serialization/CArchive.h>

#include <opencv2/imgcodecs.hpp>

#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "app_runner.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/apps/TopView.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "hif/io/Rings.h"
#include "job_runner.h"
#include "kitti_fixture.h"

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
using hif::test::runApp;
using hif::test::WorkDir;
using hif::test::workDir;

namespace
{
/** Every object of a rawlog (gzip-compressed or not), in order. */
std::vector<mrpt::serialization::CSerializable::Ptr> rawlogObjects(const std::string& file)
{
    mrpt::io::CFileGZInputStream in(file);
    auto arch = mrpt::serialization::archiveFrom(in);
    std::vector<mrpt::serialization::CSerializable::Ptr> objects;
    for (;;)
    {
        try
        {
            objects.push_back(arch.ReadObject());
        }
        catch (const mrpt::serialization::CExceptionEOF&)
        {
            return objects;
        }
    }
}

/** How many points of each colour (red, green, blue packed) a coloured PLY holds. */
std::map<uint32_t, std::size_t> coloursOf(const std::string& file)
{
    std::ifstream f(file, std::ios::binary);
    EXPECT_TRUE(f.good()) << file;
    for (std::string line; std::getline(f, line) && line != "end_header";)
    {
    }
    std::map<uint32_t, std::size_t> n;
    for (char rec[15]; f.read(rec, 15);)
        ++n[(uint32_t(uint8_t(rec[12])) << 16) | (uint32_t(uint8_t(rec[13])) << 8) |
            uint8_t(rec[14])];
    return n;
}

/** classes.ply's points (x y z intensity, float32; red green blue class, uchar) counted by
 *  (colour, class), and the sum of their intensities. */
std::map<std::pair<uint32_t, int>, std::size_t> classesOf(const std::string& file,
                                                          double& intensity_sum)
{
    std::ifstream f(file, std::ios::binary);
    EXPECT_TRUE(f.good()) << file;
    std::string header;
    for (std::string line; std::getline(f, line) && line != "end_header";) header += line + "\n";
    EXPECT_NE(header.find("property float intensity\nproperty uchar red\nproperty uchar green\n"
                          "property uchar blue\nproperty uchar class\n"),
              std::string::npos)
        << header;
    std::map<std::pair<uint32_t, int>, std::size_t> n;
    intensity_sum = 0;
    for (char rec[20]; f.read(rec, 20);)
    {
        float i = 0;
        std::memcpy(&i, rec + 12, 4);
        intensity_sum += i;
        ++n[{(uint32_t(uint8_t(rec[16])) << 16) | (uint32_t(uint8_t(rec[17])) << 8) |
                 uint8_t(rec[18]),
             int(rec[19])}];
    }
    return n;
}

uint32_t packed(hif::apps::TopView::Outcome o)
{
    const uint8_t* c = hif::apps::TopView::kRgb[o];
    return (uint32_t(c[0]) << 16) | (uint32_t(c[1]) << 8) | c[2];
}

/** The vertex count a PLY header states. */
std::size_t plyVertexCount(const std::string& file)
{
    std::ifstream ply(file);
    EXPECT_TRUE(ply.good()) << file;
    for (std::string line; std::getline(ply, line) && line != "end_header";)
        if (line.rfind("element vertex ", 0) == 0) return std::stoul(line.substr(15));
    ADD_FAILURE() << file << " has no element vertex line";
    return 0;
}
}  // namespace

TEST(Apps, HelpExitsZeroAndABadFlagStopsTheApp)
{
    for (const std::string app :
         {"kitti2rawlog", "hif-clean", "hif-eval", "hif-synthetic-kitti", "hif-icp-slam"})
    {
        SCOPED_TRACE(app);
        const auto help = runApp(app, "--help");
        EXPECT_EQ(help.code, 0) << help.output;
        EXPECT_NE(help.output.find("USAGE:"), std::string::npos) << help.output;
        EXPECT_EQ(help.output.find("error:"), std::string::npos) << "the app ran after --help";
        const auto bad = runApp(app, "--no-such-flag");
        EXPECT_NE(bad.code, 0);
        EXPECT_NE(bad.output.find("PARSE ERROR"), std::string::npos) << bad.output;
        EXPECT_EQ(bad.output.find("error:"), std::string::npos) << "the app ran: " << bad.output;
    }
}

TEST(HifEval, AgreesWithAHandCountedExample)
{
    const WorkDir work = workDir("eval_hand");
    const std::string& d = work.path();
    fs::create_directories(d + "/labels");
    fs::create_directories(d + "/pred");
    // Scan 0: truth  road(40) road car(10) moving-car(252) unlabeled(0) moving-person(254|id 3)
    //         pred   9        251  9       251             251          9
    // Scored: 3 static (kept 2), 2 dynamic (removed 1); the unlabeled point is ignored.
    hif::io::writeLabels(d + "/labels/000000.label", {40, 40, 10, 252, 0, 254u | (3u << 16)});
    hif::io::writeLabels(d + "/pred/000000.label", {9, 251, 9, 251, 251, 9});
    // Scan 1: truth  outlier(1) building(50) moving-bicyclist(253)
    //         pred   251        9            253 (a moving class also counts as removed)
    hif::io::writeLabels(d + "/labels/000001.label", {1, 50, 253});
    hif::io::writeLabels(d + "/pred/000001.label", {251, 9, 253});
    // Totals: static 4, kept 3 -> SA 75; dynamic 3, removed 2 -> DA 66.67;
    // AA = sqrt(75 * 66.67) = 70.71; HA = 2 * 75 * 66.67 / 141.67 = 70.59.
    const auto r = runApp("hif-eval", "--labels " + d + "/labels --predictions " + d +
                                          "/pred --json " + d + "/scores.json");
    ASSERT_EQ(r.code, 0) << r.output;
    const json j = readJson(d + "/scores.json");
    const json& t = j["total"];
    EXPECT_EQ(t["static_total"], 4);
    EXPECT_EQ(t["static_kept"], 3);
    EXPECT_EQ(t["dynamic_total"], 3);
    EXPECT_EQ(t["dynamic_removed"], 2);
    EXPECT_EQ(t["ignored"], 2);
    EXPECT_DOUBLE_EQ(t["SA"].get<double>(), 75.0);
    EXPECT_NEAR(t["DA"].get<double>(), 200.0 / 3.0, 1e-9);
    EXPECT_NEAR(t["AA"].get<double>(), std::sqrt(75.0 * 200.0 / 3.0), 1e-9);
    EXPECT_NEAR(t["HA"].get<double>(), 2 * 75.0 * (200.0 / 3.0) / (75.0 + 200.0 / 3.0), 1e-9);
    ASSERT_EQ(j["per_scan"].size(), 2u);
    EXPECT_DOUBLE_EQ(j["per_scan"][0]["SA"].get<double>(), 200.0 / 3.0);
    EXPECT_DOUBLE_EQ(j["per_scan"][0]["DA"].get<double>(), 50.0);
    EXPECT_DOUBLE_EQ(j["per_scan"][1]["DA"].get<double>(), 100.0);
    EXPECT_NE(r.output.find("SA 75.00  DA 66.67  AA 70.71  HA 70.59"), std::string::npos)
        << r.output;

    // Per moving class, and, with the scans, per range band (points on the x axis at these
    // ranges) and with every point within 3 m counted dynamic, as the DynamicMap benchmark
    // does.
    fs::create_directories(d + "/velodyne");
    auto writeBin = [&](const std::string& name, const std::vector<float>& ranges)
    {
        std::vector<float> p;
        for (float range : ranges) p.insert(p.end(), {range, 0.0f, 0.0f, 0.0f});
        std::ofstream(d + "/velodyne/" + name, std::ios::binary)
            .write(reinterpret_cast<const char*>(p.data()), std::streamsize(p.size() * 4));
    };
    writeBin("000000.bin", {5, 15, 25, 12, 2, 40});
    writeBin("000001.bin", {1, 60, 8});
    const auto rb =
        runApp("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred --scans " + d +
                               "/velodyne --json " + d + "/scores2.json");
    ASSERT_EQ(rb.code, 0) << rb.output;
    const json j2 = readJson(d + "/scores2.json");
    const json& cls = j2["per_moving_class"];
    EXPECT_EQ(cls.size(), 3u);
    EXPECT_DOUBLE_EQ(cls["moving-car"]["DA"].get<double>(), 100.0);
    EXPECT_DOUBLE_EQ(cls["moving-person"]["DA"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(cls["moving-bicyclist"]["DA"].get<double>(), 100.0);
    const json& bands = j2["per_range"];
    ASSERT_EQ(bands.size(), 5u);
    // 0-10: road kept, bicyclist removed; 10-20: road removed, car removed; 20-35: parked car
    // kept; 35-50: person kept; 50+: building kept.
    const int static_kept[5] = {1, 0, 1, 0, 1}, static_total[5] = {1, 1, 1, 0, 1};
    const int dyn_removed[5] = {1, 1, 0, 0, 0}, dyn_total[5] = {1, 1, 0, 1, 0};
    for (int b = 0; b < 5; ++b)
    {
        SCOPED_TRACE(bands[b]["band"].get<std::string>());
        EXPECT_EQ(bands[b]["static_kept"].get<int>(), static_kept[b]);
        EXPECT_EQ(bands[b]["static_total"].get<int>(), static_total[b]);
        EXPECT_EQ(bands[b]["dynamic_removed"].get<int>(), dyn_removed[b]);
        EXPECT_EQ(bands[b]["dynamic_total"].get<int>(), dyn_total[b]);
    }
    EXPECT_EQ(bands[0]["band"], "0-10");
    EXPECT_EQ(bands[4]["band"], "50+");
    // Printed, a band without dynamic points has no DA ("-"), one without static points no SA.
    EXPECT_NE(rb.output.find("20-35                  1         0  100.00       -"),
              std::string::npos)
        << rb.output;
    EXPECT_NE(rb.output.find("35-50                  0         1       -    0.00"),
              std::string::npos)
        << rb.output;
    // The two points within 3 m (unlabelled) were removed: as the benchmark counts, DA 4 / 5.
    EXPECT_EQ(j2["with_ego_points"]["dynamic_total"].get<int>(), 5);
    EXPECT_DOUBLE_EQ(j2["with_ego_points"]["DA"].get<double>(), 80.0);
    EXPECT_DOUBLE_EQ(j2["with_ego_points"]["SA"].get<double>(), 75.0);

    // A scan of another length than its labels, or a truncated one, is named.
    writeBin("000001.bin", {1, 60});
    const auto short_scan =
        runApp("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred --scans " + d +
                               "/velodyne --json " + d + "/scores3.json --overwrite");
    expectError(short_scan, "000001.bin' does not hold the 3 points of its label file");
    fs::resize_file(d + "/velodyne/000001.bin", 20);
    expectError(
        runApp("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred --scans " + d +
                               "/velodyne --json " + d + "/scores3.json --overwrite"),
        "000001.bin' is 20 bytes, not a multiple of 16");

    // A prediction whose size differs from its labels is an error naming both files.
    hif::io::writeLabels(d + "/pred/000001.label", {251, 9});
    const auto bad = runApp("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred");
    expectError(bad, "000001.label' has 2 points");
}

class SyntheticPipeline : public ::testing::Test
{
protected:
    // CTest runs each test in its own process, two at a time: one folder per process.
    static void SetUpTestSuite()
    {
        work_ =
            std::make_unique<WorkDir>(hif::test::kWork + "/synthetic_" + std::to_string(getpid()));
        root_ = work_->path();
        const auto g = synthesize(root_ + "/seq", 20);
        const auto c = g.code == 0 ? toRawlog(root_ + "/seq", root_ + "/scans.rawlog") : g;
        setup_ok_ = g.code == 0 && c.code == 0;
        setup_log_ = g.output + c.output;
    }
    // A failed set-up fails every test (gtest would report them as skipped).
    void SetUp() override { ASSERT_TRUE(setup_ok_) << setup_log_; }
    // The folder goes unless a test failed.
    static void TearDownTestSuite() { work_.reset(); }
    static std::unique_ptr<WorkDir> work_;
    static std::string root_, setup_log_;
    static bool setup_ok_;
};
std::unique_ptr<WorkDir> SyntheticPipeline::work_;
std::string SyntheticPipeline::root_, SyntheticPipeline::setup_log_;
bool SyntheticPipeline::setup_ok_ = false;

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

TEST_F(SyntheticPipeline, RefusesToOverwriteAndNamesBadInput)
{
    // The rawlog exists: kitti2rawlog does not replace it unless told to.
    auto r = runApp("kitti2rawlog", "-i " + root_ + "/seq -o " + root_ + "/scans.rawlog");
    expectError(r, "already exists; pass --overwrite");
    // A missing input is named.
    r = runApp("hif-clean", "-i " + root_ + "/nothing.rawlog -o " + root_ + "/x");
    expectError(r, "nothing.rawlog' does not exist");
    // A truncated rawlog is an error naming the file, not a silent partial map.
    {
        std::ifstream in(root_ + "/scans.rawlog", std::ios::binary);
        std::vector<char> bytes((std::istreambuf_iterator<char>(in)), {});
        std::ofstream out(root_ + "/truncated.rawlog", std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2 + 7));
    }
    r = runApp("hif-clean", "-i " + root_ + "/truncated.rawlog -o " + root_ + "/trunc -q");
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
    r = runApp("kitti2rawlog", "-i " + bad + " -o " + bad + "/x.rawlog");
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
    r = runApp("hif-clean",
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
    const auto r = runApp("hif-clean", "-i " + dm + " -o " + dm + "/out -q");
    ASSERT_EQ(r.code, 0) << r.output;
    ASSERT_TRUE(fs::exists(dm + "/hif_output.pcd")) << r.output;
    const json sum = readJson(dm + "/out/summary.json");
    EXPECT_EQ(sum["scans"], 20);
    EXPECT_EQ(hif::io::readPcd(dm + "/hif_output.pcd").x.size(),
              sum["points_kept"].get<std::size_t>());
    const auto e = runApp("hif-eval", "--labels " + root_ + "/seq/labels --predictions " + dm +
                                          "/out/predictions --json " + dm + "/scores.json");
    ASSERT_EQ(e.code, 0) << e.output;
    const json s = readJson(dm + "/scores.json")["total"];
    EXPECT_GE(s["SA"].get<double>(), 99.0);
    EXPECT_GE(s["DA"].get<double>(), 95.0);
    // A second run does not replace the benchmark output without --overwrite.
    const auto again = runApp("hif-clean", "-i " + dm + " -o " + dm + "/out2 -q");
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
    r = runApp("hif-clean", "-i " + root_ + "/neither -o " + root_ + "/neither/out");
    expectError(r, "is a folder with neither velodyne/, pcd/ nor poses.txt");
    r = runApp("hif-clean", "-i " + root_ + "/seq -o " + root_ + "/bad_format --format las");
    expectError(r, "--format");
    EXPECT_FALSE(fs::exists(root_ + "/bad_format"));
}

// A sensor mounted off the robot's origin, turned and tilted, on a robot that moves and turns:
// every kept point must land where it was in the world (robot pose (+) sensor pose), in the
// clouds hif-clean writes.
TEST(HifClean, PlacesPointsAtTheRobotPoseComposedWithTheSensorPose)
{
    const WorkDir work = workDir("sensor_pose");
    const std::string& d = work.path();
    const mrpt::poses::CPose3D sensor(0.8, -0.3, 1.7, mrpt::DEG2RAD(30.0), mrpt::DEG2RAD(3.0),
                                      mrpt::DEG2RAD(-2.0));
    std::size_t points = 0;
    {
        mrpt::io::CFileOutputStream f(d + "/scans.rawlog");
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 5; ++s)
        {
            const mrpt::poses::CPose3D robot(0.5 * s, 0.2 * s, 0.0, mrpt::DEG2RAD(5.0 * s), 0, 0);
            auto pose = mrpt::obs::CObservationRobotPose::Create();
            pose->pose.mean = robot;
            arch << *pose;
            // A wall at x = 10 and the ground z = 0 in the world, seen from the sensor.
            const mrpt::poses::CPose3D world_to_sensor = -(robot + sensor);
            auto cloud = mrpt::maps::CSimplePointsMap::Create();
            for (double a = -4.0; a <= 4.0; a += 0.25)
                for (double b = 0.0; b <= 2.5; b += 0.25)
                {
                    cloud->insertPoint(world_to_sensor.composePoint({10.0, a, b}));
                    cloud->insertPoint(world_to_sensor.composePoint({2.0 + b * 2.0, a, 0.0}));
                }
            points = cloud->size();
            auto obs = mrpt::obs::CObservationPointCloud::Create();
            obs->pointcloud = cloud;
            obs->sensorPose = sensor;
            arch << *obs;
        }
    }
    const auto r =
        runApp("hif-clean", "-i " + d + "/scans.rawlog -o " + d + "/out -q --format pcd");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_FALSE(fs::exists(d + "/out/static_map.ply"));
    const hif::io::PcdCloud kept = hif::io::readPcd(d + "/out/static_map.pcd");
    ASSERT_GT(kept.size(), points) << "most points of a static scene are kept";
    for (std::size_t i = 0; i < kept.size(); ++i)
        ASSERT_TRUE(std::abs(kept.x[i] - 10.0f) < 1e-3f || std::abs(kept.z[i]) < 1e-3f)
            << "point " << i << " at (" << kept.x[i] << ", " << kept.y[i] << ", " << kept.z[i]
            << ") is on neither the wall nor the ground";
}

namespace
{
/** A synthetic clip of `scene` (10 scans), converted to a rawlog in `seq`. */
void makeClip(const std::string& seq, const std::string& scene, double speed, long long seed)
{
    auto r = synthesize(seq, 10,
                        [&](hif::jobs::SyntheticKittiOptions& o)
                        {
                            o.scene = scene;
                            o.ego_speed = speed;
                            o.seed = seed;
                        });
    ASSERT_EQ(r.code, 0) << r.output;
    r = toRawlog(seq, seq + "/scans.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
}

/** The cleaning (in process) of `input` into `out` with what `set` changes, scored by hif-eval
 *  against `labels`: the scores' JSON. */
json cleanAndScoreInput(const std::string& input, const std::string& labels, const std::string& out,
                        const std::function<void(Options&)>& set = {})
{
    const auto c = clean(input, out, set);
    EXPECT_EQ(c.code, 0) << c.output;
    const auto e = evaluate(labels, out + "/predictions",
                            [&](hif::jobs::EvaluateOptions& o) { o.json = out + "/scores.json"; });
    EXPECT_EQ(e.code, 0) << e.output;
    return readJson(out + "/scores.json");
}

/** cleanAndScoreInput() on the rawlog of the clip in `seq` (into seq/name). */
json cleanAndScore(const std::string& seq, const std::string& name,
                   const std::function<void(Options&)>& set = {})
{
    return cleanAndScoreInput(seq + "/scans.rawlog", seq + "/labels", seq + "/" + name, set);
}

/** What the options become for the paper's method, online, or without a picture. */
void paperConfig(Options& o) { o.config = HIF_SHARE_DIR "/config/kitti-paper.ini"; }
void onlineMode(Options& o) { o.online = true; }
void noPicture(Options& o) { o.picture = false; }
}  // namespace

// People walking in short clips, the sensor standing or moving at 3 m/s: the map alone keeps
// most of them (kitti-paper.ini); the shipped configs remove them, offline and online, and keep
// the static scene.
TEST(Walkers, SyntheticWalkersAreRemovedOfflineAndOnline)
{
    if (HIF_SANITIZED)
        GTEST_SKIP() << "removal floors: the plain suite (scripts/test.sh) checks them; under the "
                        "sanitizers the same pipeline runs in SyntheticPipeline.* (this test "
                        "takes 45 s there)";
    const WorkDir work = workDir("walkers_" + std::to_string(getpid()));
    for (const auto& [speed, seed] : {std::pair{0, 3}, std::pair{3, 2}})
    {
        const std::string seq = work.path() + "/v" + std::to_string(speed);
        SCOPED_TRACE(seq);
        ASSERT_NO_FATAL_FAILURE(makeClip(seq, "walkers", speed, seed));
        const json paper = cleanAndScore(seq, "paper", paperConfig);
        const json offline = cleanAndScore(seq, "offline");
        const json online = cleanAndScore(seq, "online", onlineMode);
        const double paper_da = paper["per_moving_class"]["moving-person"]["DA"].get<double>();
        // Measured: person DA 97 and 92 offline, 86 and 77 online (the paper: under 40; testing
        // the first point of a run alone gave 96 and 86 offline, 75 and 70 online).
        for (const json* s : {&offline, &online})
        {
            EXPECT_GE((*s)["total"]["SA"].get<double>(), 99.5);
            EXPECT_GT((*s)["per_moving_class"]["moving-person"]["dynamic_total"].get<int>(), 1000);
        }
        EXPECT_GE(offline["per_moving_class"]["moving-person"]["DA"].get<double>(), 85.0);
        EXPECT_GE(online["per_moving_class"]["moving-person"]["DA"].get<double>(), 72.0);
        EXPECT_LT(paper_da, 50.0);
    }
}

// People walking towards the sensor or away from it, within 15 degrees of its line of sight
// (issue 23's hard case): the beams through where a person was land on the person again, a
// little nearer or farther, so fewer are removed than of the people crossing the view. The floors
// guard today's figures (person DA 94.2 and 72.9 offline, 65.8 and 58.3 online; before the
// free-space test followed a surface drifting along the beams, 80.5 offline on the first clip;
// the paper's method 30.6 and 19.0); the targets are 85 offline and 75 online.
TEST(Walkers, WalkersAlongTheLineOfSightAreRemovedInPart)
{
    if (HIF_SANITIZED)
        GTEST_SKIP() << "removal floors: the plain suite (scripts/test.sh) checks them";
    const WorkDir work = workDir("radial_" + std::to_string(getpid()));
    for (const auto& [speed, seed] : {std::pair{0, 1}, std::pair{3, 2}})
    {
        const std::string seq = work.path() + "/v" + std::to_string(speed);
        SCOPED_TRACE(seq);
        ASSERT_NO_FATAL_FAILURE(makeClip(seq, "radial", speed, seed));
        // The scene is what it says: each person seen in the first and the last scan moved along
        // the line of sight from the sensor (within 15 degrees, and some more for the centroid of
        // what is seen of a person).
        const hif::io::KittiSequence kitti(seq);
        std::map<uint32_t, std::vector<Eigen::Vector3d>> centroids;  // instance -> first, last
        for (const std::size_t i : {std::size_t{0}, kitti.size() - 1})
        {
            const hif::io::Cloud c = kitti.readScan(i);
            const std::vector<uint32_t> labels = hif::io::readLabels(kitti.labelFile(i));
            std::map<uint32_t, std::pair<Eigen::Vector3d, int>> sum;
            for (std::size_t k = 0; k < c.size(); ++k)
                if ((labels[k] & 0xFFFF) == 254)
                {
                    auto& [p, n] = sum[labels[k] >> 16];
                    if (n == 0) p.setZero();
                    p += kitti.pose(i) * Eigen::Vector3d(c.x[k], c.y[k], c.z[k]);
                    ++n;
                }
            for (const auto& [id, pn] : sum)
                if (pn.second >= 30) centroids[id].push_back(pn.first / pn.second);
        }
        const Eigen::Vector3d sensor_mid =
            0.5 * (kitti.pose(0).translation() + kitti.pose(kitti.size() - 1).translation());
        std::size_t people = 0;
        for (const auto& [id, c] : centroids)
        {
            if (c.size() != 2) continue;
            Eigen::Vector3d moved = c[1] - c[0], los = 0.5 * (c[0] + c[1]) - sensor_mid;
            moved.z() = los.z() = 0;
            ASSERT_GT(moved.norm(), 0.4) << "person " << id;
            const double cosine = std::abs(moved.dot(los)) / (moved.norm() * los.norm());
            EXPECT_GT(cosine, std::cos(25.0 * M_PI / 180.0)) << "person " << id;
            ++people;
        }
        EXPECT_GE(people, 3u);
        const json paper = cleanAndScore(seq, "paper", paperConfig);
        const json offline = cleanAndScore(seq, "offline");
        const json online = cleanAndScore(seq, "online", onlineMode);
        for (const json* s : {&offline, &online})
        {
            EXPECT_GE((*s)["total"]["SA"].get<double>(), 99.5);
            EXPECT_GT((*s)["per_moving_class"]["moving-person"]["dynamic_total"].get<int>(), 3000);
        }
        EXPECT_GE(offline["per_moving_class"]["moving-person"]["DA"].get<double>(), 70.0);
        EXPECT_GE(online["per_moving_class"]["moving-person"]["DA"].get<double>(), 55.0);
        EXPECT_LT(paper["per_moving_class"]["moving-person"]["DA"].get<double>(), 40.0);
    }
}

// Cyclists at 3 to 6 m/s, the sensor moving at 3 m/s: they move fast enough for the map to
// remove much of them, the rest (the bicycle's low parts, near the ground) is the free-space
// test's.
TEST(Cyclists, SyntheticCyclistsAreRemovedOfflineAndOnline)
{
    if (HIF_SANITIZED)
        GTEST_SKIP() << "removal floors: the plain suite (scripts/test.sh) checks them; under the "
                        "sanitizers the same pipeline runs in SyntheticPipeline.* (this test "
                        "takes 45 s there)";
    const WorkDir work = workDir("cyclists_" + std::to_string(getpid()));
    const std::string seq = work.path() + "/v3";
    ASSERT_NO_FATAL_FAILURE(makeClip(seq, "cyclists", 3, 2));
    const json paper = cleanAndScore(seq, "paper", paperConfig);
    const json offline = cleanAndScore(seq, "offline");
    const json online = cleanAndScore(seq, "online", onlineMode);
    auto da = [](const json& s)
    { return s["per_moving_class"]["moving-bicyclist"]["DA"].get<double>(); };
    // Measured: DA 90.5 offline, 80.0 online; the paper 71.2.
    for (const json* s : {&offline, &online})
    {
        EXPECT_GE((*s)["total"]["SA"].get<double>(), 99.5);
        EXPECT_GT((*s)["per_moving_class"]["moving-bicyclist"]["dynamic_total"].get<int>(), 1000);
    }
    EXPECT_GE(da(offline), 85.0);
    EXPECT_GE(da(online), 72.0);
    EXPECT_LT(da(paper), da(offline) - 10.0);
}

class RealKitti : public ::testing::TestWithParam<std::tuple<std::string, double, double>>
{
};

TEST_P(RealKitti, OfflineCleaningMeetsTheFloors)
{
    const auto& [seq, sa_floor, aa_floor] = GetParam();
    const std::string dir = hif::test::kittiRoot() + "/sequences/" + seq;
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const WorkDir work = workDir("kitti" + seq);
    const std::string& w = work.path();
    auto r = runApp("kitti2rawlog", "-i " + dir + " -o " + w + "/scans.rawlog --external");
    ASSERT_EQ(r.code, 0) << r.output;
    const json scores = cleanAndScoreInput(w + "/scans.rawlog", dir + "/labels", w + "/out");
    const json& s = scores["total"];
    EXPECT_GE(s["SA"].get<double>(), sa_floor) << s;
    EXPECT_GE(s["AA"].get<double>(), aa_floor) << s;
    // 04's walking person, 35-43 m away: mostly removed (measured 92 %; 69 % testing points
    // within 40 m only, 5 % without the free-space test).
    if (seq == "04")
    {
        EXPECT_GE(scores["per_moving_class"]["moving-person"]["DA"].get<double>(), 85.0);
    }
}

// The targets as floors (04: AA >= 95; 03: SA >= 98), and SA floors a little under
// what the shipped kitti.ini measures (01: SA 99.13, AA 95.67; 03: SA 98.77; 04: SA 98.85, AA
// 96.51). The results are deterministic, so a failure is a regression, not noise.
INSTANTIATE_TEST_SUITE_P(Sequences, RealKitti,
                         ::testing::Values(std::make_tuple("01", 98.6, 95.0),
                                           std::make_tuple("03", 98.0, 98.0),
                                           std::make_tuple("04", 98.3, 95.0)));

// KITTI 04 with every 2nd and every 4th ring (about an HDL-32E's and a VLP-16's spacing): the
// copies hold their rings and labels, and are cleaned. The floors are a little under today's
// figures (misses where beams passed; 32 rings: SA 98.14, AA 95.15; 16 rings: SA 95.84, AA
// 91.92), as a guard against regressions on the way to issue 20's SA >= 98.
TEST(RealKittiRings, SparserCopiesOf04KeepTheirRingsAndLabelsAndAreCleaned)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const WorkDir work = workDir("kitti04_rings");
    for (const auto& [k, sa_floor, aa_floor] :
         {std::tuple{2, 98.0, 94.8}, std::tuple{4, 95.7, 91.7}})
    {
        SCOPED_TRACE(k);
        const std::string seq = work.path() + "/every" + std::to_string(k);
        const std::string cmd = std::string(HIF_DECIMATE_RINGS) + " " + dir + " " + seq + " " +
                                std::to_string(k) + " > /dev/null";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
        const hif::io::KittiSequence full(dir), sparse(seq);
        ASSERT_EQ(sparse.size(), full.size());
        for (std::size_t i = 0; i < sparse.size(); ++i)
        {
            const auto rings = hif::io::ringOfEachPoint(sparse.readScan(i));
            EXPECT_EQ(rings.back() + 1, 64u / unsigned(k) + 1) << "scan " << i;
            EXPECT_EQ(hif::io::readLabels(sparse.labelFile(i)).size(), sparse.pointCount(i));
            EXPECT_NEAR(double(sparse.pointCount(i)) / double(full.pointCount(i)), 1.0 / k, 0.05);
        }
        const json s = cleanAndScoreInput(seq, seq + "/labels", seq + "_out", noPicture)["total"];
        EXPECT_GE(s["SA"].get<double>(), sa_floor) << s;
        EXPECT_GE(s["AA"].get<double>(), aa_floor) << s;
    }
}

// --rawlog-out: the scans again without their dynamic points, a rawlog MRPT's own tools and
// hif-clean read back (with the same poses and frame numbers), holding exactly the kept points.
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
    auto r = runApp("kitti2rawlog", "-i " + root_ + "/seq -o " + d +
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
    expectError(runApp("kitti2rawlog", "-i " + root_ + "/seq -o " + d +
                                           "/x -q --dynamicmap "
                                           "--odometry"),
                "--odometry and --start-time apply to rawlogs");
    expectError(runApp("kitti2rawlog", "-i " + root_ + "/seq -o " + d +
                                           "/y.rawlog -q "
                                           "--start-time -5"),
                "--start-time");
}

// Rawlogs as other MRPT tools write them: sensory frames (actions, then a frame with the pose
// and a 3D range scan), observations with 2D laser scans, and Velodyne scans with their points.
// hif-clean cleans each, and its --rawlog-out keeps each scan's kind: the 3D and Velodyne scans
// keep their static points, the 2D scan marks the ranges of its dynamic points invalid.
TEST(HifClean, ReadsSensoryFramesAnd2DAnd3DAndVelodyneScansAndWritesThemBack)
{
    using namespace mrpt::obs;
    const WorkDir work = workDir("mrpt_kinds");
    const std::string& d = work.path();
    // A wall 6 m ahead and the ground, seen from a robot that moves 0.3 m a scan; a box passes
    // in front of the wall in the first scan only.
    const auto pointsOf = [](int s)
    {
        std::vector<mrpt::math::TPoint3D> p;
        for (double a = -3.0; a <= 3.0; a += 0.1)
            for (double z = 0.0; z <= 2.0; z += 0.1) p.push_back({6.0 - 0.3 * s, a, z - 1.0});
        for (double x = 1.0; x <= 5.0; x += 0.1)
            for (double a = -3.0; a <= 3.0; a += 0.1) p.push_back({x, a, -1.0});
        if (s == 0)
            for (double a = -0.5; a <= 0.5; a += 0.05)
                for (double z = 0.0; z <= 1.0; z += 0.05) p.push_back({3.0, a, z - 0.8});
        return p;
    };
    {
        mrpt::io::CFileOutputStream f(d + "/frames3d.rawlog");
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 5; ++s)
        {
            arch << mrpt::obs::CActionCollection();
            mrpt::obs::CSensoryFrame sf;
            auto pose = CObservationRobotPose::Create();
            pose->pose.mean = mrpt::poses::CPose3D(0.3 * s, 0, 0, 0, 0, 0);
            sf.insert(pose);
            auto o3d = CObservation3DRangeScan::Create();
            o3d->hasPoints3D = true;
            const auto pts = pointsOf(s);
            o3d->resizePoints3DVectors(pts.size());
            for (std::size_t i = 0; i < pts.size(); ++i)
            {
                o3d->points3D_x[i] = float(pts[i].x);
                o3d->points3D_y[i] = float(pts[i].y);
                o3d->points3D_z[i] = float(pts[i].z);
            }
            sf.insert(o3d);
            arch << sf;
        }
    }
    // Observations format: per scan its pose, then the scan `make(s)` builds.
    const auto writeRawlog =
        [&d](const std::string& name, const std::function<CObservation::Ptr(int)>& make)
    {
        mrpt::io::CFileOutputStream f(d + "/" + name);
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 5; ++s)
        {
            auto pose = CObservationRobotPose::Create();
            pose->pose.mean = mrpt::poses::CPose3D(0.3 * s, 0, 0, 0, 0, 0);
            arch << *pose << *make(s);
        }
    };
    writeRawlog("scans2d.rawlog",
                [](int s)
                {
                    auto scan = CObservation2DRangeScan::Create();
                    scan->aperture = float(M_PI);
                    scan->resizeScan(181);
                    for (std::size_t i = 0; i < 181; ++i)
                    {
                        // The wall at x = 6 - 0.3 s, and, in the first scan, a box at 3 m
                        // across 20 rays.
                        const double ang = -M_PI / 2 + M_PI * double(i) / 180.0;
                        const double wall = (6.0 - 0.3 * s) / std::max(0.2, std::cos(ang));
                        const bool box = s == 0 && i >= 80 && i < 100;
                        scan->setScanRange(i,
                                           float(box ? 3.0 / std::cos(ang) : std::min(wall, 30.0)));
                        scan->setScanRangeValidity(i, std::cos(ang) > 0.2 || box);
                    }
                    return scan;
                });
    // As the Velodyne driver leaves it after generatePointCloud(): the points (and here no raw
    // packets).
    writeRawlog("velodyne.rawlog",
                [&pointsOf](int s)
                {
                    auto velo = CObservationVelodyneScan::Create();
                    for (const auto& p : pointsOf(s))
                    {
                        velo->point_cloud.x.push_back(float(p.x));
                        velo->point_cloud.y.push_back(float(p.y));
                        velo->point_cloud.z.push_back(float(p.z));
                        velo->point_cloud.intensity.push_back(100);
                    }
                    return velo;
                });
    for (const std::string kind : {"frames3d", "scans2d", "velodyne"})
    {
        SCOPED_TRACE(kind);
        const std::string out = d + "/" + kind;
        auto r = clean(d + "/" + kind + ".rawlog", out,
                       [&](Options& o)
                       {
                           o.picture = false;
                           o.rawlog_out = out + ".clean.rawlog";
                       });
        ASSERT_EQ(r.code, 0) << r.output;
        const json s = readJson(out + "/summary.json");
        EXPECT_EQ(s["scans"], 5);
        EXPECT_GT(s["points_removed"].get<std::size_t>(), 0u) << "the box is removed";
        // The cleaned rawlog: the same kind of scan, only the kept points.
        std::size_t points = 0, scans = 0;
        for (const auto& o : rawlogObjects(out + ".clean.rawlog"))
        {
            if (auto o3d = std::dynamic_pointer_cast<CObservation3DRangeScan>(o))
            {
                ++scans;
                points += o3d->points3D_x.size();
            }
            if (auto velo = std::dynamic_pointer_cast<CObservationVelodyneScan>(o))
            {
                ++scans;
                points += velo->point_cloud.size();
                EXPECT_EQ(velo->point_cloud.intensity.size(), velo->point_cloud.size());
            }
            if (auto o2d = std::dynamic_pointer_cast<CObservation2DRangeScan>(o))
            {
                ++scans;
                for (std::size_t i = 0; i < o2d->getScanSize(); ++i)
                    points += o2d->getScanRangeValidity(i) ? 1 : 0;
            }
        }
        EXPECT_EQ(scans, 5u);
        EXPECT_EQ(points, s["points_kept"].get<std::size_t>());
    }
}

TEST(HifSyntheticKitti, EachSensorScansWithItsOwnBeams)
{
    const WorkDir work = workDir("sensors_" + std::to_string(getpid()));
    struct Case
    {
        std::string sensor;
        int beams;  ///< distinct elevations (0: a rosette)
        double top, bottom;
    };
    for (const Case& c : std::vector<Case>{{"hdl-64e", 64, 2.0, -24.8},
                                           {"hdl-32e", 32, 10.67, -30.67},
                                           {"vlp-16", 16, 15.0, -15.0},
                                           {"os1-128", 128, 22.5, -22.5},
                                           {"mid-70", 0, 0, 0}})
    {
        SCOPED_TRACE(c.sensor);
        const std::string seq = work.path() + "/" + c.sensor;
        const auto r = synthesize(seq, 2,
                                  [&](hif::jobs::SyntheticKittiOptions& o)
                                  {
                                      o.scene = "walkers";
                                      o.sensor = c.sensor;
                                  });
        ASSERT_EQ(r.code, 0) << r.output;
        const hif::io::KittiSequence s(seq);
        std::vector<hif::io::Cloud> scans{s.readScan(0), s.readScan(1)};
        // Range noise moves a return along its beam: its elevation is the beam's. Each return
        // lies on one of the sensor's beams (evenly spaced from top to bottom here).
        std::set<int> hit;  // beams with a return
        std::size_t off_beam = 0;
        double widest = 0;  // angle off the forward axis, degrees
        for (const auto& scan : scans)
            for (std::size_t i = 0; i < scan.size(); ++i)
            {
                const double rxy = std::hypot(scan.x[i], scan.y[i]);
                const double range = std::hypot(rxy, scan.z[i]);
                widest = std::max(widest, std::acos(scan.x[i] / range) * 180.0 / M_PI);
                if (c.beams == 0) continue;
                const double el = std::atan2(scan.z[i], rxy) * 180.0 / M_PI;
                const double step = (c.top - c.bottom) / (c.beams - 1);
                const long b = std::lround((c.top - el) / step);
                if (b < 0 || b >= c.beams || std::abs(c.top - double(b) * step - el) > 0.01)
                    ++off_beam;
                else
                    hit.insert(int(b));
            }
        if (c.beams > 0)
        {
            EXPECT_EQ(off_beam, 0u);
            EXPECT_GE(double(hit.size()), 0.75 * c.beams) << "most beams return something";
            EXPECT_GT(widest, 150.0) << "a spinning sensor sees all around";
        }
        else
        {
            // The rosette: ahead only, within its 70.4-degree cone, and never the same path.
            EXPECT_LE(widest, 35.2 + 0.5);
            std::size_t same = 0;
            const std::size_t n = std::min(scans[0].size(), scans[1].size());
            for (std::size_t i = 0; i < n; ++i)
                same += scans[0].x[i] == scans[1].x[i] && scans[0].y[i] == scans[1].y[i];
            EXPECT_LT(same, n / 100);
            EXPECT_GT(n, 3000u);
        }
    }
}

// Every sensor of hif-synthetic-kitti, in the street (cars, sliding boxes) and walkers scenes,
// cleaned end to end with the shipped defaults (the sensor model estimated from the scans):
// floors a little under today's figures (scripts/sensors.sh, seed 1, 10 scans; doc/sensors.md).
// And a model given in the config: used from the start, and a wrong one warned of.
TEST(Sensors, EachSensorsClipIsCleanedWithTheDefaults)
{
    if (HIF_SANITIZED) GTEST_SKIP() << "removal floors: the plain suite (scripts/test.sh)";
    const WorkDir work = workDir("sensor_clips_" + std::to_string(getpid()));
    struct Floors
    {
        std::string sensor;
        double street_sa, car_da, walkers_sa, person_da;
    };
    for (const Floors& f : std::vector<Floors>{{"hdl-64e", 99.0, 99.3, 99.6, 86.0},
                                               {"hdl-32e", 98.4, 98.3, 99.5, 75.0},
                                               {"vlp-16", 97.0, 95.0, 99.2, 61.0},
                                               {"os1-128", 98.8, 99.3, 99.5, 87.0},
                                               {"mid-70", 73.5, 65.0, 82.0, 80.0}})
        for (const std::string scene : {"street", "walkers"})
        {
            SCOPED_TRACE(f.sensor + " " + scene);
            const std::string seq = work.path() + "/" + f.sensor + "_" + scene;
            auto r = synthesize(seq, 10,
                                [&](hif::jobs::SyntheticKittiOptions& o)
                                {
                                    o.scene = scene;
                                    o.sensor = f.sensor;
                                });
            ASSERT_EQ(r.code, 0) << r.output;
            const json s = cleanAndScoreInput(seq, seq + "/labels", seq + "/out", noPicture);
            const json& total = s["total"];
            if (scene == "street")
            {
                EXPECT_GE(total["SA"].get<double>(), f.street_sa);
                EXPECT_GE(s["per_moving_class"]["moving-car"]["DA"].get<double>(), f.car_da);
            }
            else
            {
                EXPECT_GE(total["SA"].get<double>(), f.walkers_sa);
                EXPECT_GE(s["per_moving_class"]["moving-person"]["DA"].get<double>(), f.person_da);
            }
        }

    // The VLP-16's beams given in the config: the map's model from the start (in summary.json,
    // "given"); an HDL-64E's given instead, the scans contradict it, and hif-clean says so.
    const std::string seq = work.path() + "/vlp-16_street";
    std::stringstream text;
    text << std::ifstream(HIF_SHARE_DIR "/config/kitti.ini").rdbuf();
    std::string vlp16 = "sensor_beams_deg=", hdl64 = "sensor_beams_deg=";
    for (int b = 0; b < 16; ++b) vlp16 += " " + std::to_string(-15 + 2 * b);
    for (int b = 0; b < 64; ++b) hdl64 += " " + std::to_string(-24.8 + 26.8 * b / 63.0);
    const std::string tail = "\nsensor_horizontal_resolution_deg=0.2\n";
    std::ofstream(seq + "/vlp16.ini") << text.str() << vlp16 << tail;
    std::ofstream(seq + "/hdl64.ini") << text.str() << hdl64 << tail;
    auto r = clean(seq, seq + "/given",
                   [&](Options& o)
                   {
                       o.picture = false;
                       o.config = seq + "/vlp16.ini";
                   });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("sensor : 16 beams from -15.00 to 15.00 deg, 2.000 deg apart"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("(given in the config)"), std::string::npos);
    EXPECT_EQ(r.output.find("does not look like"), std::string::npos) << r.output;
    const json g = readJson(seq + "/given/summary.json")["sensor"];
    EXPECT_TRUE(g["given"].get<bool>());
    EXPECT_EQ(g["beams"].get<int>(), 16);
    EXPECT_EQ(g["scans_checked"].get<int>(), 1);  // the first scan
    r = clean(seq, seq + "/wrong",
              [&](Options& o)
              {
                  o.picture = false;
                  o.config = seq + "/hdl64.ini";
              });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: scan 0 does not look like the sensor given in the config "
                            "(is it this LiDAR's?): 64 beams expected, the scan has 16"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(readJson(seq + "/wrong/summary.json")["sensor"]["contradictions"].size(), 1u);
}
