// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_nothing_lost.cpp
 * @brief  Nothing a user gave is lost, nothing is silently wrong: no output is an input or
 *         another output, two runs never write one folder at once, a stopped run leaves no
 *         partial results, georeferenced (UTM) coordinates keep their millimetres, inputs that
 *         are not what they claim (poses, DynamicMap folders, external scans, predictions) are
 *         named, and a stray point never breaks the picture.
 */
#include <gtest/gtest.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <thread>

#include "app_runner.h"
#include "hif/apps/Staged.h"
#include "hif/apps/TopView.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "job_runner.h"
#include "kitti_fixture.h"
#include "synthetic_suite.h"

extern char** environ;

namespace fs = std::filesystem;
// The app runner's helpers (runInProcess, runApp, expectError, readJson, bytesOf, WorkDir, ...).
using namespace hif::test;  // NOLINT(google-build-using-namespace)

namespace
{
/** A short synthetic sequence and its rawlog, shared by the tests of the suite. */
class NothingLost : public SyntheticSuite<NothingLost>
{
public:
    static constexpr const char* kFolder = "nothing_lost";
    static constexpr long long kScans = 6;
    static constexpr const char* kRawlog = "all.rawlog";
};

/** An app started in the background, its stdout and stderr into `log`. */
pid_t spawnApp(const std::string& app, const std::vector<std::string>& args, const std::string& log)
{
    const std::string exe = hif::test::kBin + "/" + app;
    std::vector<char*> argv{const_cast<char*>(exe.c_str())};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&fa, 1, 2);
    pid_t pid = -1;
    const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    EXPECT_EQ(rc, 0) << exe;
    return rc == 0 ? pid : -1;
}

/** Waits (up to 60 s) until `ready()`; false if it never was or the process ended first. */
bool waitUntil(pid_t pid, const std::function<bool()>& ready)
{
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (std::chrono::steady_clock::now() < end)
    {
        if (ready()) return true;
        int status = 0;
        if (waitpid(pid, &status, WNOHANG) == pid) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return false;
}

/** Entries of `dir` whose name holds `part`. */
std::vector<std::string> entriesWith(const std::string& dir, const std::string& part)
{
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().find(part) != std::string::npos)
            found.push_back(e.path().filename().string());
    return found;
}

/** A KITTI folder `dir` with the scans of `from` (linked, not copied), its calibration and
 *  times, and its poses moved by `shift` in the LiDAR's world frame, exactly: poses.txt holds
 *  camera poses P with T = inv(Tr) P Tr, so P gains inv(R_Tr^T) shift. */
void shiftedSequence(const std::string& from, const std::string& dir, const Eigen::Vector3d& shift)
{
    fs::create_directories(dir);
    fs::create_symlink(fs::canonical(fs::path(from) / "velodyne"), fs::path(dir) / "velodyne");
    if (fs::exists(fs::path(from) / "labels"))
        fs::create_symlink(fs::canonical(fs::path(from) / "labels"), fs::path(dir) / "labels");
    fs::copy_file(fs::path(from) / "calib.txt", fs::path(dir) / "calib.txt");
    fs::copy_file(fs::path(from) / "times.txt", fs::path(dir) / "times.txt");
    const hif::io::KittiSequence seq(from);
    const Eigen::Vector3d d = seq.Tr().linear().transpose().inverse() * shift;
    std::ifstream in(fs::path(from) / "poses.txt");
    std::ofstream out(fs::path(dir) / "poses.txt");
    out.precision(17);
    for (std::string line; std::getline(in, line);)
    {
        std::istringstream is(line);
        double v[12];
        for (double& x : v) is >> x;
        v[3] += d.x();
        v[7] += d.y();
        v[11] += d.z();
        for (int k = 0; k < 12; ++k) out << v[k] << (k == 11 ? '\n' : ' ');
    }
}
}  // namespace

TEST_F(NothingLost, HifEvalReplacesNoFileUnaskedAndNeverAnInput)
{
    const std::string out = root_ + "/eval_out";
    ASSERT_EQ(runInProcess("hif-clean", "-i " + root_ + "/all.rawlog -o " + out + " -q").code, 0);
    const std::string base = "--labels " + root_ + "/seq/labels --predictions " + out +
                             "/predictions --scans " + root_ + "/seq/velodyne -q ";
    const std::string label = root_ + "/seq/labels/000001.label";
    const std::string label_bytes = bytesOf(label);
    // Onto a label file being scored: never, with or without --overwrite.
    for (const std::string flag : {"--json", "--png", "--classes-ply"})
        for (const std::string ow : {"", " --overwrite"})
        {
            SCOPED_TRACE(flag + ow);
            expectError(runInProcess("hif-eval", base + flag + " " + label + ow),
                        "would be one of the .label files of the ground truth (--labels)");
        }
    EXPECT_EQ(bytesOf(label), label_bytes);
    // Through a link to it, the same (real paths are compared).
    fs::create_symlink(label, root_ + "/link.label");
    expectError(runInProcess("hif-eval", base + "--json " + root_ + "/link.label --overwrite"),
                "would be one of the .label files of the ground truth (--labels)");
    EXPECT_EQ(bytesOf(label), label_bytes);
    // A user's own files stay unless --overwrite is given.
    for (const std::string name : {"mine.json", "mine.png", "mine.ply"})
    {
        std::ofstream(root_ + "/" + name) << "keep me";
        const std::string flag = name == "mine.json"  ? "--json "
                                 : name == "mine.png" ? "--png "
                                                      : "--classes-ply ";
        expectError(runInProcess("hif-eval", base + flag + root_ + "/" + name),
                    "'" + root_ + "/" + name + "' already exists; pass --overwrite to replace it");
        EXPECT_EQ(bytesOf(root_ + "/" + name), "keep me");
        const Result r =
            runInProcess("hif-eval", base + flag + root_ + "/" + name + " --overwrite");
        EXPECT_EQ(r.code, 0) << r.output;
        EXPECT_NE(bytesOf(root_ + "/" + name), "keep me");
    }
    EXPECT_TRUE(entriesWith(root_, ".partial").empty());
    // Two outputs of one run are never one file.
    expectError(runInProcess("hif-eval",
                             base + "--json " + root_ + "/x.out --classes-ply " + root_ + "/x.out"),
                "two outputs of one run cannot be the same file");
}

TEST_F(NothingLost, HifCleanAndKitti2rawlogNeverWriteOverAnInputOrAnotherOutput)
{
    const std::string rawlog = root_ + "/all.rawlog";
    const std::string bytes = bytesOf(rawlog);
    const std::string in = "-i " + rawlog + " -q -o " + root_ + "/o ";
    expectError(runInProcess("hif-clean", in + "--rawlog-out " + rawlog + " --overwrite"),
                "'" + rawlog + "' (--rawlog-out) is the input (-i)");
    fs::create_symlink(rawlog, root_ + "/same.rawlog");
    expectError(
        runInProcess("hif-clean", in + "--rawlog-out " + root_ + "/same.rawlog --overwrite"),
        "is the input (-i) '" + rawlog + "'");
    EXPECT_EQ(bytesOf(rawlog), bytes);
    expectError(runInProcess("hif-clean", in + "--rawlog-out " + root_ + "/o/static_map.ply"),
                "(--rawlog-out) is also the static_map.ply of -o: two outputs of one run cannot "
                "be the same file");
    expectError(runInProcess("hif-clean", in + "--rawlog-out " + root_ + "/o/predictions/x.rawlog"),
                "lie one inside the other");
    // A config kept in the output folder under an output's name.
    fs::create_directories(root_ + "/o2");
    fs::copy_file(HIF_SHARE_DIR "/config/kitti.ini", root_ + "/o2/summary.json");
    const std::string config = bytesOf(root_ + "/o2/summary.json");
    expectError(runInProcess("hif-clean", "-i " + rawlog + " -q -o " + root_ + "/o2 -c " + root_ +
                                              "/o2/summary.json --overwrite"),
                "(the summary.json of -o) is the config");
    EXPECT_EQ(bytesOf(root_ + "/o2/summary.json"), config);
    EXPECT_FALSE(fs::exists(root_ + "/o"));
    // kitti2rawlog: never over a file of the sequence it reads.
    const std::string poses = bytesOf(root_ + "/seq/poses.txt");
    expectError(runInProcess("kitti2rawlog",
                             "-i " + root_ + "/seq -o " + root_ + "/seq/poses.txt --overwrite -q"),
                "(-o) is the poses.txt of -i");
    expectError(runInProcess("kitti2rawlog",
                             "-i " + root_ + "/seq -o " + root_ + "/seq/velodyne/000009.bin -q"),
                "would be one of the .bin files of the scans of -i");
    EXPECT_EQ(bytesOf(root_ + "/seq/poses.txt"), poses);
    EXPECT_FALSE(fs::exists(root_ + "/seq/velodyne/000009.bin"));
}

TEST(StagedFolder, ASecondWriterOfAFolderIsRefusedWhileTheFirstWrites)
{
    const WorkDir work = workDir("staged_lock_" + std::to_string(getpid()));
    const std::string dir = work.path() + "/out";
    {
        hif::apps::StagedFolder first(dir, {"a.txt"}, false, "--overwrite");
        std::ofstream(first.path() + "/a.txt") << "first";
        try
        {
            hif::apps::StagedFolder second(dir, {"a.txt"}, true, "--overwrite");
            FAIL() << "two writers of one folder";
        }
        catch (const std::runtime_error& e)
        {
            EXPECT_NE(std::string(e.what()).find("is being written by another run right now"),
                      std::string::npos)
                << e.what();
        }
        first.commit();
    }
    EXPECT_EQ(bytesOf(dir + "/a.txt"), "first");
    // Once the first is done, the next one may (and, without --overwrite, refuses the file).
    EXPECT_THROW(hif::apps::StagedFolder(dir, {"a.txt"}, false, "--overwrite"), std::runtime_error);
    {
        hif::apps::StagedFolder again(dir, {"a.txt"}, true, "--overwrite");
        std::ofstream(again.path() + "/a.txt") << "second";
        again.commit();
    }
    EXPECT_EQ(bytesOf(dir + "/a.txt"), "second");
    // A file that appears while a run writes, without --overwrite, is not replaced.
    {
        hif::apps::StagedFolder late(dir, {"b.txt"}, false, "--overwrite");
        std::ofstream(late.path() + "/b.txt") << "mine";
        std::ofstream(dir + "/b.txt") << "someone else's";
        EXPECT_THROW(late.commit(), std::runtime_error);
    }
    EXPECT_EQ(bytesOf(dir + "/b.txt"), "someone else's");
    // A run that made the folder and failed leaves no empty folder behind.
    {
        hif::apps::StagedFolder failed(work.path() + "/new", {"a.txt"}, false, "--overwrite");
        EXPECT_TRUE(fs::is_directory(work.path() + "/new"));
    }
    EXPECT_FALSE(fs::exists(work.path() + "/new"));
    EXPECT_TRUE(entriesWith(work.path(), ".partial").empty());
}

TEST_F(NothingLost, TwoCleaningsIntoOneNewFolderAtOnceNeverBothSucceed)
{
    const std::string out = root_ + "/together";
    const std::vector<std::string> args{"-i", root_ + "/all.rawlog", "-o", out, "-q"};
    const pid_t a = spawnApp("hif-clean", args, root_ + "/together_a.log");
    const pid_t b = spawnApp("hif-clean", args, root_ + "/together_b.log");
    int sa = 0, sb = 0;
    waitpid(a, &sa, 0);
    waitpid(b, &sb, 0);
    ASSERT_TRUE(WIFEXITED(sa) && WIFEXITED(sb));
    const int ok = (WEXITSTATUS(sa) == 0) + (WEXITSTATUS(sb) == 0);
    EXPECT_EQ(ok, 1) << "exactly one of two runs into one folder succeeds";
    const std::string failed =
        bytesOf(root_ + (WEXITSTATUS(sa) == 0 ? "/together_b.log" : "/together_a.log"));
    // Refused while the other wrote, or after it, because its results are there now.
    EXPECT_TRUE(failed.find("is being written by another run right now") != std::string::npos ||
                failed.find("already exists; pass --overwrite") != std::string::npos)
        << failed;
    EXPECT_EQ(readJson(out + "/summary.json")["scans"], 6);
    EXPECT_TRUE(entriesWith(root_, ".partial").empty());
}

TEST_F(NothingLost, AStoppedGeneratorLeavesNoHalfSequenceAndAKilledOneIsCleanedUpLater)
{
    const std::string target = root_ + "/gen";
    for (const int sig : {SIGINT, SIGTERM, SIGHUP, SIGKILL})
    {
        SCOPED_TRACE(strsignal(sig));
        const pid_t pid =
            spawnApp("hif-synthetic-kitti", {"-o", target, "-n", "400"}, root_ + "/gen.log");
        // Stopped while it writes: its staging folder is there.
        ASSERT_TRUE(waitUntil(pid, [&] { return !entriesWith(root_, ".gen.partial-").empty(); }))
            << bytesOf(root_ + "/gen.log");
        std::this_thread::sleep_for(std::chrono::milliseconds(100));  // a few scans written
        kill(pid, sig);
        int status = 0;
        waitpid(pid, &status, 0);
        ASSERT_TRUE(WIFSIGNALED(status)) << bytesOf(root_ + "/gen.log");
        EXPECT_EQ(WTERMSIG(status), sig);
        if (sig == SIGKILL)
        {
            // Nothing can clean up after kill -9; the next run does, and says so.
            EXPECT_EQ(entriesWith(root_, ".gen.partial-").size(), 1u);
            const Result r = runInProcess("hif-synthetic-kitti", "-o " + target + " -n 2");
            EXPECT_EQ(r.code, 0) << r.output;
            EXPECT_NE(r.output.find("left by a run that was stopped (process " +
                                    std::to_string(pid) + " is gone)"),
                      std::string::npos)
                << r.output;
        }
        else
        {
            EXPECT_NE(bytesOf(root_ + "/gen.log").find("stopped by SIG"), std::string::npos);
            EXPECT_FALSE(fs::exists(target)) << "a half sequence";
        }
        EXPECT_TRUE(entriesWith(root_, ".gen.partial-").empty());
    }
    EXPECT_EQ(hif::io::KittiSequence(target).size(), 2u);
}

TEST(NothingLostOnRealScans, AStoppedCleaningLeavesTheEarlierResultsAndNoPartialFiles)
{
    const std::string seq = hif::test::kittiRoot() + "/sequences/08";
    HIF_REQUIRE_KITTI_SEQUENCE(seq);
    const WorkDir work = workDir("stopped_clean_" + std::to_string(getpid()));
    const std::string& d = work.path();
    // Earlier results in the folder, and a cleaned rawlog beside it.
    std::ofstream(d + "/clean.rawlog") << "earlier";
    fs::create_directories(d + "/out");
    std::ofstream(d + "/out/summary.json") << "earlier";
    for (const int sig : {SIGINT, SIGTERM, SIGHUP})
    {
        SCOPED_TRACE(strsignal(sig));
        const pid_t pid = spawnApp(
            "hif-clean",
            {"-i", seq, "-o", d + "/out", "--overwrite", "--rawlog-out", d + "/clean.rawlog", "-q"},
            d + "/clean.log");
        // Stopped once it has begun writing (its partial rawlog is there).
        ASSERT_TRUE(waitUntil(pid, [&] { return !entriesWith(d, ".clean.partial-").empty(); }))
            << bytesOf(d + "/clean.log");
        kill(pid, sig);
        int status = 0;
        waitpid(pid, &status, 0);
        ASSERT_TRUE(WIFSIGNALED(status)) << bytesOf(d + "/clean.log");
        EXPECT_EQ(WTERMSIG(status), sig);
        EXPECT_NE(bytesOf(d + "/clean.log").find("its partial outputs were removed"),
                  std::string::npos);
        EXPECT_TRUE(entriesWith(d, ".partial").empty());
        EXPECT_TRUE(entriesWith(d + "/out", ".old").empty());
        EXPECT_EQ(bytesOf(d + "/out/summary.json"), "earlier");
        EXPECT_EQ(bytesOf(d + "/clean.rawlog"), "earlier");
    }
}

TEST(Georeferenced, AShiftedRealClipGivesTheSameClassesAndItsPointsPlusTheShift)
{
    const std::string clip = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(clip);
    const WorkDir work = workDir("georeferenced_" + std::to_string(getpid()));
    const std::string& d = work.path();
    // Its first 6 scans: enough for the comparison, at the time the sanitizers' build has.
    const std::string seq = hif::test::firstScans(clip, 6, d + "/clip");
    // UTM-like: 630 km east, 5,800 km north, 250 m up; whole metres keep the pillars aligned.
    const Eigen::Vector3d shift(630000, 5800000, 250);
    shiftedSequence(seq, d + "/utm", shift);
    const std::string flags = " -q --format both --classes-ply";
    Result r = runInProcess("hif-clean", "-i " + seq + " -o " + d + "/local" + flags);
    ASSERT_EQ(r.code, 0) << r.output;
    r = runInProcess("hif-clean", "-i " + d + "/utm -o " + d + "/shifted" + flags);
    ASSERT_EQ(r.code, 0) << r.output;
    // The same classes, scan for scan.
    for (const auto& e : fs::directory_iterator(d + "/local/predictions"))
        EXPECT_EQ(bytesOf(e.path().string()),
                  bytesOf(d + "/shifted/predictions/" + e.path().filename().string()))
            << e.path();
    EXPECT_EQ(readJson(d + "/local/summary.json")["cloud_coordinates"], "float32");
    EXPECT_EQ(readJson(d + "/shifted/summary.json")["cloud_coordinates"], "float64");
    // The points: the local ones plus the shift, to the millimetre (float64 in the files).
    for (const std::string name : {"static_map.pcd", "removed.pcd"})
    {
        const auto local = hif::io::readPcd(d + "/local/" + name);
        const auto shifted = hif::io::readPcd(d + "/shifted/" + name);
        ASSERT_EQ(local.size(), shifted.size()) << name;
        double worst = 0;
        for (std::size_t i = 0; i < local.size(); ++i)
            worst =
                std::max(worst, (shifted.point(i) - shift - local.point(i)).cwiseAbs().maxCoeff());
        EXPECT_LT(worst, 1e-3) << name;
    }
    for (const std::string name : {"static_map.ply", "removed.ply", "classes.ply"})
        EXPECT_NE(bytesOf(d + "/shifted/" + name).find("property double x\n"), std::string::npos)
            << name;
    EXPECT_NE(bytesOf(d + "/local/static_map.ply").find("property float x\n"), std::string::npos);
    // The picture is the same area (one row or column more or less, as the cells fall).
    const auto pl = readJson(d + "/local/summary.json")["picture"];
    const auto ps = readJson(d + "/shifted/summary.json")["picture"];
    EXPECT_NEAR(pl["width"].get<double>(), ps["width"].get<double>(), 12);
    EXPECT_NEAR(pl["height"].get<double>(), ps["height"].get<double>(), 12);
    // hif-eval in UTM: the same scores, its cloud in float64.
    const auto score = [&](const std::string& scans, const std::string& out)
    {
        const Result e = runInProcess("hif-eval", "--labels " + seq + "/labels --predictions " + d +
                                                      "/" + out + "/predictions --scans " + scans +
                                                      " -q --json " + d + "/" + out + ".json " +
                                                      "--classes-ply " + d + "/" + out + ".ply");
        EXPECT_EQ(e.code, 0) << e.output;
        return readJson(d + "/" + out + ".json")["total"];
    };
    EXPECT_EQ(score(seq + "/velodyne", "local"), score(d + "/utm/velodyne", "shifted"));
    EXPECT_NE(bytesOf(d + "/shifted.ply").find("property double x\n"), std::string::npos);
    // kitti2rawlog --dynamicmap writes the shifted scans' world points to the millimetre too.
    for (const std::string name : {"local", "shifted"})
    {
        const Result c =
            runInProcess("kitti2rawlog", "-i " + (name == "local" ? seq : d + "/utm") + " -o " + d +
                                             "/dm_" + name + " --dynamicmap --last 1 -q");
        ASSERT_EQ(c.code, 0) << c.output;
    }
    const auto dl = hif::io::readPcd(d + "/dm_local/pcd/000001.pcd");
    const auto ds = hif::io::readPcd(d + "/dm_shifted/pcd/000001.pcd");
    ASSERT_EQ(dl.size(), ds.size());
    double worst = 0;
    for (std::size_t i = 0; i < dl.size(); ++i)
        worst = std::max(worst, (ds.point(i) - shift - dl.point(i)).cwiseAbs().maxCoeff());
    EXPECT_LT(worst, 1e-3);
    EXPECT_NEAR((ds.viewpoint.translation() - dl.viewpoint.translation() - shift).norm(), 0, 1e-6);
}

TEST_F(NothingLost, AGridOriginOrAPoseOffTheGridIsRefused)
{
    // An origin whose pillar index overflows would leave every point outside the grid.
    const std::string far_origin = ini("origin_x=0.0", "origin_x=3e9", "far_origin.ini");
    expectError(runInProcess("hif-clean", "-i " + root_ + "/all.rawlog -o " + root_ +
                                              "/far_origin -q -c " + far_origin),
                "invalid origin_x = 3e+09 (must be such that |origin_x| / pillar_size < 2^31");
    // A pose 3e9 m away: its scan's points lie outside the grid, and the run says which.
    shiftedSequence(root_ + "/seq", root_ + "/far_pose", Eigen::Vector3d(3e9, 0, 0));
    const auto points = fs::file_size(root_ + "/seq/velodyne/000000.bin") / 16;
    expectError(runInProcess("hif-clean", "-i " + root_ + "/far_pose -o " + root_ + "/fp -q"),
                "scan 0 of '" + root_ + "/far_pose': " + std::to_string(points) +
                    " of its points lie outside the map's grid");
    EXPECT_FALSE(fs::exists(root_ + "/fp"));
    EXPECT_FALSE(fs::exists(root_ + "/far_origin"));
}

TEST_F(NothingLost, DynamicMapFoldersAreReadAsStrictlyAsKittiFolders)
{
    const std::string dm = root_ + "/dm";
    ASSERT_EQ(
        runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + dm + " --dynamicmap -q").code, 0);
    // Files that are not numbered scans are named and left out.
    fs::copy_file(dm + "/pcd/000000.pcd", dm + "/pcd/gt_cloud.pcd");
    fs::copy_file(dm + "/pcd/000001.pcd", dm + "/pcd/static_map.pcd");
    std::ofstream(dm + "/pcd/notes.txt") << "mine";
    Result r = runInProcess("hif-clean", "-i " + dm + " -o " + root_ + "/dm_out -q");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: '" + dm +
                            "/pcd' holds 3 file(s) not named as scans (NNNNNN.pcd), left out: "
                            "gt_cloud.pcd, notes.txt, static_map.pcd"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(readJson(root_ + "/dm_out/summary.json")["scans"], 6);
    // Results are never written among the scans.
    expectError(runInProcess("hif-clean", "-i " + dm + " -o " + dm + "/pcd -q --overwrite"),
                "would be one of the .pcd files of the scans of -i");
    // A scan without VIEWPOINT is not taken from the origin.
    {
        std::string pcd = bytesOf(dm + "/pcd/000002.pcd");
        const auto at = pcd.find("VIEWPOINT");
        pcd.erase(at, pcd.find('\n', at) + 1 - at);
        std::ofstream(dm + "/pcd/000002.pcd", std::ios::binary) << pcd;
    }
    expectError(runInProcess("hif-clean", "-i " + dm + " -o " + root_ + "/dm_out2 -q --overwrite"),
                "pcd/000002.pcd' has no VIEWPOINT line");
    EXPECT_FALSE(fs::exists(root_ + "/dm_out2"));
    // An ascii scan with PCL's nan for invalid points is read, those points invalid.
    {
        const auto c = hif::io::readPcd(dm + "/pcd/000003.pcd");
        std::ofstream f(dm + "/pcd/000002.pcd");
        f << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
          << "WIDTH " << c.size() << "\nHEIGHT 1\nVIEWPOINT";
        const Eigen::Quaterniond q(c.viewpoint.linear());
        const Eigen::Vector3d t = c.viewpoint.translation();
        f.precision(17);
        f << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.w() << ' ' << q.x() << ' '
          << q.y() << ' ' << q.z() << "\nPOINTS " << c.size() << "\nDATA ascii\n";
        f.precision(9);
        for (std::size_t i = 0; i < c.size(); ++i)
            if (i % 10 == 0)
                f << "nan nan nan 0\n";
            else
                f << c.x[i] << ' ' << c.y[i] << ' ' << c.z[i] << ' ' << c.intensity[i] << '\n';
    }
    r = runInProcess("hif-clean", "-i " + dm + " -o " + root_ + "/dm_out3 -q --overwrite");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto c3 = hif::io::readPcd(dm + "/pcd/000003.pcd");
    EXPECT_EQ(readJson(root_ + "/dm_out3/summary.json")["points_invalid"], (c3.size() + 9) / 10);
}

TEST_F(NothingLost, HifEvalReportsMissingPredictionsAndValuesThatAreNeitherStaticNorMoving)
{
    const std::string out = root_ + "/eval_missing";
    ASSERT_EQ(runInProcess("hif-clean", "-i " + root_ + "/all.rawlog -o " + out + " -q").code, 0);
    fs::remove(out + "/predictions/000004.label");
    {
        // Two points of scan 1 hold a semantic class (40, road) and 0.
        std::fstream f(out + "/predictions/000001.label",
                       std::ios::in | std::ios::out | std::ios::binary);
        const uint32_t values[2] = {40, 0};
        f.write(reinterpret_cast<const char*>(values), sizeof values);
    }
    const Result r =
        runInProcess("hif-eval", "--labels " + root_ + "/seq/labels --predictions " + out +
                                     "/predictions -q --json " + out + "/scores.json");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("1 label files in '" + root_ + "/seq/labels' have no prediction in '" +
                            out + "/predictions' (the first: 000004.label)"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("warning: 2 predicted points in 1 files are neither 9 (static) nor "
                            "251-259 (moving), e.g. 40 in '" +
                            out + "/predictions/000001.label': they are scored as static"),
              std::string::npos)
        << r.output;
    const auto j = readJson(out + "/scores.json");
    EXPECT_EQ(j["labels_without_predictions"], 1);
    EXPECT_EQ(j["predicted_points_neither_static_nor_moving"], 2);
    EXPECT_EQ(j["scans_scored"], 5);
}

TEST_F(NothingLost, ExternalScanFilesThatAreMissingOrTruncatedAreNamed)
{
    const std::string seq = copyOfSequence("external");
    const std::string rawlog = root_ + "/external.rawlog";
    ASSERT_EQ(runInProcess("kitti2rawlog", "-i " + seq + " -o " + rawlog + " --external -q").code,
              0);
    const std::string bin = fs::absolute(seq + "/velodyne/000003.bin").string();
    const std::string keep = bytesOf(bin);
    fs::remove(bin);
    expectError(runInProcess("hif-clean", "-i " + rawlog + " -o " + root_ + "/ext -q"),
                "rawlog '" + rawlog + "', scan 3: its points are in the external file '" + bin +
                    "', which does not exist");
    std::ofstream(bin, std::ios::binary).write(keep.data(), std::streamsize(keep.size() - 8));
    expectError(runInProcess("hif-clean", "-i " + rawlog + " -o " + root_ + "/ext -q"),
                "scan 3: its points are in the external file '" + bin + "', which is " +
                    std::to_string(keep.size() - 8) + " bytes: not a whole number of points");
    EXPECT_FALSE(fs::exists(root_ + "/ext"));
}

TEST_F(NothingLost, HifIcpSlamSaysWhatItCouldNotDo)
{
    // One scan: there is no trajectory to compare, and it says so (not "no pose").
    ASSERT_EQ(
        runInProcess("kitti2rawlog", "-i " + root_ + "/seq -o " + root_ + "/one.rawlog --last 0 -q")
            .code,
        0);
    Result r =
        runInProcess("hif-icp-slam", "-i " + root_ + "/one.rawlog -o " + root_ + "/slam1 -q");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("no trajectory error: the input holds one scan"), std::string::npos)
        << r.output;
    // Scans of one point each: ICP can never run, which is an error, not identity poses.
    {
        mrpt::io::CFileOutputStream f(root_ + "/points.rawlog");
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 4; ++s)
        {
            auto pts = mrpt::maps::CSimplePointsMap::Create();
            pts->insertPoint(10.0f + float(s), 0.0f, 0.0f);
            auto obs = mrpt::obs::CObservationPointCloud::Create();
            obs->pointcloud = pts;
            arch << *obs;
        }
    }
    expectError(
        runInProcess("hif-icp-slam", "-i " + root_ + "/points.rawlog -o " + root_ + "/slam2 -q"),
        "ICP could not align any of the 3 scans after the first (fewer than 3 points");
    EXPECT_FALSE(fs::exists(root_ + "/slam2"));
}

TEST_F(NothingLost, AStrayPointOrAFarPoseLeavesThePictureWholeAndBounded)
{
    // One point 3 km away in one scan.
    const std::string far = copyOfSequence("stray");
    {
        const float p[4] = {3000.0f, 0.0f, 0.0f, 0.5f};
        std::ofstream(far + "/velodyne/000002.bin", std::ios::binary | std::ios::app)
            .write(reinterpret_cast<const char*>(p), sizeof p);
    }
    for (const std::string mode : {"", "--online"})
    {
        SCOPED_TRACE(mode);
        const Result ref = runInProcess(
            "hif-clean", "-i " + root_ + "/seq -o " + root_ + "/ref -q --overwrite " + mode);
        ASSERT_EQ(ref.code, 0) << ref.output;
        const Result r = runInProcess(
            "hif-clean", "-i " + far + " -o " + root_ + "/stray_out -q --overwrite " + mode);
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("map.png shows the map's main area: 1 of"), std::string::npos)
            << r.output;
        // The same picture as without the stray point: same size, same cells.
        const auto a = readJson(root_ + "/ref/summary.json")["picture"];
        const auto b = readJson(root_ + "/stray_out/summary.json")["picture"];
        EXPECT_EQ(a["width"], b["width"]);
        EXPECT_EQ(a["height"], b["height"]);
        EXPECT_EQ(a["cell_m"], b["cell_m"]);
        EXPECT_EQ(b["points_outside"], 1);
    }
    // A pose 390 km off: the picture shows the main area, no larger, and the run is not slowed.
    const std::string jump = root_ + "/jump";
    shiftedSequence(root_ + "/seq", jump, Eigen::Vector3d::Zero());
    {
        std::ifstream in(jump + "/poses.txt");
        std::vector<std::string> lines;
        for (std::string l; std::getline(in, l);) lines.push_back(l);
        std::istringstream is(lines[3]);
        double v[12];
        for (double& x : v) is >> x;
        v[3] += 390000.0;
        std::ostringstream os;
        os.precision(17);
        for (int k = 0; k < 12; ++k) os << v[k] << ' ';
        lines[3] = os.str();
        std::ofstream out(jump + "/poses.txt");
        for (const auto& l : lines) out << l << '\n';
    }
    // The program, not the job in process: its peak memory (summary.json) is the process's.
    const Result r = runApp("hif-clean", "-i " + jump + " -o " + root_ + "/jump_out -q");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto pic = readJson(root_ + "/jump_out/summary.json")["picture"];
    EXPECT_LT(pic["width"].get<int>(), 2000);
    EXPECT_LT(pic["height"].get<int>(), 2000);
    EXPECT_GT(pic["points_outside"].get<int>(), 50000);  // the whole far scan
    EXPECT_LT(readJson(root_ + "/jump_out/summary.json")["peak_rss_mb"].get<double>(), 400.0);
}

TEST(TopViewPicture, StrayPointsAreLeftOutAndTheSizeIsBounded)
{
    const WorkDir work = workDir("topview_" + std::to_string(getpid()));
    const auto draw = [&](const std::function<void(hif::apps::TopView&)>& add)
    {
        hif::apps::TopView v;
        add(v);
        return v.write(work.path() + "/p.png", "test", false);
    };
    const auto street = [](hif::apps::TopView& v)
    {
        for (double x = 0; x < 200; x += 0.1)
            for (double y = -20; y < 20; y += 0.5) v.add(x, y, 0.0f, hif::apps::TopView::kKept);
    };
    const auto plain = draw(street);
    // A point 3 km away, one 390 km away, one at 1e12 m: left out, the picture unchanged.
    const auto stray = draw(
        [&](hif::apps::TopView& v)
        {
            street(v);
            v.add(3000, 0, 0, hif::apps::TopView::kRemoved);
            v.add(390000, 5, 1, hif::apps::TopView::kKept);
            v.add(1e12, 0, 0, hif::apps::TopView::kKept);
            v.add(std::nan(""), 0, 0, hif::apps::TopView::kKept);
        });
    EXPECT_EQ(stray.width, plain.width);
    EXPECT_EQ(stray.height, plain.height);
    EXPECT_EQ(stray.points_outside, 3u);
    EXPECT_EQ(stray.points, plain.points + 3);
    // A thin, very long strip: no side beyond kMaxSide, whatever the scaling up for width.
    const auto strip = draw(
        [](hif::apps::TopView& v)
        {
            for (double x = 0; x < 5000; x += 0.2) v.add(x, 0.0, 0.0f, hif::apps::TopView::kKept);
        });
    EXPECT_LE(strip.width, hif::apps::TopView::kMaxSide);
    EXPECT_LE(strip.height, hif::apps::TopView::kMaxSide);
    EXPECT_GE(strip.height, 40 + 10 + 82);  // room for the legend below the title band
}

TEST_F(NothingLost, MessagesNameWhatIsWrong)
{
    const std::string in = "-i " + root_ + "/all.rawlog -q ";
    const std::string seq = copyOfSequence("messages");
    // A pose with inf, and a word after a row.
    const std::string poses = bytesOf(seq + "/poses.txt");
    {
        std::string p = poses;
        const auto second = p.find('\n') + 1;
        p.replace(second, p.find(' ', second) - second, "inf");
        std::ofstream(seq + "/poses.txt") << p;
    }
    expectError(runInProcess("hif-clean", "-i " + seq + " -o " + root_ + "/m -q"),
                "poses.txt' line 2: number 1 of 12, 'inf', is not finite");
    {
        std::string p = poses;
        p.insert(p.find('\n'), " x");
        std::ofstream(seq + "/poses.txt") << p;
    }
    expectError(runInProcess("kitti2rawlog", "-i " + seq + " -o " + root_ + "/m.rawlog -q"),
                "poses.txt' line 1: 'x' after the 12 numbers of a 3x4 row-major matrix");
    // A folder as the config; a dangling link as the output folder; a missing folder.
    expectError(runInProcess("hif-clean", in + "-o " + root_ + "/m -c " + root_),
                "config '" + root_ + "' is a folder, not an .ini file");
    fs::create_symlink(root_ + "/nowhere/at/all", root_ + "/dangling");
    expectError(runInProcess("hif-clean", in + "-o " + root_ + "/dangling"),
                "the output folder '" + root_ + "/dangling' is a symbolic link to '" + root_ +
                    "/nowhere/at/all', which does not exist");
    expectError(runInProcess("hif-clean", in + "-o " + root_ + "/m --rawlog-out " + root_ +
                                              "/no/such/folder/clean.rawlog"),
                "--rawlog-out '" + root_ + "/no/such/folder/clean.rawlog': the folder '" + root_ +
                    "/no/such/folder' does not exist");
    // A rawlog pose that is not finite: the scan would be lost, point by point.
    {
        mrpt::io::CFileOutputStream f(root_ + "/nan_pose.rawlog");
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 2; ++s)
        {
            auto pose = mrpt::obs::CObservationRobotPose::Create();
            pose->pose.mean = mrpt::poses::CPose3D(s == 1 ? std::nan("") : 0.0, 0, 0, 0, 0, 0);
            auto pts = mrpt::maps::CSimplePointsMap::Create();
            for (float x = 2; x < 10; x += 0.5f) pts->insertPoint(x, 0.0f, -1.7f);
            auto obs = mrpt::obs::CObservationPointCloud::Create();
            obs->pointcloud = pts;
            arch << *pose << *obs;
        }
    }
    expectError(runInProcess("hif-clean", "-i " + root_ + "/nan_pose.rawlog -o " + root_ + "/m -q"),
                "scan 1 of '" + root_ + "/nan_pose.rawlog' has a pose that is not finite");
    // hif-eval with one folder for the labels and the predictions scores nothing real.
    expectError(runInProcess("hif-eval", "--labels " + root_ + "/seq/labels --predictions " +
                                             root_ + "/seq/labels/ -q"),
                "--labels and --predictions are the same folder");
    // Map counts a handful at most, and whole numbers.
    for (const std::string count : {"1000000", "-1", "one"})
    {
        ini("CHeightIntervalMap_count=1", "CHeightIntervalMap_count=" + count, "count.ini");
        expectError(runInProcess("hif-clean", in + "-o " + root_ + "/m -c " + root_ + "/count.ini"),
                    "count.ini', [map]: CHeightIntervalMap_count = '" + count +
                        "' is not a whole number in [0, 16]");
    }
    EXPECT_FALSE(fs::exists(root_ + "/m"));
    // A full disk (here: a file-size limit) is said as such, and leaves nothing behind.
    const auto limited = [&](const std::string& app, const std::string& args)
    {
        const std::string log = root_ + "/limited.log";
        const std::string cmd = "sh -c 'ulimit -f 2000; trap \"\" XFSZ; exec " + hif::test::kBin +
                                "/" + app + " " + args + "' > " + log + " 2>&1";
        const int status = std::system(cmd.c_str());
        return Result{WIFEXITED(status) ? WEXITSTATUS(status) : -1, bytesOf(log)};
    };
    expectError(limited("kitti2rawlog", "-i " + root_ + "/seq -o " + root_ + "/full.rawlog -q"),
                "'" + root_ + "/full.rawlog' could not be written (disk full?): File too large");
    expectError(
        limited("hif-clean", in + "-o " + root_ + "/full --rawlog-out " + root_ + "/full.rawlog"),
        "could not be written (disk full?): File too large");
    EXPECT_FALSE(fs::exists(root_ + "/full.rawlog"));
    EXPECT_FALSE(fs::exists(root_ + "/full"));
    EXPECT_TRUE(entriesWith(root_, ".partial").empty());
}
