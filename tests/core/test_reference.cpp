// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_reference.cpp
 * @brief  PillarGrid against a slow, obviously-correct implementation of Section III on random
 *         scans: std::map of pillars, std::set of endpoints, explicit overlap sets, Eq. 5 in
 *         probability form, no merging.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "hif/PillarGrid.h"
#include "hif/SensorModel.h"
#include "hif/detail/InsertSteps.h"

using namespace hif;
using hif::detail::bayesFilter;

namespace
{
struct RefInterval
{
    double b, t, p;  // [b, t) in height cells, P(static)
};

struct RefPillar
{
    double p_empty;
    std::vector<RefInterval> h;
};

class ReferenceHif
{
public:
    ReferenceHif(const GridGeometry& g, const Params& p) : geo_(g), prm_(p) {}

    void insert(const std::vector<std::array<double, 3>>& pts)
    {
        // Eq. 1: pillar of every point; heights as cells.
        std::map<std::pair<int, int>, std::set<int>> cells;
        for (const auto& q : pts)
        {
            const int m =
                static_cast<int>(std::floor((q[0] - geo_.origin_x) * (1.0 / geo_.pillar_size)));
            const int n =
                static_cast<int>(std::floor((q[1] - geo_.origin_y) * (1.0 / geo_.pillar_size)));
            cells[{m, n}].insert(
                static_cast<int>(std::floor(q[2] * (1.0 / geo_.height_resolution))));
        }
        const int gap = static_cast<int>(std::lround(prm_.merge_gap / geo_.height_resolution));
        const int pad =
            static_cast<int>(std::lround(prm_.interval_padding / geo_.height_resolution));
        for (auto& [key, occ] : cells)
        {
            // Eq. 4: fill gaps of at most `gap` empty cells, pad, then take maximal runs.
            std::set<int> filled;
            int prev = *occ.begin();
            for (int c : occ)
            {
                if (c - prev - 1 <= gap)
                    for (int k = prev; k <= c; ++k) filled.insert(k);
                filled.insert(c);
                prev = c;
            }
            std::set<int> padded;
            for (int c : filled)
                for (int k = c - pad; k <= c + pad; ++k) padded.insert(k);
            std::vector<RefInterval> scan;
            for (int c : padded)
            {
                if (!scan.empty() && scan.back().t == c)
                    scan.back().t = c + 1;
                else
                    scan.push_back({double(c), double(c + 1), 0.0});
            }
            auto it = pillars_.find(key);
            if (it == pillars_.end())
                it = pillars_.emplace(key, RefPillar{prm_.p_empty_init, {}}).first;
            update(it->second, scan);
        }
    }

    // P(static) at cell z of pillar (m, n): interval, else p_empty, else the prior.
    double prob(int m, int n, int z) const
    {
        const auto it = pillars_.find({m, n});
        if (it == pillars_.end()) return prm_.p_empty_init;
        for (const auto& h : it->second.h)
            if (h.b <= z && z < h.t) return h.p;
        return it->second.p_empty;
    }

    const std::map<std::pair<int, int>, RefPillar>& pillars() const { return pillars_; }

private:
    double clip(double p) const { return std::max(prm_.p_min, std::min(prm_.p_max, p)); }

    void update(RefPillar& g, const std::vector<RefInterval>& t) const
    {
        const double a = prm_.alpha, b = prm_.beta;
        std::set<double> e;  // Eq. 9
        for (const auto& h : t) e.insert({h.b, h.t});
        for (const auto& h : g.h) e.insert({h.b, h.t});
        double base = 1e300;  // Eq. 15
        for (const auto& h : t) base = std::min(base, h.b);
        const std::vector<double> es(e.begin(), e.end());
        std::vector<RefInterval> out;
        for (std::size_t k = 0; k + 1 < es.size(); ++k)  // Eq. 10
        {
            const double lo = es[k], hi = es[k + 1];
            auto overlaps = [&](const RefInterval& h)
            { return std::max(h.b, lo) < std::min(h.t, hi); };
            std::vector<const RefInterval*> om_t, om_g;  // Eq. 11
            for (const auto& h : t)
                if (overlaps(h)) om_t.push_back(&h);
            for (const auto& h : g.h)
                if (overlaps(h)) om_g.push_back(&h);
            EXPECT_LE(om_g.size(), 1u);
            double p;
            if (om_t.empty() && om_g.empty())
                continue;
            else if (!om_t.empty() && !om_g.empty())
                p = bayesFilter(om_g[0]->p, a, b);  // Eq. 12
            else if (!om_g.empty())
                p = (prm_.low_height_preservation && hi <= base)
                        ? om_g[0]->p                              // Eq. 16
                        : bayesFilter(om_g[0]->p, 1 - a, 1 - b);  // Eq. 13
            else
                p = bayesFilter(g.p_empty, a, b);  // Eq. 14
            out.push_back({lo, hi, clip(p)});      // Eq. 17-18
        }
        g.h = out;
        g.p_empty = clip(bayesFilter(g.p_empty, 1 - a, 1 - b));  // Eq. 8
    }

    GridGeometry geo_;
    Params prm_;
    std::map<std::pair<int, int>, RefPillar> pillars_;
};

std::vector<std::array<double, 3>> randomScan(std::mt19937& rng, int n, double shift)
{
    // A few pillars, heights clustered on a ground, a box and random clutter.
    std::uniform_real_distribution<double> xy(-2.5 + shift, 2.5 + shift), u(0, 1);
    std::normal_distribution<double> noise(0, 0.03);
    std::vector<std::array<double, 3>> pts;
    for (int i = 0; i < n; ++i)
    {
        const double x = xy(rng), y = xy(rng), r = u(rng);
        double z;
        if (r < 0.5)
            z = noise(rng);  // ground
        else if (r < 0.8)
            z = 0.5 + 1.0 * u(rng) + (shift > 0.5 ? 0.7 : 0.0);  // box, moves up
        else
            z = 4.0 * u(rng);  // clutter
        pts.push_back({x, y, z});
    }
    return pts;
}

void compareAll(const PillarGrid& grid, const ReferenceHif& ref)
{
    ASSERT_EQ(grid.pillarCount(), ref.pillars().size());
    for (const auto& [key, rp] : ref.pillars())
    {
        const Pillar* gp = grid.findPillar({int32_t(key.first), int32_t(key.second)});
        ASSERT_NE(gp, nullptr);
        EXPECT_NEAR(logistic(gp->logodds_empty), rp.p_empty, 1e-5);
        for (int z = -40; z < 140; ++z)
        {
            const GridGeometry& g = grid.geometry();
            const double x = g.origin_x + (key.first + 0.5) * g.pillar_size;
            const double y = g.origin_y + (key.second + 0.5) * g.pillar_size;
            const double zz = (z + 0.5) * g.height_resolution;
            ASSERT_NEAR(grid.staticProbability(x, y, zz), ref.prob(key.first, key.second, z), 1e-5)
                << "pillar (" << key.first << ", " << key.second << ") cell " << z;
        }
    }
}
}  // namespace

class AgainstReference : public ::testing::TestWithParam<bool>
{
};

TEST_P(AgainstReference, RandomScansGiveTheSameProbabilitiesEverywhere)
{
    Params prm = Params::paper();  // the reference implements the paper as written
    prm.low_height_preservation = GetParam();
    prm.max_intervals_per_pillar = 1000000;  // the reference does not cap
    GridGeometry geo;
    geo.origin_x = 0.25;
    geo.origin_y = -0.4;
    PillarGrid grid(geo, prm);
    ReferenceHif ref(geo, prm);
    std::mt19937 rng(GetParam() ? 11 : 12);
    for (int scan = 0; scan < 30; ++scan)
    {
        const auto pts = randomScan(rng, 300, 0.1 * scan);
        std::vector<float> x, y, z;
        for (const auto& q : pts)
        {
            x.push_back(float(q[0]));
            y.push_back(float(q[1]));
            z.push_back(float(q[2]));
            // The reference gets exactly what the grid sees (float inputs).
        }
        std::vector<std::array<double, 3>> as_float;
        for (std::size_t i = 0; i < x.size(); ++i) as_float.push_back({x[i], y[i], z[i]});
        grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        ref.insert(as_float);
        compareAll(grid, ref);
        if (HasFatalFailure()) return;
    }
}

INSTANTIATE_TEST_SUITE_P(Lhp, AgainstReference, ::testing::Values(true, false));

// Dense pillars (heights deduplicated with the bitmap), pillars spanning hundreds of metres in
// height (comparison sort), a point millions of metres away (the scan's bounding box is too
// large for the counting sort, so pillars are grouped by a comparison sort), and scans of
// several 16k-point chunks with NaN points in each (compaction between chunks): the grid must
// still agree with the reference, and with itself on 3 threads, bit for bit.
TEST(AgainstReference, DenseTallAndFarScansOnOneAndThreeThreads)
{
    Params prm = Params::paper();
    prm.max_intervals_per_pillar = 1000000;
    PillarGrid grid(GridGeometry(), prm), grid3(GridGeometry(), prm);
    grid3.setThreads(3);
    ReferenceHif ref(GridGeometry(), prm);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int scan = 0; scan < 12; ++scan)
    {
        // About 100 points per pillar; every other scan spans three chunks.
        auto pts = randomScan(rng, scan % 2 ? 40000 : 3000, 0.2 * scan);
        for (int i = 0; i < 200; ++i)  // tall pillars
            pts.push_back({10.5 + 3 * u(rng), -4.5, -300.0 + 600.0 * u(rng)});
        if (scan % 3 == 0) pts.push_back({3.0e6 + scan, -2.0e6, 1.0});
        std::vector<float> x, y, z;
        std::vector<std::array<double, 3>> as_float;  // the reference gets the valid points
        for (std::size_t i = 0; i < pts.size(); ++i)
        {
            const bool invalid = i % 997 == 3;
            x.push_back(invalid ? nan : float(pts[i][0]));
            y.push_back(float(pts[i][1]));
            z.push_back(float(pts[i][2]));
            if (!invalid) as_float.push_back({x.back(), y.back(), z.back()});
        }
        const PointsView view{x.data(), y.data(), z.data(), x.size()};
        const InsertStats st = grid.insertScan(view);
        EXPECT_EQ(st.points_used, as_float.size());
        EXPECT_EQ(st.points_invalid, pts.size() - as_float.size());
        grid3.insertScan(view);
        ref.insert(as_float);
        compareAll(grid, ref);
        if (HasFatalFailure()) return;
        ASSERT_TRUE(grid == grid3) << "3 threads differ from 1 after scan " << scan;

        std::vector<uint8_t> dyn1, dyn3;
        const ClassifyStats c1 = grid.classify(view, dyn1);
        const ClassifyStats c3 = grid3.classify(view, dyn3);
        EXPECT_EQ(dyn1, dyn3);
        EXPECT_EQ(c1.static_points, c3.static_points);
        for (std::size_t i = 0; i < pts.size(); i += 97)  // classify() agrees with isStatic()
            ASSERT_EQ(dyn1[i] == 0, grid.isStatic(x[i], y[i], z[i])) << "point " << i;
    }
}

// A scan in LiDAR order (ring by ring, azimuth by azimuth), so that most points repeat the
// pillar and height cell of the point before them (bucketPoints() does not store those), with
// NaN and far out-of-range points among them, placed by a rotation and a translation, and
// point counts that are not multiples of the vector width: the map must agree with the
// reference fed with every valid point, and every point's class with isStatic() of its world
// position, on 1 and on 3 threads.
TEST(AgainstReference, LidarOrderedScansWithRepeatsOnATransform)
{
    Params prm = Params::paper();
    prm.max_intervals_per_pillar = 1000000;
    GridGeometry geo;
    geo.origin_x = 0.3;
    PillarGrid grid(geo, prm), grid3(geo, prm);
    grid3.setThreads(3);
    ReferenceHif ref(geo, prm);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    struct Scan
    {
        std::vector<float> x, y, z;
        Eigen::Isometry3d T;
        std::vector<std::array<double, 3>> world;
    };
    std::vector<Scan> scans;
    for (int scan = 0; scan < 3; ++scan)
    {
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.rotate(Eigen::AngleAxisd(0.3 + scan, Eigen::Vector3d::UnitZ()) *
                 Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitX()));
        T.translation() = Eigen::Vector3d(5.3 + 2.0 * scan, -2.1, 0.4);
        std::vector<float> x, y, z;
        for (int ring = 0; ring < 23; ++ring)
        {
            const double el = (-20.0 + ring) * M_PI / 180.0;
            for (int k = 0; k < 1800 + scan; ++k)
            {
                const double az = k * 0.2 * M_PI / 180.0;
                // Ground 1.7 m below the sensor up to 40 m, else a wall; a box near it moves.
                double r = el < 0 ? std::min(40.0, 1.7 / std::tan(-el)) : 30.0;
                if (std::abs(az - 1.0 - 0.3 * scan) < 0.1 && ring > 12) r = 8.0;
                x.push_back(float(r * std::cos(el) * std::cos(az)));
                y.push_back(float(r * std::cos(el) * std::sin(az)));
                z.push_back(float(r * std::sin(el)));
            }
        }
        std::vector<bool> valid(x.size(), true);
        for (std::size_t i = 5; i < x.size(); i += 50)
        {
            z[i] = nan;
            valid[i] = false;
        }
        for (std::size_t i = 11; i < x.size(); i += 777)
        {
            x[i] = 1e12f;
            valid[i] = false;
        }
        // World positions, with the operations in the order bucketPoints() uses.
        const Eigen::Matrix3d R = T.linear();
        const Eigen::Vector3d t = T.translation();
        std::vector<std::array<double, 3>> world;
        for (std::size_t i = 0; i < x.size(); ++i)
        {
            const double sx = x[i], sy = y[i], sz = z[i];
            world.push_back({R(0, 0) * sx + R(0, 1) * sy + R(0, 2) * sz + t.x(),
                             R(1, 0) * sx + R(1, 1) * sy + R(1, 2) * sz + t.y(),
                             R(2, 0) * sx + R(2, 1) * sy + R(2, 2) * sz + t.z()});
        }
        std::vector<std::array<double, 3>> valid_world;
        for (std::size_t i = 0; i < x.size(); ++i)
            if (valid[i]) valid_world.push_back(world[i]);

        const PointsView view{x.data(), y.data(), z.data(), x.size()};
        detail::ScanBuckets sp;
        detail::bucketPoints(grid, view, T, sp, true);
        EXPECT_EQ(sp.points_valid, valid_world.size());
        EXPECT_LT(sp.entryCount() * 2, sp.points_valid) << "most points should be repeats";

        const InsertStats st = grid.insertScan(view, T);
        EXPECT_EQ(st.points_used, valid_world.size());
        grid3.insertScan(view, T);
        ref.insert(valid_world);
        compareAll(grid, ref);
        if (HasFatalFailure()) return;
        ASSERT_TRUE(grid == grid3) << "3 threads differ from 1 after scan " << scan;

        scans.push_back({x, y, z, T, world});
    }

    // Every scan classified against the final map (as offline): the box's earlier places were
    // seen empty later, so its points there are dynamic.
    std::size_t n_dynamic_valid = 0;
    for (const Scan& sc : scans)
    {
        const PointsView view{sc.x.data(), sc.y.data(), sc.z.data(), sc.x.size()};
        std::vector<uint8_t> dyn1, dyn3;
        const ClassifyStats c1 = grid.classify(view, dyn1, sc.T);
        const ClassifyStats c3 = grid3.classify(view, dyn3, sc.T);
        EXPECT_EQ(c1.static_points, c3.static_points);
        EXPECT_EQ(dyn1, dyn3);
        std::size_t n_static = 0;
        for (std::size_t i = 0; i < sc.x.size(); ++i)
        {
            // NaN points are dynamic; finite ones out of the index range have the prior.
            const auto& w = sc.world[i];
            const bool finite = !std::isnan(sc.z[i]);
            const bool stat = finite && grid.isStatic(w[0], w[1], w[2]);
            ASSERT_EQ(dyn1[i] == 0, stat) << "point " << i;
            n_static += stat;
            n_dynamic_valid += finite && !stat;
        }
        EXPECT_EQ(c1.static_points, n_static);
        EXPECT_GT(n_static, 0u);
    }
    EXPECT_GT(n_dynamic_valid, 0u) << "the moving box should leave dynamic points";
}

// See-through misses split pillars over threads: 1 and 3 threads must give the same map.
TEST(SeeThroughMisses, SameMapOnOneAndThreeThreads)
{
    Params prm;
    prm.see_through_range = 30.0;
    PillarGrid g1(GridGeometry(), prm), g3(GridGeometry(), prm), off;
    g3.setThreads(3);
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(0, 1);
    for (int scan = 0; scan < 8; ++scan)
    {
        // Ground near the sensor only (far ground returns are sparse), a wall at 25 m all
        // around, and a box that moves 2 m between scans.
        std::vector<float> x, y, z;
        auto add = [&](double px, double py, double pz)
        {
            x.push_back(float(px));
            y.push_back(float(py));
            z.push_back(float(pz));
        };
        for (int i = 0; i < 20000; ++i)
        {
            const double az = 2 * M_PI * u(rng);
            const double r = 6.0 * std::sqrt(u(rng));
            add(r * std::cos(az), r * std::sin(az), -1.7 + 0.02 * u(rng));
            add(25.0 * std::cos(az), 25.0 * std::sin(az), -1.7 + 4.0 * u(rng));
        }
        for (int i = 0; i < 2000; ++i)
            add(8.0 + scan * 2.0 + u(rng), -3.0 + u(rng), -1.5 + 1.3 * u(rng));
        const PointsView view{x.data(), y.data(), z.data(), x.size()};
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(0.3 * scan, 0.1 * scan, 0.0);
        g1.insertScan(view, T);
        g3.insertScan(view, T);
        off.insertScan(view, T);
        ASSERT_TRUE(g1 == g3) << "3 threads differ from 1 after scan " << scan;
    }
    // The misses did something: a box position left behind, which no later return falls in,
    // is empty only with them.
    EXPECT_FALSE(g1.isStatic(8.5, -2.5, -1.0));
    EXPECT_TRUE(off.isStatic(8.5, -2.5, -1.0));
}

// The buffers kept from scan to scan are only buffers: a grid that frees them now and then
// builds the same map and gives the same classes as one that keeps them. The scans are those of
// a 16-ring LiDAR, so that the ground rule (and its memo of runs down the image) takes part.
TEST(ScanBuffers, ReleasingThemChangesNeitherTheMapNorTheClasses)
{
    std::vector<double> el;
    for (int e = -15; e <= 15; e += 2) el.push_back(e);
    const SensorModel sensor = SensorModel::fromBeams(el, 0.4);
    Params prm;
    prm.p_empty_init = 0.42;
    prm.see_through_range = 30.0;
    prm.ground_max_slope_deg = 5.0;
    PillarGrid kept(GridGeometry(), prm), released(GridGeometry(), prm);
    Params no_rule = prm;
    no_rule.ground_max_slope_deg = 0.0;
    PillarGrid without_ground_rule(GridGeometry(), no_rule);
    for (PillarGrid* g : {&kept, &released, &without_ground_rule})
    {
        g->setSensorModel(sensor);
        g->setThreads(2);
    }
    constexpr double kGround = -1.7, kWall = 20.0;
    std::vector<float> x, y, z;
    for (int scan = 0; scan < 6; ++scan)
    {
        // Ground, a wall 20 m around the sensor, and a box 1 m wide whose face, 1.5 m high,
        // comes 1.1 m nearer each scan while the sensor moves 0.4 m towards it.
        const double box = 12.0 - 1.1 * scan;
        x.clear();
        y.clear();
        z.clear();
        for (int a = 0; a < 900; ++a)
        {
            const double az = a * 0.4 * M_PI / 180.0, c = std::cos(az), s = std::sin(az);
            for (const double e_deg : el)
            {
                const double t = std::tan(e_deg * M_PI / 180.0);
                double d = kWall;  // horizontal distance to the first surface along the beam
                if (t < 0) d = std::min(d, kGround / t);
                if (c > 0 && std::abs(box * s / c + 2.5) < 0.5 && box / c * t < kGround + 1.5)
                    d = std::min(d, box / c);
                x.push_back(float(d * c));
                y.push_back(float(d * s));
                z.push_back(float(d * t));
            }
        }
        const PointsView view{x.data(), y.data(), z.data(), x.size()};
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(0.4 * scan, 0.0, 0.0);
        kept.insertScan(view, T);
        released.insertScan(view, T);
        without_ground_rule.insertScan(view, T);
        std::vector<uint8_t> a, b;
        const ClassifyStats sa = kept.classify(view, a, T);
        const ClassifyStats sb = released.classify(view, b, T);
        if (scan % 2 == 0) released.releaseScanBuffers();
        ASSERT_TRUE(kept == released) << "the maps differ after scan " << scan;
        ASSERT_EQ(a, b) << "the classes differ at scan " << scan;
        EXPECT_EQ(sa.static_points, sb.static_points);
        if (scan > 1)
        {
            EXPECT_GT(sa.dynamic_points, 0u) << "the box should be dynamic";
        }
    }
    EXPECT_FALSE(kept == without_ground_rule) << "the ground rule should take part";
}

// classify() is const and may run on several threads at once on one grid: each call takes its
// own scan buffer from the grid, so concurrent calls give what one call at a time gives.
TEST(Classify, ConcurrentCallsOnOneGridGiveTheSequentialResults)
{
    std::mt19937 rng(7);
    PillarGrid grid(GridGeometry(), Params::paper());
    struct FloatScan
    {
        std::vector<float> x, y, z;
        [[nodiscard]] PointsView view() const { return {x.data(), y.data(), z.data(), x.size()}; }
    };
    std::vector<FloatScan> scans(6);
    for (std::size_t k = 0; k < scans.size(); ++k)
    {
        for (const auto& p : randomScan(rng, 3000, 0.3 * double(k)))
        {
            scans[k].x.push_back(float(p[0]));
            scans[k].y.push_back(float(p[1]));
            scans[k].z.push_back(float(p[2]));
        }
        grid.insertScan(scans[k].view(), Eigen::Isometry3d::Identity());
    }
    std::vector<std::vector<uint8_t>> want(scans.size());
    for (std::size_t k = 0; k < scans.size(); ++k) (void)grid.classify(scans[k].view(), want[k]);
    std::vector<std::vector<std::vector<uint8_t>>> got(scans.size(),
                                                       std::vector<std::vector<uint8_t>>(20));
    std::vector<std::thread> threads;
    for (std::size_t k = 0; k < scans.size(); ++k)
        threads.emplace_back(
            [&, k]
            {
                for (auto& out : got[k]) (void)grid.classify(scans[k].view(), out);
            });
    for (std::thread& t : threads) t.join();
    for (std::size_t k = 0; k < scans.size(); ++k)
        for (const auto& out : got[k]) ASSERT_EQ(out, want[k]) << "scan " << k;
    // Some points of each kind, or the comparison says little.
    std::size_t dynamic = 0, total = 0;
    for (const auto& w : want)
        for (const uint8_t d : w)
        {
            dynamic += d;
            ++total;
        }
    EXPECT_GT(dynamic, 0u);
    EXPECT_LT(dynamic, total);
}
