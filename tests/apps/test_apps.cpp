// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_apps.cpp
 * @brief  The apps' command lines: the programs' --help and a bad flag, and hif-eval's on a
 *         hand-counted example (its printed tables and JSON).
 */
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "app_checks.h"
#include "app_runner.h"
#include "hif/io/Labels.h"
#include "job_runner.h"

namespace fs = std::filesystem;
using nlohmann::json;

using hif::test::clean;
using hif::test::expectError;
using hif::test::readJson;
using hif::test::runApp;
using hif::test::runInProcess;
using hif::test::WorkDir;
using hif::test::workDir;

namespace
{
/** A KITTI .bin scan of points on the x axis at `ranges` (intensity 0). */
void writeRangesOnTheXAxis(const std::string& file, const std::vector<float>& ranges)
{
    std::vector<float> p;
    for (float range : ranges) p.insert(p.end(), {range, 0.0f, 0.0f, 0.0f});
    std::ofstream(file, std::ios::binary)
        .write(reinterpret_cast<const char*>(p.data()), std::streamsize(p.size() * 4));
}
}  // namespace

// The programs themselves, as a user runs them: their exit codes and TCLAP's messages. Most
// tests run their command lines in process (runInProcess()): the same words, parsed by the same
// command line, give what the program gives, to the byte.
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
        for (const auto& [args, program] : {std::pair{"--help", help}, {"--no-such-flag", bad}})
        {
            const auto in_process = runInProcess(app, args);
            EXPECT_EQ(in_process.code, program.code) << args;
            EXPECT_EQ(in_process.output, program.output) << args;
        }
    }
}

// A job's refusal in process is the program's too: its error line (a quoted value kept whole)
// and its exit code.
TEST(Apps, AJobsRefusalInProcessIsTheProgramsToo)
{
    const WorkDir work = workDir("in_process_" + std::to_string(getpid()));
    const std::string& d = work.path();
    const std::string args = "-i " + d + " -o " + d + "/out --extrinsic '1 2  3' -q";
    const auto program = runApp("hif-clean", args);
    const auto in_process = runInProcess("hif-clean", args);
    expectError(program, "'1 2  3'");
    EXPECT_EQ(in_process.code, program.code);
    EXPECT_EQ(in_process.output, program.output);
}

// --objects: each moving object (class and SemanticKITTI instance id) scored apart, with the
// scans it is in and, with --scans, its mean range.
TEST(HifEval, ScoresEachMovingObjectApart)
{
    const WorkDir work = workDir("eval_objects");
    const std::string& d = work.path();
    for (const char* sub : {"/labels", "/pred", "/velodyne"}) fs::create_directories(d + sub);
    auto label = [](uint32_t cls, uint32_t id) { return cls | (id << 16); };
    // Scan 0: car 1 (2 points, 1 removed), person 1 (1 point, removed), road.
    // Scan 1: car 1 (1 point, removed), car 2 (2 points, none removed).
    hif::io::writeLabels(d + "/labels/000000.label",
                         {label(252, 1), label(252, 1), label(254, 1), 40});
    hif::io::writeLabels(d + "/pred/000000.label", {251, 9, 251, 9});
    hif::io::writeLabels(d + "/labels/000001.label", {label(252, 1), label(252, 2), label(252, 2)});
    hif::io::writeLabels(d + "/pred/000001.label", {251, 9, 9});
    auto writeBin = [&](const std::string& name, const std::vector<float>& ranges)
    { writeRangesOnTheXAxis(d + "/velodyne/" + name, ranges); };
    writeBin("000000.bin", {10, 20, 30, 5});
    writeBin("000001.bin", {30, 40, 44});
    const std::string args =
        "--labels " + d + "/labels --predictions " + d + "/pred --objects --json " + d;
    const auto r = runInProcess("hif-eval", args + "/objects.json --scans " + d + "/velodyne");
    ASSERT_EQ(r.code, 0) << r.output;
    const json rows = readJson(d + "/objects.json")["per_object"];
    ASSERT_EQ(rows.size(), 3u) << rows;
    // By class, then instance: car 1, car 2, person 1.
    EXPECT_EQ(rows[0]["class"], "moving-car");
    EXPECT_EQ(rows[0]["instance"], 1);
    EXPECT_EQ(rows[0]["scans"], 2);
    EXPECT_EQ(rows[0]["dynamic_total"], 3);
    EXPECT_EQ(rows[0]["dynamic_removed"], 2);
    EXPECT_NEAR(rows[0]["DA"].get<double>(), 200.0 / 3.0, 1e-9);
    EXPECT_DOUBLE_EQ(rows[0]["mean_range"].get<double>(), 20.0);
    EXPECT_EQ(rows[1]["instance"], 2);
    EXPECT_EQ(rows[1]["scans"], 1);
    EXPECT_DOUBLE_EQ(rows[1]["DA"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(rows[1]["mean_range"].get<double>(), 42.0);
    EXPECT_EQ(rows[2]["class"], "moving-person");
    EXPECT_DOUBLE_EQ(rows[2]["DA"].get<double>(), 100.0);
    EXPECT_NE(
        r.output.find("moving-car 1                   2         3         2   66.67      20.0"),
        std::string::npos)
        << r.output;
    // Without --scans the range is unknown: "-", null in the JSON.
    const auto n = runInProcess("hif-eval", args + "/no_scans.json");
    ASSERT_EQ(n.code, 0) << n.output;
    EXPECT_TRUE(readJson(d + "/no_scans.json")["per_object"][0]["mean_range"].is_null());
    EXPECT_NE(n.output.find("66.67         -"), std::string::npos) << n.output;
    // Without --objects, no such table.
    const auto plain =
        runInProcess("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred");
    ASSERT_EQ(plain.code, 0) << plain.output;
    EXPECT_EQ(plain.output.find("moving object"), std::string::npos) << plain.output;
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
    const auto r = runInProcess("hif-eval", "--labels " + d + "/labels --predictions " + d +
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
    // Per static class: road 1 of 2 kept, the parked car and the building kept.
    const json& st = j["per_static_class"];
    ASSERT_EQ(st.size(), 3u) << st;
    EXPECT_EQ(st["road"]["static_total"], 2);
    EXPECT_EQ(st["road"]["static_kept"], 1);
    EXPECT_DOUBLE_EQ(st["road"]["SA"].get<double>(), 50.0);
    EXPECT_EQ(st["car"]["static_kept"], 1);
    EXPECT_EQ(st["building"]["static_total"], 1);
    EXPECT_NE(r.output.find("road                           2         1   50.00"),
              std::string::npos)
        << r.output;

    // Per moving class, and, with the scans, per range band (points on the x axis at these
    // ranges) and with every point within 3 m counted dynamic, as the DynamicMap benchmark
    // does.
    fs::create_directories(d + "/velodyne");
    auto writeBin = [&](const std::string& name, const std::vector<float>& ranges)
    { writeRangesOnTheXAxis(d + "/velodyne/" + name, ranges); };
    writeBin("000000.bin", {5, 15, 25, 12, 2, 40});
    writeBin("000001.bin", {1, 60, 8});
    const auto rb =
        runInProcess("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred --scans " +
                                     d + "/velodyne --json " + d + "/scores2.json");
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
    // Per moving class in each band: the bicyclist 0-10 m (removed), the car 10-20 m (removed),
    // the person 35-50 m (kept); no class where a band has none of it.
    EXPECT_EQ(bands[0]["per_moving_class"].size(), 1u);
    EXPECT_EQ(bands[0]["per_moving_class"]["moving-bicyclist"]["dynamic_removed"], 1);
    EXPECT_EQ(bands[1]["per_moving_class"].size(), 1u);
    EXPECT_DOUBLE_EQ(bands[1]["per_moving_class"]["moving-car"]["DA"].get<double>(), 100.0);
    EXPECT_TRUE(bands[2]["per_moving_class"].empty());
    EXPECT_EQ(bands[3]["per_moving_class"]["moving-person"]["dynamic_total"], 1);
    EXPECT_DOUBLE_EQ(bands[3]["per_moving_class"]["moving-person"]["DA"].get<double>(), 0.0);
    // Printed as a column per moving class present (252, 253, 254 in that order), "-" where a
    // band has none of it.
    EXPECT_NE(rb.output.find("DA       car bicyclist    person"), std::string::npos) << rb.output;
    EXPECT_NE(rb.output.find("0.00         -         -      0.00"), std::string::npos) << rb.output;
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
        runInProcess("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred --scans " +
                                     d + "/velodyne --json " + d + "/scores3.json --overwrite");
    expectError(short_scan, "000001.bin' does not hold the 3 points of its label file");
    fs::resize_file(d + "/velodyne/000001.bin", 20);
    expectError(
        runInProcess("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred --scans " +
                                     d + "/velodyne --json " + d + "/scores3.json --overwrite"),
        "000001.bin' is 20 bytes, not a multiple of 16");

    // A prediction whose size differs from its labels is an error naming both files.
    hif::io::writeLabels(d + "/pred/000001.label", {251, 9});
    const auto bad =
        runInProcess("hif-eval", "--labels " + d + "/labels --predictions " + d + "/pred");
    expectError(bad, "000001.label' has 2 points");
}
