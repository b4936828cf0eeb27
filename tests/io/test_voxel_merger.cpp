// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_voxel_merger.cpp
 * @brief  VoxelMerger against a simple reference (a std::map of voxel sums), with and without
 *         spilling to run files, far from the origin, and on a voxel left and seen again.
 */
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include "hif/io/VoxelKey.h"
#include "hif/io/VoxelMerger.h"
#include "work_dir.h"

namespace
{
using hif::io::MergedPoint;
using hif::io::VoxelMerger;

struct Point
{
    double x, y, z;
    float intensity;
    uint32_t scan;
};

/** A sensor driving along x: each scan, points around it (some in voxels of earlier scans). */
std::vector<Point> drive(std::size_t scans, std::size_t per_scan, double offset, unsigned seed)
{
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> around(-6.0, 6.0), height(-1.0, 3.0);
    std::uniform_real_distribution<float> intensity(0.0f, 1.0f);
    std::vector<Point> pts;
    for (uint32_t s = 0; s < scans; ++s)
        for (std::size_t i = 0; i < per_scan; ++i)
            pts.push_back({offset + 2.0 * s + around(rng), offset + around(rng), height(rng),
                           intensity(rng), s});
    return pts;
}

/** The reference: every voxel's points, added up in a std::map, in key order. */
std::vector<MergedPoint> reference(const std::vector<Point>& pts, double voxel)
{
    struct Sum
    {
        double x = 0, y = 0, z = 0, i = 0;
        uint32_t n = 0;
    };
    std::map<std::array<int64_t, 3>, Sum> sums;
    for (const Point& p : pts)
    {
        Sum& s = sums[{static_cast<int64_t>(std::floor(p.x / voxel)),
                       static_cast<int64_t>(std::floor(p.y / voxel)),
                       static_cast<int64_t>(std::floor(p.z / voxel))}];
        s.x += p.x;
        s.y += p.y;
        s.z += p.z;
        s.i += p.intensity;
        ++s.n;
    }
    std::vector<MergedPoint> out;
    for (const auto& [key, s] : sums)
        out.push_back({s.x / s.n, s.y / s.n, s.z / s.n, static_cast<float>(s.i / s.n), s.n});
    return out;
}

std::vector<MergedPoint> merged(const std::vector<Point>& pts, double voxel, std::size_t max_voxels,
                                const std::string& prefix, std::size_t* spills = nullptr)
{
    VoxelMerger m(voxel, prefix, max_voxels);
    uint32_t scan = 0;
    for (const Point& p : pts)
    {
        for (; scan < p.scan; ++scan) m.nextScan();
        m.add(p.x, p.y, p.z, p.intensity);
    }
    EXPECT_EQ(m.pointsAdded(), pts.size());
    EXPECT_LE(m.peakVoxels(), max_voxels);
    std::vector<MergedPoint> out;
    const std::size_t voxels = m.finish([&](const MergedPoint& p) { out.push_back(p); });
    EXPECT_EQ(voxels, out.size());
    if (spills) *spills = m.spills();
    return out;
}

void expectSame(const std::vector<MergedPoint>& got, const std::vector<MergedPoint>& want,
                double tolerance)
{
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t k = 0; k < got.size(); ++k)
    {
        ASSERT_EQ(got[k].points, want[k].points) << "voxel " << k;
        ASSERT_NEAR(got[k].x, want[k].x, tolerance) << "voxel " << k;
        ASSERT_NEAR(got[k].y, want[k].y, tolerance) << "voxel " << k;
        ASSERT_NEAR(got[k].z, want[k].z, tolerance) << "voxel " << k;
        ASSERT_NEAR(got[k].intensity, want[k].intensity, 1e-6) << "voxel " << k;
    }
}
}  // namespace

TEST(VoxelMerger, MatchesTheReferenceInMemoryAndThroughRunFiles)
{
    hif::test::WorkDir dir("voxel_merger");
    const std::vector<Point> pts = drive(60, 3000, 0.0, 1);
    const std::vector<MergedPoint> want = reference(pts, 0.5);
    ASSERT_GT(want.size(), 20000u);
    std::size_t spills = 0;
    expectSame(merged(pts, 0.5, 2 * want.size(), dir.path() + "/all", &spills), want, 1e-9);
    EXPECT_EQ(spills, 0u);
    // A tenth of the voxels in memory: many run files, the same map.
    expectSame(merged(pts, 0.5, want.size() / 10, dir.path() + "/tenth", &spills), want, 1e-9);
    EXPECT_GT(spills, 10u);
    // The run files are gone.
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(VoxelMerger, KeepsMillimetresAtUtmCoordinates)
{
    hif::test::WorkDir dir("voxel_merger_utm");
    const double east = 4.5e6;  // UTM northing-sized coordinates
    const std::vector<Point> pts = drive(20, 2000, east, 2);
    const std::vector<MergedPoint> want = reference(pts, 0.2);
    const std::vector<MergedPoint> got = merged(pts, 0.2, want.size() / 4, dir.path() + "/utm");
    expectSame(got, want, 1e-6);
    // Each centroid lies inside its voxel.
    for (const MergedPoint& p : got)
        ASSERT_LT(std::abs(p.x - (std::floor(p.x / 0.2) + 0.5) * 0.2), 0.1 + 1e-9);
}

TEST(VoxelMerger, AVoxelLeftAndSeenAgainIsOnePoint)
{
    hif::test::WorkDir dir("voxel_merger_loop");
    VoxelMerger m(1.0, dir.path() + "/loop", 8);
    m.add(0.25, 0.25, 0.25, 1.0f);
    // The sensor goes away: many other voxels push the first one out to a run file...
    for (int s = 1; s <= 50; ++s)
    {
        m.nextScan();
        m.add(10.0 + s, 0.5, 0.5, 0.0f);
    }
    EXPECT_GT(m.spills(), 0u);
    // ...and comes back to it.
    m.nextScan();
    m.add(0.75, 0.75, 0.75, 3.0f);
    std::vector<MergedPoint> out;
    EXPECT_EQ(m.finish([&](const MergedPoint& p) { out.push_back(p); }), 51u);
    ASSERT_EQ(out.size(), 51u);
    EXPECT_EQ(out.front().points, 2u);
    EXPECT_DOUBLE_EQ(out.front().x, 0.5);
    EXPECT_FLOAT_EQ(out.front().intensity, 2.0f);
}

TEST(VoxelMerger, RefusesWhatItCannotMerge)
{
    EXPECT_THROW(VoxelMerger(0.0, "/tmp/x", 10), std::invalid_argument);
    hif::test::WorkDir dir("voxel_merger_bad");
    VoxelMerger m(0.001, dir.path() + "/bad", 10);
    m.add(std::nan(""), 0, 0, 0);  // not finite: left out
    EXPECT_EQ(m.pointsAdded(), 0u);
    EXPECT_THROW(m.add(3e6, 0, 0, 0), std::runtime_error);  // 3e9 voxels from the origin
    // A run file that cannot be created names itself.
    VoxelMerger nowhere(1.0, dir.path() + "/missing/dir/run", 2);
    nowhere.add(0, 0, 0, 0);
    try
    {
        nowhere.add(5, 0, 0, 0);
        nowhere.nextScan();  // points are added in batches, at the latest here
        FAIL() << "no error";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("missing/dir/run0.part"), std::string::npos)
            << e.what();
    }
}

TEST(VoxelKey, IsExactFarFromTheOriginAndRefusesWhatDoesNotFit)
{
    using hif::io::voxelKeyOf;
    // 2^21 voxels apart: a key packed into 21 bits per axis made these one voxel.
    const auto a = voxelKeyOf(0.5, 0.5, 0.5, 1.0);
    const auto b = voxelKeyOf(0.5 + double(1 << 21), 0.5, 0.5, 1.0);
    ASSERT_TRUE(a && b);
    EXPECT_NE(*a, *b);
    EXPECT_EQ(b->i, 1 << 21);
    // Negative coordinates round down, not toward zero.
    EXPECT_EQ(voxelKeyOf(-0.25, 0.0, 0.0, 0.5)->i, -1);
    // UTM at 1 cm: some 4.6e8 voxels from the origin, still exact.
    const auto utm = voxelKeyOf(4.6e6 + 0.005, 0.0, 0.0, 0.01);
    ASSERT_TRUE(utm);
    EXPECT_EQ(utm->i, 460000000);
    EXPECT_FALSE(voxelKeyOf(3e7, 0.0, 0.0, 0.01));  // 3e9 voxels
    EXPECT_FALSE(voxelKeyOf(std::nan(""), 0.0, 0.0, 1.0));
}
