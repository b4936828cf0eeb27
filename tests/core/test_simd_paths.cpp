// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_simd_paths.cpp
 * @brief  The AVX and the scalar paths of the per-point passes (quantization, the see-through
 *         range image, the insertion gate's walk down a pillar's rows, the free-space test's
 *         images) give the same map and the same classes, bit for bit: on real KITTI scans, and
 *         on a synthetic scan with invalid points.
 */
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "hif/FreeSpaceTest.h"
#include "hif/PillarGrid.h"
#include "hif/detail/Cpu.h"
#include "hif/io/KittiSequence.h"
#include "kitti_fixture.h"

using namespace hif;

namespace
{
/** Restores the default (AVX allowed) when a test ends, whatever happened. */
struct AvxGuard
{
    ~AvxGuard() { detail::setAvxAllowed(true); }
};

/** The offline configuration's additions on (see-through misses use the range image; the
 *  surfaces at pillars' edges the first pass's edge codes; the free-space test its own
 *  images). */
Params offlineParams()
{
    Params p;
    p.p_empty_init = 0.42;
    p.see_through_range = 35.0;
    p.pillar_edge_margin = 0.1;
    p.free_space_window = 10;
    return p;
}

struct Result
{
    PillarGrid grid{GridGeometry(), offlineParams()};
    std::vector<std::vector<uint8_t>> classes;  ///< by the map alone
    std::vector<std::vector<uint8_t>> tested;   ///< with the free-space test of all the scans
};

template <typename Scans>
Result runWith(bool avx, const Scans& scans)
{
    detail::setAvxAllowed(avx);
    Result r;
    for (const auto& [view, T] : scans) r.grid.insertScan(view, T);
    FreeSpaceTest test(scans.size());
    for (const auto& [view, T] : scans) test.add(view, T, r.grid.imageLayout());
    for (const auto& [view, T] : scans)
    {
        r.classes.emplace_back();
        r.grid.classify(view, r.classes.back(), T);
        r.tested.emplace_back();
        r.grid.classify(view, r.tested.back(), T, &test);
    }
    return r;
}
}  // namespace

TEST(SimdPaths, SameMapAndClassesOnRealScans)
{
    const std::string dir = test::kittiRoot() + "/sequences/08";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    AvxGuard guard;
    detail::setAvxAllowed(true);
    if (!detail::useAvx()) GTEST_SKIP() << "this CPU has no AVX: there is one path only";

    const io::KittiSequence seq(dir);
    // 24 of the 40 scans: the middle ones have the free-space test's whole window (10 scans)
    // on both sides; the sanitizers' build runs this several times slower.
    const std::size_t n = std::min<std::size_t>(seq.size(), 24);
    std::vector<io::Cloud> clouds;
    std::vector<std::pair<PointsView, Eigen::Isometry3d>> scans;
    for (std::size_t i = 0; i < n; ++i) clouds.push_back(seq.readScan(i));
    for (std::size_t i = 0; i < n; ++i)
    {
        const io::Cloud& c = clouds[i];
        scans.push_back({{c.x.data(), c.y.data(), c.z.data(), c.size()}, seq.pose(i)});
    }
    const Result avx = runWith(true, scans);
    const Result scalar = runWith(false, scans);
    EXPECT_GT(avx.grid.pillarCount(), 1000u);
    EXPECT_TRUE(avx.grid == scalar.grid) << "the maps differ";
    ASSERT_EQ(avx.classes.size(), scalar.classes.size());
    for (std::size_t i = 0; i < avx.classes.size(); ++i)
    {
        EXPECT_EQ(avx.classes[i], scalar.classes[i]) << "classes of scan " << i << " differ";
        EXPECT_EQ(avx.tested[i], scalar.tested[i])
            << "classes of scan " << i << " with the free-space test differ";
    }
}

// Points in LiDAR order with NaNs and far points among them, counts that are not multiples of
// four, and a rotated sensor: every lane of the vector code and its scalar remainder are used.
TEST(SimdPaths, SameMapAndClassesOnASyntheticScanWithInvalidPoints)
{
    AvxGuard guard;
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(0, 1);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    std::vector<std::vector<float>> xs, ys, zs;
    std::vector<std::pair<PointsView, Eigen::Isometry3d>> scans;
    for (int s = 0; s < 6; ++s)
    {
        std::vector<float> x, y, z;
        for (int ring = 0; ring < 16; ++ring)
            for (int k = 0; k < 1001 + s; ++k)
            {
                const double el = (-15.0 + 1.5 * ring) * M_PI / 180.0;
                const double az = 2 * M_PI * k / (1001 + s);
                const double r = 5.0 + 30.0 * u(rng);
                x.push_back(float(r * std::cos(el) * std::cos(az)));
                y.push_back(float(r * std::cos(el) * std::sin(az)));
                z.push_back(float(r * std::sin(el)));
                if (k % 97 == 5) z.back() = nan;
                if (k % 389 == 7) x.back() = 3e12f;
            }
        xs.push_back(x), ys.push_back(y), zs.push_back(z);
    }
    for (int s = 0; s < 6; ++s)
    {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.rotate(Eigen::AngleAxisd(0.4 * s, Eigen::Vector3d::UnitZ()) *
                 Eigen::AngleAxisd(0.03, Eigen::Vector3d::UnitY()));
        T.translation() = Eigen::Vector3d(1.5 * s, -0.7 * s, 1.7);
        scans.push_back({{xs[s].data(), ys[s].data(), zs[s].data(), xs[s].size()}, T});
    }
    const Result a = runWith(true, scans);
    const Result b = runWith(false, scans);
    EXPECT_TRUE(a.grid == b.grid);
    EXPECT_EQ(a.classes, b.classes);
    EXPECT_EQ(a.tested, b.tested);
}
