// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_removal.cpp
 * @brief  Removal floors: synthetic walkers (across the view and along the line of sight) and
 *         cyclists, offline and online against the paper's method; real KITTI clips, and sparser
 *         copies of 04 (32 and 16 rings).
 */
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <tuple>

#include "app_checks.h"
#include "app_runner.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "hif/io/Rings.h"
#include "job_runner.h"
#include "kitti_fixture.h"

using nlohmann::json;

using hif::test::clean;
using hif::test::runInProcess;
using hif::test::WorkDir;
using hif::test::workDir;

using hif::test::cleanAndScore;
using hif::test::cleanAndScoreInput;
using hif::test::makeClip;
using hif::test::noPicture;
using hif::test::onlineMode;
using hif::test::paperConfig;

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
        // Measured: person DA 96.8 and 97.0 offline, 84.5 and 82.4 online (2026-12-08, the
        // simulated Velodyne's firings drifting from turn to turn; before, 97 and 92 offline, 86
        // and 77 online; the paper: under 40; testing the first point of a run alone gave 96 and
        // 86 offline, 75 and 70 online).
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

// The same people beside vegetation that beams enter (hif-synthetic-kitti --foliage: canopies,
// bushes along the sidewalks, hedges): a beam returns from a leaf at a random depth or passes
// through, so other scans see through a hedge now and then, as they see through a mover. The
// test must tell the two apart by the time they were seen in, and the pillar's share. Today:
// vegetation kept 99.45 % offline and 99.14 % online (hif-eval's per_static_class), person DA
// 98.02 and 86.75, SA 99.81 and 99.82 (99.30 and 98.59 %, 97.99 and 86.87, 99.79 and 99.76
// before a judge's beam past the edge of a point's surface asked the next judge to agree). A
// lower share next to a mover (doc/algorithm.md, not kept) keeps 96.0 and 89.2 % of the
// vegetation here.
TEST(Walkers, WalkersBesideFoliageAreRemovedAndTheFoliageKept)
{
    if (HIF_SANITIZED) GTEST_SKIP() << "removal floors: the plain suite (scripts/test.sh)";
    const WorkDir work = workDir("foliage_walkers_" + std::to_string(getpid()));
    const std::string seq = work.path() + "/v0";
    ASSERT_NO_FATAL_FAILURE(makeClip(seq, "walkers", 0, 3, true));
    for (const bool online : {false, true})
    {
        SCOPED_TRACE(online ? "online" : "offline");
        const std::string name = online ? "online" : "offline";
        const json s =
            cleanAndScore(seq, name, [&](hif::jobs::CleanOptions& o) { o.online = online; });
        const json& leaves = s["per_static_class"]["vegetation"];
        ASSERT_GT(leaves["static_total"].get<int>(), 20000) << s["per_static_class"];
        EXPECT_GE(leaves["SA"].get<double>(), online ? 98.0 : 99.0);
        EXPECT_GE(s["total"]["SA"].get<double>(), 99.5);
        EXPECT_GE(s["per_moving_class"]["moving-person"]["DA"].get<double>(), online ? 80.0 : 90.0);
    }
}

// People walking towards the sensor or away from it, within 15 degrees of its line of sight
// (issue 23's hard case): the beams through where a person was land on the person again, a
// little nearer or farther, so fewer are removed than of the people crossing the view. The floors
// guard today's figures (person DA 95.3 and 90.6 offline, 69.8 and 66.4 online, 2026-12-08, the
// simulated Velodyne's firings drifting from turn to turn; on the clips before, 96.9 and 87.2
// offline, 78.8 and 68.9 online, 2026-12-07, with
// a thing one beam wide facing the beams for a drift's measure and the middle of each run asked
// about a drift; 95.9 and 81.2 offline, 72.3 and 61.5 online, 2026-12-06; 95.9
// and 80.4 offline before a surface seen nearer before and farther after counted as moved; earlier
// 95.5 and 76.8 offline, 68.3 and 59.6 online; 95.5 and 73.7,
// 68.3 and 58.3 before the steady drift read the beam nearest each point's elevation; 94.2 and
// 72.9, 65.8 and 58.3 before the free-space test followed a steady drift within the margin, 80.5
// offline on the first clip before it followed a surface drifting out of it; the paper's
// method 30.6 and 19.0); the targets are 85 offline and 75 online.
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
        EXPECT_GE(offline["per_moving_class"]["moving-person"]["DA"].get<double>(), 85.0);
        EXPECT_GE(online["per_moving_class"]["moving-person"]["DA"].get<double>(), 65.0);
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
    // Measured: DA 96.0 offline, 82.9 online (2026-12-08, the simulated Velodyne's firings
    // drifting from turn to turn; 90.5 and 80.0 on an earlier day, the paper 71.2 then).
    for (const json* s : {&offline, &online})
    {
        EXPECT_GE((*s)["total"]["SA"].get<double>(), 99.5);
        EXPECT_GT((*s)["per_moving_class"]["moving-bicyclist"]["dynamic_total"].get<int>(), 1000);
    }
    EXPECT_GE(da(offline), 85.0);
    EXPECT_GE(da(online), 72.0);
    EXPECT_LT(da(paper), da(offline) - 10.0);
}

// Traffic around a sensor driving at 12 m/s (hif-synthetic-kitti --scene traffic, seed 3): cars
// and vans ahead of it and behind it at about its speed, in the next lane and the other way.
// Online, the ones that lead the sensor hide their own next places from the scans before; the
// free-space test finds them by their constant speed along the beams (doc/algorithm.md).
TEST(Traffic, CarsLeadingTheSensorAreRemovedOnline)
{
    if (HIF_SANITIZED) GTEST_SKIP() << "removal floors: the plain suite (scripts/test.sh)";
    const WorkDir work = workDir("traffic_" + std::to_string(getpid()));
    const std::string seq = work.path() + "/v12";
    ASSERT_NO_FATAL_FAILURE(makeClip(seq, "traffic", 12, 3));
    const json offline = cleanAndScore(seq, "offline");
    const json online = cleanAndScore(seq, "online", onlineMode);
    auto da = [](const json& s) { return s["per_moving_class"]["moving-car"]["DA"].get<double>(); };
    // Measured: DA 98.8 offline; online 89.3 (2026-12-08, the simulated Velodyne's firings
    // drifting from turn to turn; 98.6 and 86.3 on an earlier day, 83.1 online when the
    // constant-speed rule needed three scans of past, 78.3 before that rule).
    for (const json* s : {&offline, &online})
    {
        EXPECT_GE((*s)["total"]["SA"].get<double>(), 99.2);
        EXPECT_GT((*s)["per_moving_class"]["moving-car"]["dynamic_total"].get<int>(), 5000);
    }
    EXPECT_GE(da(offline), 95.0);
    EXPECT_GE(da(online), 84.5);
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
    auto r = runInProcess("kitti2rawlog", "-i " + dir + " -o " + w + "/scans.rawlog --external");
    ASSERT_EQ(r.code, 0) << r.output;
    const json scores = cleanAndScoreInput(w + "/scans.rawlog", dir + "/labels", w + "/out");
    const json& s = scores["total"];
    EXPECT_GE(s["SA"].get<double>(), sa_floor) << s;
    EXPECT_GE(s["AA"].get<double>(), aa_floor) << s;
    // 04's walking person, 35-43 m away: mostly removed (measured 96 %, 92.9 % before a mover's
    // lowest ring at the road's height went with it; 69 % testing points within 40 m only, 5 %
    // without the free-space test).
    if (seq == "04")
    {
        EXPECT_GE(scores["per_moving_class"]["moving-person"]["DA"].get<double>(), 94.0);
    }
}

// The targets as floors (04: AA >= 95; 03: SA >= 98), and SA floors a little under
// what the shipped kitti.ini measures (01: SA 99.41, AA 95.98; 03: SA 99.33; 04: SA 99.15, AA
// 96.62; 01 99.16, 03 98.83, 04 98.84 before p_empty held only where beams had passed). The
// results are deterministic, so a failure is a regression, not noise.
INSTANTIATE_TEST_SUITE_P(Sequences, RealKitti,
                         ::testing::Values(std::make_tuple("01", 99.2, 95.0),
                                           std::make_tuple("03", 99.1, 98.0),
                                           std::make_tuple("04", 98.9, 95.0)));

// Online (each scan judged with the past only, kitti-online.ini), floors a little under what the
// shipped config measures: 01 SA 99.17, car DA 75.06 (74.94 before a lowest return on a face
// above the ground was no ground, 74.37 before a pillar the map saw partly empty was tested as
// a mover's, 73.29 before the lowest return of a new pillar shown gone went
// with it, 70.46 before new pillars too small for an object were tested, 69.35 before a mover's
// lowest ring at the road's height went with it, 66.18 before a pillar's lowest return out of sight
// of the ground went with the mover); 03 SA 98.74 (97.83 before p_empty held only where beams had
// passed); 04 SA 98.95, AA 93.11, person DA 61.69 (59.74). Deterministic: a failure is a
// regression.
TEST(RealKittiOnline, OnlineCleaningMeetsTheFloors)
{
    struct Floors
    {
        std::string seq;
        double sa, da;
    };
    for (const Floors& f :
         std::vector<Floors>{{"01", 99.0, 74.5}, {"03", 98.5, 0.0}, {"04", 98.8, 86.0}})
    {
        SCOPED_TRACE(f.seq);
        const std::string dir = hif::test::kittiRoot() + "/sequences/" + f.seq;
        HIF_REQUIRE_KITTI_SEQUENCE(dir);
        const WorkDir work = workDir("kitti_online" + f.seq);
        const json scores =
            cleanAndScoreInput(dir, dir + "/labels", work.path() + "/out", onlineMode);
        const json& s = scores["total"];
        EXPECT_GE(s["SA"].get<double>(), f.sa) << s;
        if (f.seq != "03")
        {
            EXPECT_GE(s["DA"].get<double>(), f.da) << s;
        }
        if (f.seq == "04")
        {
            EXPECT_GE(scores["per_moving_class"]["moving-person"]["DA"].get<double>(), 60.0);
        }
    }
}

// KITTI 04 with every 2nd and every 4th ring (about an HDL-32E's and a VLP-16's spacing): the
// copies hold their rings and labels, and are cleaned. The floors are a little under today's
// figures (misses where beams passed, ground seen once kept, the free-space test measuring from
// the map's floor under a mover and testing a lone low ring next to a mover, p_empty held only
// where beams passed, a judge's beam past the edge of a point's surface asking the next judge;
// 32 rings: SA 98.86, AA 96.27; 16 rings: SA 97.96, AA 94.98; before the last, SA 98.69 and
// 97.62; earlier 16 rings AA 92.16 without the lone rings, SA 97.15 before p_empty held only
// where beams passed; the walking person 20.0 % or more (2.5 % when its lowest ring was taken
// for the ground)), as a guard against regressions on the way to issue 20's SA >= 98.
TEST(RealKittiRings, SparserCopiesOf04KeepTheirRingsAndLabelsAndAreCleaned)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const WorkDir work = workDir("kitti04_rings");
    for (const auto& [k, sa_floor, aa_floor, person_floor] :
         {std::tuple{2, 98.7, 95.3, 75.0}, std::tuple{4, 97.8, 93.3, 15.0}})
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
        const json scores = cleanAndScoreInput(seq, seq + "/labels", seq + "_out", noPicture);
        const json& s = scores["total"];
        EXPECT_GE(s["SA"].get<double>(), sa_floor) << s;
        EXPECT_GE(s["AA"].get<double>(), aa_floor) << s;
        EXPECT_GE(scores["per_moving_class"]["moving-person"]["DA"].get<double>(), person_floor);
    }
}

// The tool's choice of rings (hif_decimate_rings ... k phase, scripts/rings.sh with
// HIF_RINGS_PHASES=all): the k copies of every k-th ring, from ring 0 to ring k-1, split each
// scan's points and labels between them, nothing left out and nothing twice; and each is
// cleaned. The floors are a little under today's figures from each first ring (SA 97.96,
// 97.96, 97.98, 98.15, and 97.62, 97.62, 97.68, 97.90 before a judge's beam past the edge of
// a point's surface needed the next judge to agree; AA 94.98, 94.62, 93.26, 93.87; AA 94.20,
// 93.20, 92.55, 93.25 before a mover's lowest ring at the road's height went with it): every
// choice is as much a 16-beam LiDAR, and which rings a held-out copy keeps is not known.
TEST(RealKittiRings, TheCopiesFromEachFirstRingSplitEveryScan)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const WorkDir work = workDir("kitti04_ring_phases");
    constexpr int k = 4;
    const hif::io::KittiSequence full(dir);
    std::vector<hif::io::KittiSequence> copies;
    for (int phase = 0; phase < k; ++phase)
    {
        const std::string seq = work.path() + "/from" + std::to_string(phase);
        const std::string cmd = std::string(HIF_DECIMATE_RINGS) + " " + dir + " " + seq + " " +
                                std::to_string(k) + " " + std::to_string(phase) + " > /dev/null";
        ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
        copies.emplace_back(seq);
        ASSERT_EQ(copies.back().size(), full.size());
    }
    const std::string bad = std::string(HIF_DECIMATE_RINGS) + " " + dir + " " + work.path() +
                            "/bad 4 4 > /dev/null 2>&1";
    EXPECT_NE(std::system(bad.c_str()), 0) << "a phase of k or more is refused";
    for (std::size_t i = 0; i < full.size(); i += 3)
    {
        SCOPED_TRACE(i);
        // Each of the full scan's points, with its label, in exactly one copy.
        const hif::io::Cloud scan = full.readScan(i);
        const std::vector<uint32_t> labels = hif::io::readLabels(full.labelFile(i));
        std::multiset<std::tuple<float, float, float, uint32_t>> all, parts;
        for (std::size_t p = 0; p < scan.size(); ++p)
            all.emplace(scan.x[p], scan.y[p], scan.z[p], labels[p]);
        for (const auto& copy : copies)
        {
            const hif::io::Cloud part = copy.readScan(i);
            const std::vector<uint32_t> part_labels = hif::io::readLabels(copy.labelFile(i));
            ASSERT_EQ(part_labels.size(), part.size());
            EXPECT_NEAR(double(part.size()) / double(scan.size()), 1.0 / k, 0.05);
            for (std::size_t p = 0; p < part.size(); ++p)
                parts.emplace(part.x[p], part.y[p], part.z[p], part_labels[p]);
        }
        EXPECT_TRUE(parts == all);
    }
    const double aa_floor[k] = {94.4, 93.5, 93.0, 93.3};
    for (int phase = 0; phase < k; ++phase)
    {
        SCOPED_TRACE("from ring " + std::to_string(phase));
        const std::string seq = work.path() + "/from" + std::to_string(phase);
        const json s = cleanAndScoreInput(seq, seq + "/labels", seq + "_out", noPicture)["total"];
        EXPECT_GE(s["SA"].get<double>(), 97.8) << s;
        EXPECT_GE(s["AA"].get<double>(), aa_floor[phase]) << s;
    }
}

// --rawlog-out: the scans again without their dynamic points, a rawlog MRPT's own tools and
// hif-clean read back (with the same poses and frame numbers), holding exactly the kept points.
