// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_bad_input.cpp
 * @brief  Mistakes a user makes get a clear error and leave nothing half done: wrong .ini
 *         lines, negative numbers, an empty scan file, a run that fails over earlier results,
 *         scans converted from the middle of a sequence; and the apps' output reads well when
 *         redirected.
 */
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "app_runner.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/Labels.h"
#include "job_runner.h"
#include "synthetic_suite.h"

namespace fs = std::filesystem;
using hif::test::bytesOf;
using hif::test::expectError;
using hif::test::readJson;
using hif::test::Result;
using hif::test::runApp;
using hif::test::runInProcess;
using hif::test::WorkDir;
using hif::test::workDir;

namespace
{
/** A short synthetic sequence, converted, in a fresh folder. */
class BadInput : public hif::test::SyntheticSuite<BadInput>
{
public:
    static constexpr const char* kFolder = "bad_input";
    static constexpr long long kScans = 6;
    static constexpr const char* kRawlog = "all.rawlog";
};
}  // namespace

TEST_F(BadInput, IniMistakesNameTheKeySectionAndFile)
{
    const std::string file = root_ + "/bad.ini";
    struct Case
    {
        std::string from, to, message;
    };
    for (const Case& c : std::vector<Case>{
             {"pillar_size=1.0", "pillar_sise=2.0",
              "'" + file +
                  "', [map_CHeightIntervalMap_00_creationOpts]: unknown key 'pillar_sise'; did "
                  "you mean 'pillar_size'?"},
             {"pillar_size=1.0", "pillar_size=abc",
              "[map_CHeightIntervalMap_00_creationOpts]: pillar_size = 'abc' is not a number"},
             {"origin_x=0.0", "origin_x=1.5m", "origin_x = '1.5m' is not a number"},
             {"alpha=0.6", "alpha 0.6",
              "'alpha 0.6' in [map_CHeightIntervalMap_00_insertOpts] is not key = value"},
             {"[map_CHeightIntervalMap_00_insertOpts]", "[map_CHeightIntervalMap_00_insertOpts",
              "section header '[map_CHeightIntervalMap_00_insertOpts' has no closing ']'"},
             {"low_height_preservation=true", "low_height_preservation=maybe",
              "low_height_preservation = 'maybe' is not true or false"},
             {"max_intervals_per_pillar=16", "max_intervals_per_pillar=-3",
              "max_intervals_per_pillar = '-3' is not a whole number >= 0"},
             {"alpha=0.6", "alpha=0.4",
              "[map_CHeightIntervalMap_00_insertOpts]: hif::Params: invalid alpha = 0.4 (must be "
              "in (0.5, 1))"}})
    {
        SCOPED_TRACE(c.to);
        const std::string config = ini(c.from, c.to);
        expectError(hif::test::clean(root_ + "/all.rawlog", root_ + "/x",
                                     [&](hif::jobs::CleanOptions& o) { o.config = config; }),
                    c.message);
    }
}

TEST_F(BadInput, NegativeNumbersAreRejectedNotWrapped)
{
    const std::string in = "-i " + root_ + "/all.rawlog -o " + root_ + "/neg -q ";
    expectError(runInProcess("hif-clean", in + "--threads -3"), "--threads -3 is not in [1, 1024]");
    expectError(runInProcess("hif-clean", in + "--first-frame -2"),
                "--first-frame -2 is not in [0, 999999]");
    expectError(runInProcess("hif-synthetic-kitti", "-o " + root_ + "/neg_seq -n -1"),
                "--scans -1 is not in [1, 999999]");
    expectError(runInProcess("hif-synthetic-kitti", "-o " + root_ + "/neg_seq --seed -1"),
                "--seed -1 is not in [0, 4294967295]");
    expectError(runInProcess("hif-synthetic-kitti", "-o " + root_ + "/neg_seq --ego-speed -1"),
                "--ego-speed -1.000000 is not in [0, 60] m/s");
    expectError(
        runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + root_ + "/neg.rawlog --first -2"),
        "--first -2 is not in [0, 5]");
    EXPECT_FALSE(fs::exists(root_ + "/neg"));
    EXPECT_FALSE(fs::exists(root_ + "/neg_seq")) << "a rejected flag made the output folder";
    EXPECT_FALSE(fs::exists(root_ + "/neg.rawlog"));
}

TEST_F(BadInput, AnEmptyScanFileIsATruncatedOne)
{
    const WorkDir work = workDir("bad_input_empty_" + std::to_string(getpid()));
    const std::string& seq = work.path();
    fs::copy(root_ + "/seq", seq, fs::copy_options::recursive);
    std::ofstream(seq + "/velodyne/000003.bin", std::ios::trunc).close();
    expectError(runInProcess("kitti2rawlog", "-i " + seq + " -o " + seq + "/x.rawlog"),
                "velodyne/000003.bin' is empty (0 bytes): truncated?");
    EXPECT_FALSE(fs::exists(seq + "/x.rawlog"));
}

TEST_F(BadInput, AFailedRunOverEarlierResultsLeavesThemWhole)
{
    const std::string out = root_ + "/keep";
    auto r = runInProcess("hif-clean", "-i " + root_ + "/all.rawlog -o " + out + " -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const std::string summary = bytesOf(out + "/summary.json");
    const std::string map = bytesOf(out + "/map.hifmap");
    fs::create_directories(out + "/mine");  // the user's own file in the folder
    std::ofstream(out + "/mine/notes.txt") << "keep me";

    // The same run over them, failing on the fourth scan of a truncated rawlog.
    {
        const std::string all = bytesOf(root_ + "/all.rawlog");
        std::ofstream(root_ + "/cut.rawlog", std::ios::binary)
            .write(all.data(), std::streamsize(all.size() * 3 / 5));
    }
    r = runInProcess("hif-clean", "-i " + root_ + "/cut.rawlog -o " + out + " -q --overwrite");
    expectError(r, "cut.rawlog' is corrupt or truncated");
    EXPECT_EQ(bytesOf(out + "/summary.json"), summary);
    EXPECT_EQ(bytesOf(out + "/map.hifmap"), map);
    std::size_t predictions = 0;
    for (const auto& e : fs::directory_iterator(out + "/predictions"))
        predictions += e.path().extension() == ".label";
    EXPECT_EQ(predictions, 6u);
    for (const auto& e : fs::directory_iterator(root_))
        EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos)
            << "left behind: " << e.path();

    // A run that succeeds replaces them, and leaves the user's file.
    r = runInProcess("hif-clean",
                     "-i " + root_ + "/all.rawlog -o " + out + "/ -q --overwrite --online");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readJson(out + "/summary.json")["mode"], "online");
    EXPECT_EQ(bytesOf(out + "/mine/notes.txt"), "keep me");
    EXPECT_EQ(r.output.find("//"), std::string::npos) << r.output;
}

TEST_F(BadInput, ScansConvertedFromTheMiddleKeepTheirNumbers)
{
    const std::string rawlog = root_ + "/from2.rawlog";
    auto r =
        runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + rawlog + " --first 2 --last 4");
    ASSERT_EQ(r.code, 0) << r.output;
    r = runInProcess("hif-clean", "-i " + rawlog + " -o " + root_ + "/from2 -q");
    ASSERT_EQ(r.code, 0) << r.output;
    for (int f = 0; f < 6; ++f)
        EXPECT_EQ(fs::exists(root_ + "/from2/predictions/00000" + std::to_string(f) + ".label"),
                  f >= 2 && f <= 4)
            << f;
    // Scored against the right labels: the sizes match scan for scan.
    r = runInProcess("hif-eval", "--labels " + root_ + "/seq/labels --predictions " + root_ +
                                     "/from2/predictions -q");
    EXPECT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("3 scans"), std::string::npos) << r.output;
    expectError(
        runInProcess("hif-clean", "-i " + rawlog + " -o " + root_ + "/from2b -q --first-frame 0"),
        "--first-frame 0 disagrees with the input, whose first scan is frame 2");
}

TEST_F(BadInput, RedirectedOutputReadsInOrderAndFoldersAreNamedForWhatTheyAre)
{
    // Not a terminal: the header comes before the progress lines, and a rawlog (whose length
    // is unknown) still says how many scans it took.
    const auto r = runApp("hif-clean", "-i " + root_ + "/all.rawlog -o " + root_ + "/log");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto header = r.output.find("[hif-clean] output :");
    const auto progress = r.output.find("[hif-clean] inserting");
    ASSERT_NE(header, std::string::npos) << r.output;
    ASSERT_NE(progress, std::string::npos) << r.output;
    EXPECT_LT(header, progress) << r.output;
    EXPECT_NE(r.output.find("inserting 6 scans"), std::string::npos) << r.output;

    expectError(runInProcess("hif-eval", "--labels " + root_ + "/all.rawlog --predictions " +
                                             root_ + "/log/predictions"),
                "labels folder '" + root_ + "/all.rawlog' is not a folder");
}

// Found by fuzz_pcd (tests/fuzz): a header whose sizes or point count the file cannot hold is
// refused before anything is allocated for it, naming the file and the number.
TEST(BadPcd, AHeaderThatPromisesMoreThanTheFileHoldsIsRefused)
{
    const WorkDir work = workDir("bad_pcd_" + std::to_string(getpid()));
    const std::string& dir = work.path();
    auto pcd = [&](const std::string& size, const std::string& count, const std::string& points)
    {
        const std::string file = dir + "/scan.pcd";
        std::ofstream f(file, std::ios::binary | std::ios::trunc);
        f << "FIELDS x y z\nSIZE 4 4 " << size << "\nTYPE F F F\nCOUNT 1 1 " << count << "\nPOINTS "
          << points << "\nDATA binary\n";
        const float xyz[6] = {1, 2, 3, 4, 5, 6};
        f.write(reinterpret_cast<const char*>(xyz), sizeof(xyz));
        return file;
    };
    auto message = [](const std::string& file)
    {
        try
        {
            (void)hif::io::readPcd(file);
        }
        catch (const std::exception& e)
        {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    EXPECT_EQ(hif::io::readPcd(pcd("4", "1", "2")).x.size(), 2u);
    EXPECT_NE(message(pcd("-4", "1", "2")).find("has SIZE -4 for field z"), std::string::npos);
    EXPECT_NE(message(pcd("4", "0", "2")).find("has COUNT 0 for field z"), std::string::npos);
    const std::string big = message(pcd("4", "1", "1000000000000"));
    EXPECT_NE(big.find("scan.pcd"), std::string::npos) << big;
    EXPECT_NE(big.find("POINTS says 1000000000000, but 24 bytes of data follow DATA"),
              std::string::npos)
        << big;
    EXPECT_NE(message(pcd("4", "1", "3")).find("POINTS says 3, but 24 bytes"), std::string::npos);
}
