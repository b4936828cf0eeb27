// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_pillar_update.cpp
 * @brief  Eq. 4-18 with hand-computed numbers: interval construction, the Bayes filter, the
 *         three overlap cases, LHP, clipping, p_empty, the lossless merge and the bound.
 */
#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <random>
#include <set>

#include "hif/PillarGrid.h"
#include "hif/detail/InsertSteps.h"
#include "hif/detail/PillarUpdate.h"
#include "lidar_beams.h"

using namespace hif;
using namespace hif::detail;

namespace
{
constexpr double kTol = 1e-6;

double probOf(const Interval& iv) { return logistic(iv.logodds); }

Interval iv(int32_t lo, int32_t hi, double p) { return {lo, hi, static_cast<float>(logit(p))}; }

Pillar pillar(double p_empty, std::vector<Interval> ivs)
{
    Pillar p;
    p.logodds_empty = static_cast<float>(logit(p_empty));
    p.intervals = std::move(ivs);
    return p;
}

// The paper's model: alpha 0.6, beta 0.45 (defaults); LHP as given.
LogOddsModel model(bool lhp = true)
{
    Params p = Params::paper();
    p.low_height_preservation = lhp;
    return LogOddsModel::fromParams(p);
}

void update(Pillar& g, const std::vector<Span>& t, bool lhp = true, std::size_t cap = 1000)
{
    PillarUpdater(model(lhp), cap).update(g, t.data(), t.size());
}
}  // namespace

TEST(BayesFilter, Eq5HandNumbers)
{
    // 0.6 * 0.5 / (0.6 * 0.5 + 0.45 * 0.5) = 0.3 / 0.525
    EXPECT_NEAR(bayesFilter(0.5, 0.6, 0.45), 0.571428571, 1e-9);
    // Eq. 8 / 13: 0.4 * 0.5 / (0.4 * 0.5 + 0.55 * 0.5) = 0.2 / 0.475
    EXPECT_NEAR(bayesFilter(0.5, 0.4, 0.55), 0.421052632, 1e-9);
    // Log-odds form used by the code is the same function.
    const LogOddsModel m = model();
    for (double p : {0.1, 0.3, 0.5, 0.77})
    {
        EXPECT_NEAR(logistic(logit(p) + m.hit), bayesFilter(p, 0.6, 0.45), kTol);
        EXPECT_NEAR(logistic(logit(p) + m.miss), bayesFilter(p, 0.4, 0.55), kTol);
    }
}

namespace
{
/** A gap and a padding, in cells, for spansFromCells(). */
struct Widths
{
    int32_t gap, pad;
};

std::vector<Span> spansOf(const std::vector<int32_t>& cells, int32_t gap, int32_t pad)
{
    std::vector<Span> s(cells.size());
    const auto widths = [&](double) { return Widths{gap, pad}; };
    s.resize(spansFromCells(cells.data(), cells.size(), widths, gap, s.data()));
    return s;
}
}  // namespace

TEST(SpansFromCells, MergesByGapAndPads)
{
    const std::vector<int32_t> cells = {0, 1, 2, 5, 6, 20};
    std::vector<Span> s = spansOf(cells, 0, 0);
    EXPECT_EQ(s, (std::vector<Span>{{0, 3}, {5, 7}, {20, 21}}));
    s = spansOf(cells, 1, 0);  // gap of 2 empty cells > 1
    EXPECT_EQ(s, (std::vector<Span>{{0, 3}, {5, 7}, {20, 21}}));
    s = spansOf(cells, 2, 0);  // 3,4 empty: merged
    EXPECT_EQ(s, (std::vector<Span>{{0, 7}, {20, 21}}));
    s = spansOf(cells, 0, 1);  // padding joins [−1,4) and [4,8)
    EXPECT_EQ(s, (std::vector<Span>{{-1, 8}, {19, 22}}));
    const std::vector<int32_t> dup = {3, 3, 3};
    EXPECT_EQ(spansOf(dup, 0, 0), (std::vector<Span>{{3, 4}}));
    EXPECT_TRUE(spansOf({}, 0, 0).empty());
}

// Widths by height: a sensor whose beams lie farther apart higher up (a VLP-32C) samples the
// top of a facade more sparsely than the ground in the same pillar. Heights from cell 10 up
// take a gap of 4 and a padding of 2, those below none: the upper cells 3 apart share a span,
// padded by the upper widths; the lower cells 2 apart do not; a span that starts below and
// ends above is padded by each end's own.
TEST(SpansFromCells, EachHeightTakesItsOwnWidths)
{
    const auto widths = [](double h) { return h >= 10.0 ? Widths{4, 2} : Widths{0, 0}; };
    auto spans = [&](const std::vector<int32_t>& cells)
    {
        std::vector<Span> s(cells.size());
        s.resize(spansFromCells(cells.data(), cells.size(), widths, 0, s.data()));
        return s;
    };
    EXPECT_EQ(spans({0, 2, 12, 15, 18}), (std::vector<Span>{{0, 1}, {2, 3}, {10, 21}}));
    // 7 and 11: their middle (9) takes no gap; 9 and 11 (middle 10) share the upper one.
    EXPECT_EQ(spans({7, 11}), (std::vector<Span>{{7, 8}, {9, 14}}));
    EXPECT_EQ(spans({9, 11}), (std::vector<Span>{{9, 14}}));
}

TEST(PillarUpdate, Case1SeenAgainIncreases_Eq12)
{
    Pillar g = pillar(0.5, {iv(0, 10, 0.5)});
    update(g, {{0, 10}});
    ASSERT_EQ(g.intervals.size(), 1u);
    EXPECT_EQ(g.intervals[0].lo, 0);
    EXPECT_EQ(g.intervals[0].hi, 10);
    EXPECT_NEAR(probOf(g.intervals[0]), 0.571428571, kTol);
}

TEST(PillarUpdate, Case2NotSeenDecreases_Eq13)
{
    Pillar g = pillar(0.5, {iv(0, 10, 0.5), iv(20, 30, 0.5)});
    update(g, {{0, 10}});
    ASSERT_EQ(g.intervals.size(), 2u);
    EXPECT_NEAR(probOf(g.intervals[0]), 0.571428571, kTol);
    EXPECT_NEAR(probOf(g.intervals[1]), 0.421052632, kTol);
}

TEST(PillarUpdate, Case3NewStartsFromPEmpty_Eq14)
{
    Pillar g = pillar(0.3, {});
    update(g, {{0, 10}});
    ASSERT_EQ(g.intervals.size(), 1u);
    // 0.6 * 0.3 / (0.6 * 0.3 + 0.45 * 0.7) = 0.18 / 0.495
    EXPECT_NEAR(probOf(g.intervals[0]), 0.363636364, kTol);
    // Eq. 8: 0.4 * 0.3 / (0.4 * 0.3 + 0.55 * 0.7) = 0.12 / 0.505
    EXPECT_NEAR(logistic(g.logodds_empty), 0.237623762, kTol);
}

TEST(PillarUpdate, NeitherIsDiscarded_Eq11)
{
    Pillar g = pillar(0.5, {iv(0, 5, 0.7)});
    update(g, {{10, 15}}, /*lhp=*/false);
    ASSERT_EQ(g.intervals.size(), 2u);
    EXPECT_EQ(g.intervals[0].hi, 5);
    EXPECT_EQ(g.intervals[1].lo, 10);  // nothing kept in [5, 10)
}

TEST(PillarUpdate, PartialOverlapSplitsAtEveryEndpoint_Eq9_10)
{
    // g [0,10) p=0.7, t [5,15): [0,5) not seen, [5,10) seen, [10,15) new.
    Pillar g = pillar(0.5, {iv(0, 10, 0.7)});
    update(g, {{5, 15}}, /*lhp=*/false);
    ASSERT_EQ(g.intervals.size(), 3u);
    EXPECT_EQ(g.intervals[0].lo, 0);
    EXPECT_EQ(g.intervals[0].hi, 5);
    EXPECT_EQ(g.intervals[1].lo, 5);
    EXPECT_EQ(g.intervals[1].hi, 10);
    EXPECT_EQ(g.intervals[2].lo, 10);
    EXPECT_EQ(g.intervals[2].hi, 15);
    EXPECT_NEAR(probOf(g.intervals[0]), 0.28 / 0.445, kTol);  // 0.4*0.7/(0.28+0.55*0.3)
    EXPECT_NEAR(probOf(g.intervals[1]), 0.42 / 0.555, kTol);  // 0.6*0.7/(0.42+0.45*0.3)
    EXPECT_NEAR(probOf(g.intervals[2]), 0.571428571, kTol);   // from p_empty 0.5
}

TEST(PillarUpdate, LowHeightPreservationKeepsOnlyWhatIsBelowTheBase_Eq15_16)
{
    // Scan sees only [10,15): b_base = 10. [0,5) lies below it (unknown), [20,25) above.
    const Pillar before = pillar(0.5, {iv(0, 5, 0.7), iv(20, 25, 0.7)});
    Pillar with = before;
    update(with, {{10, 15}}, /*lhp=*/true);
    ASSERT_EQ(with.intervals.size(), 3u);
    EXPECT_NEAR(probOf(with.intervals[0]), 0.7, kTol);           // kept
    EXPECT_NEAR(probOf(with.intervals[2]), 0.28 / 0.445, kTol);  // decreased

    Pillar without = before;
    update(without, {{10, 15}}, /*lhp=*/false);
    ASSERT_EQ(without.intervals.size(), 3u);
    EXPECT_NEAR(probOf(without.intervals[0]), 0.28 / 0.445, kTol);
    EXPECT_NEAR(probOf(without.intervals[2]), 0.28 / 0.445, kTol);

    // An interval that straddles b_base is split there: the part below is kept.
    Pillar straddle = pillar(0.5, {iv(0, 20, 0.7)});
    update(straddle, {{15, 20}}, /*lhp=*/true);
    ASSERT_EQ(straddle.intervals.size(), 2u);
    EXPECT_EQ(straddle.intervals[0].hi, 15);
    EXPECT_NEAR(probOf(straddle.intervals[0]), 0.7, kTol);
    EXPECT_NEAR(probOf(straddle.intervals[1]), 0.42 / 0.555, kTol);
}

TEST(PillarUpdate, ClippingBoundsEveryProbability_Eq17_18)
{
    Pillar up = pillar(0.5, {});
    Pillar down = pillar(0.5, {iv(10, 20, 0.5)});
    for (int k = 0; k < 50; ++k)
    {
        update(up, {{0, 5}});
        update(down, {{0, 5}});  // [10,20) above the base: never seen again
    }
    EXPECT_NEAR(probOf(up.intervals[0]), 0.9, kTol);
    EXPECT_NEAR(logistic(up.logodds_empty), 0.1, kTol);  // p_empty clipped as well
    EXPECT_NEAR(probOf(down.intervals[1]), 0.1, kTol);
    // After saturation one opposite observation moves it off the bound by one step.
    update(up, {{50, 55}});  // [0,5) is below the base: LHP keeps it
    EXPECT_NEAR(probOf(up.intervals[0]), 0.9, kTol);
    update(up, {{0, 1}});  // [1,5) now above the base and unseen
    EXPECT_NEAR(probOf(up.intervals[1]), bayesFilter(0.9, 0.4, 0.55), kTol);
}

TEST(PillarUpdate, TouchingEqualResultsAreMergedLosslessly)
{
    // Two scans split [0,10) at different places; pieces with the same history re-merge.
    Pillar g = pillar(0.5, {iv(0, 10, 0.5)});
    update(g, {{0, 4}, {6, 10}});
    // [0,4) and [6,10) seen; [4,6) not seen and above base 0.
    ASSERT_EQ(g.intervals.size(), 3u);
    update(g, {{0, 10}});
    ASSERT_EQ(g.intervals.size(), 3u);  // [4,6) still differs
    EXPECT_EQ(g.intervals[0].logodds, g.intervals[2].logodds);
    update(g, {{0, 4}, {6, 10}});
    update(g, {{4, 6}});  // base 4: [0,4) kept, [4,6) +hit, [6,10) -miss
    for (std::size_t k = 1; k < g.intervals.size(); ++k)
        EXPECT_FALSE(g.intervals[k - 1].hi == g.intervals[k].lo &&
                     g.intervals[k - 1].logodds == g.intervals[k].logodds);
}

TEST(CapIntervals, SmallestGapFirstThenSmallestLogOddsDifferenceThenTheLowerPair)
{
    // The gap decides before the log-odds: pair 0 has gap 1 and difference 2, pair 1 gap 5
    // and difference 0; pair 0 is merged.
    std::vector<Interval> v = {{0, 2, 0.0f}, {3, 5, 2.0f}, {10, 12, 2.0f}};
    v.resize(capIntervals(v.data(), v.size(), 2));
    EXPECT_EQ(v, (std::vector<Interval>{{0, 5, 1.0f}, {10, 12, 2.0f}}));
    // Equal gaps: the smaller log-odds difference (pair 1: 0.5 against 1) is merged.
    v = {{0, 2, 0.0f}, {3, 5, 1.0f}, {6, 8, 1.5f}};
    v.resize(capIntervals(v.data(), v.size(), 2));
    EXPECT_EQ(v, (std::vector<Interval>{{0, 2, 0.0f}, {3, 8, 1.25f}}));
    // Equal gaps and differences: the lower pair.
    v = {{0, 2, 0.0f}, {3, 5, 1.0f}, {6, 8, 2.0f}};
    v.resize(capIntervals(v.data(), v.size(), 2));
    EXPECT_EQ(v, (std::vector<Interval>{{0, 5, 0.5f}, {6, 8, 2.0f}}));
}

TEST(CapIntervals, MergesClosestPairWithWeightedLogOdds)
{
    std::vector<Interval> v = {{0, 2, 1.0f}, {3, 4, 0.0f}, {10, 12, 2.0f}};
    v.resize(capIntervals(v.data(), v.size(), 2));
    ASSERT_EQ(v.size(), 2u);
    EXPECT_EQ(v[0].lo, 0);
    EXPECT_EQ(v[0].hi, 4);
    EXPECT_NEAR(v[0].logodds, 2.0 / 3.0, 1e-6);  // (2 cells * 1 + 1 cell * 0) / 3
    EXPECT_EQ(v[1].lo, 10);
    v.resize(capIntervals(v.data(), v.size(), 1));
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].lo, 0);
    EXPECT_EQ(v[0].hi, 12);
}

TEST(PillarUpdate, IntervalCountStaysBoundedOverThousandsOfScans)
{
    // Random scans of one pillar: many small spans at random heights, as a tree or a
    // facade seen from a moving sensor gives.
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> height(0, 400), len(1, 6), count(1, 25);
    for (const std::size_t cap : {std::size_t{8}, std::size_t{32}})
    {
        Pillar g = pillar(0.5, {});
        PillarUpdater updater(model(), cap);
        std::size_t peak = 0;
        for (int scan = 0; scan < 5000; ++scan)
        {
            std::vector<int32_t> cells;
            const int k = count(rng);
            for (int i = 0; i < k; ++i)
            {
                const int h = height(rng), l = len(rng);
                for (int c = h; c < h + l; ++c) cells.push_back(c);
            }
            std::sort(cells.begin(), cells.end());
            const std::vector<Span> spans = spansOf(cells, 0, 0);
            updater.update(g, spans.data(), spans.size());
            peak = std::max(peak, g.intervals.size());
            for (std::size_t q = 1; q < g.intervals.size(); ++q)
                ASSERT_LE(g.intervals[q - 1].hi, g.intervals[q].lo) << "overlap at scan " << scan;
        }
        EXPECT_LE(peak, cap);
        EXPECT_EQ(peak, cap) << "this workload should reach the bound";
    }
}

TEST(PillarGrid, NewPillarTakesThePriorThenOneObservation)
{
    // The paper's arithmetic (Eq. 8, 14): p_empty falls with every scan that hits the pillar.
    // With miss_needs_beam it falls only when a beam passed through the pillar, which these
    // two points do not give (test_sensor_model.cpp has that case).
    Params prm;
    prm.miss_needs_beam = false;
    PillarGrid grid(GridGeometry(), prm);
    const std::vector<float> x = {-0.5f, -0.5f}, y = {-0.5f, -0.5f}, z = {0.0f, 1.0f};
    const InsertStats st = grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    EXPECT_EQ(st.points_used, 2u);
    EXPECT_EQ(st.pillars_created, 1u);
    ASSERT_EQ(grid.pillarCount(), 1u);
    const Pillar* p = grid.findPillar({-1, -1});
    ASSERT_NE(p, nullptr);
    // Two heights 1 m apart: two intervals (gap 0.1 m, padding 0.05 m).
    ASSERT_EQ(p->intervals.size(), 2u);
    EXPECT_NEAR(grid.staticProbability(-0.5, -0.5, 0.0), 0.571428571, kTol);
    EXPECT_NEAR(grid.staticProbability(-0.5, -0.5, 0.5), 0.421052632, kTol);  // p_empty
    EXPECT_NEAR(grid.staticProbability(5.0, 5.0, 0.0), 0.5, kTol);            // unknown
    EXPECT_TRUE(grid.isStatic(-0.5, -0.5, 1.0));
    EXPECT_FALSE(grid.isStatic(-0.5, -0.5, 0.5));
}

TEST(PillarGrid, InsertionAppliesThePose)
{
    PillarGrid grid;
    const std::vector<float> x = {1.2f}, y = {0.3f}, z = {0.0f};
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    T.translation() = Eigen::Vector3d(10.0, -20.0, 2.0);
    grid.insertScan({x.data(), y.data(), z.data(), 1}, T);
    // (1.2, 0.3, 0) rotated 90 deg about z is (-0.3, 1.2, 0); then + (10, -20, 2).
    ASSERT_NE(grid.findPillar({9, -19}), nullptr);
    EXPECT_TRUE(grid.isStatic(9.7, -18.8, 2.0));
    std::vector<uint8_t> dyn;
    const ClassifyStats cs = grid.classify({x.data(), y.data(), z.data(), 1}, dyn, T);
    EXPECT_EQ(cs.static_points, 1u);
    EXPECT_EQ(dyn, std::vector<uint8_t>{0});
}

TEST(PillarGrid, NonFinitePointsAreCountedNotUsed)
{
    PillarGrid grid;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> x = {0.5f, nan, 1e30f}, y = {0.5f, 0.5f, 0.5f}, z = {0, 0, 0};
    const InsertStats st = grid.insertScan({x.data(), y.data(), z.data(), 3});
    EXPECT_EQ(st.points_used, 1u);
    EXPECT_EQ(st.points_invalid, 2u);
    EXPECT_EQ(st.points_outside_grid, 1u);  // 1e30: a finite point beyond the index range
    std::vector<uint8_t> dyn;
    const ClassifyStats cs = grid.classify({x.data(), y.data(), z.data(), 3}, dyn);
    EXPECT_EQ(cs.invalid_points, 1u);  // NaN; 1e30 is finite, lies in unknown space
    EXPECT_EQ(dyn[1], 1);
    EXPECT_EQ(dyn[0], 0);
}

TEST(PillarGrid, APointAtExactlyTheThresholdIsStatic)
{
    // P(static) = 0.5 exactly (log-odds 0) against static_threshold 0.5: kept (">=").
    PillarGrid grid;
    grid.setPillar({0, 0}, pillar(0.2, {{0, 10, 0.0f}}));
    EXPECT_TRUE(grid.isStatic(0.5, 0.5, 0.2));
    const std::vector<float> x = {0.5f, 0.5f, 7.5f}, y = {0.5f, 0.5f, 7.5f}, z = {0.2f, 0.7f, 0.2f};
    std::vector<uint8_t> dyn;
    const ClassifyStats st = grid.classify({x.data(), y.data(), z.data(), x.size()}, dyn);
    // In the interval: static; in the pillar's empty space (0.2): dynamic; in a pillar never
    // seen, the prior p_empty_init 0.5, again exactly the threshold: static.
    EXPECT_EQ(dyn, (std::vector<uint8_t>{0, 1, 0}));
    EXPECT_EQ(st.static_points, 2u);
}

TEST(PillarGrid, HeightsTwoEmptyCellsApartShareAnIntervalThreeApartDoNot)
{
    // merge_gap 0.1 m at 0.05 m cells: up to 2 empty cells are bridged (no padding here).
    Params prm = Params::paper();
    prm.interval_padding = 0.0;
    for (const auto& [z_top, intervals] : {std::pair{0.16f, 1u}, std::pair{0.21f, 2u}})
    {
        PillarGrid grid(GridGeometry(), prm);
        const std::vector<float> x = {0.5f, 0.5f}, y = {0.5f, 0.5f}, z = {0.01f, z_top};
        grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        EXPECT_EQ(grid.findPillar({0, 0})->intervals.size(), intervals) << "top at " << z_top;
    }
}

TEST(PillarGrid, SetPillarRejectsBrokenInvariants)
{
    PillarGrid grid;
    EXPECT_THROW(grid.setPillar({0, 0}, pillar(0.5, {iv(5, 5, 0.5)})), std::invalid_argument);
    EXPECT_THROW(grid.setPillar({0, 0}, pillar(0.5, {iv(0, 5, 0.5), iv(4, 8, 0.5)})),
                 std::invalid_argument);
    EXPECT_NO_THROW(grid.setPillar({0, 0}, pillar(0.5, {iv(0, 5, 0.5), iv(5, 8, 0.6)})));
    EXPECT_EQ(grid.intervalCount(), 2u);
}

TEST(PillarGrid, SetParamsKeepsThePillarsAndRejectsBadValues)
{
    GridGeometry geo;
    geo.pillar_size = 2.0;
    PillarGrid grid(geo);
    const std::vector<float> x = {0.5f}, y = {0.5f}, z = {0.0f};
    grid.insertScan({x.data(), y.data(), z.data(), 1});
    Params p = grid.params();
    p.static_threshold = 0.6;
    grid.setParams(p);
    EXPECT_EQ(grid.pillarCount(), 1u);
    EXPECT_FALSE(grid.isStatic(0.5, 0.5, 0.0));  // 0.571 < 0.6 now
    p.alpha = 2.0;
    EXPECT_THROW(grid.setParams(p), std::invalid_argument);
    EXPECT_EQ(grid.params().alpha, Params().alpha);  // unchanged by the rejected call
    EXPECT_EQ(grid.geometry(), geo);
    geo.pillar_size = 0;
    EXPECT_THROW(PillarGrid{geo}, std::invalid_argument);
    // Cells finer than a micrometre: a subnormal height cell (a map file fuzz_map made) would
    // make every height NaN.
    geo.pillar_size = 2.0;
    geo.height_resolution = 6.5e-316;
    EXPECT_THROW(PillarGrid{geo}, std::invalid_argument);
    geo.height_resolution = 0.5 * GridGeometry::kMinCell;
    EXPECT_THROW(PillarGrid{geo}, std::invalid_argument);
    geo.height_resolution = GridGeometry::kMinCell;
    EXPECT_NO_THROW(PillarGrid{geo});
    geo.pillar_size = 1e-300;
    EXPECT_THROW(PillarGrid{geo}, std::invalid_argument);
}

// ---- Beyond the paper (Params::high_height_preservation, unseen_height_prior) ----

LogOddsModel oursModel()
{
    return LogOddsModel::fromParams(Params());  // defaults: both rules on
}

TEST(HighHeightPreservation, IntervalsAboveTheCeilingKeepTheirProbability)
{
    // g: ground [0,5) and a wall top [40,50), both 0.7. The scan sees only [0,5) and could not
    // see above cell 30: the wall top is unknown to it and keeps 0.7.
    Pillar a = pillar(0.5, {iv(0, 5, 0.7), iv(40, 50, 0.7)});
    Pillar b = a;
    PillarUpdater ours(oursModel(), 1000), paper(model(), 1000);
    const std::vector<Span> t{{0, 5}};
    ours.update(a, t.data(), t.size(), /*ceiling=*/30);
    ASSERT_EQ(a.intervals.size(), 2u);
    EXPECT_NEAR(probOf(a.intervals[1]), 0.7, kTol);
    // Without the rule (the paper), it is "expected but not seen": 0.28 / (0.28 + 0.165).
    paper.update(b, t.data(), t.size(), /*ceiling=*/30);
    EXPECT_NEAR(probOf(b.intervals[1]), 0.629213483, kTol);
    // An interval that straddles the ceiling is partly visible: it gets the miss.
    Pillar c = pillar(0.5, {iv(0, 5, 0.7), iv(25, 35, 0.7)});
    ours.update(c, t.data(), t.size(), /*ceiling=*/30);
    EXPECT_NEAR(probOf(c.intervals[1]), 0.629213483, kTol);
}

TEST(HighHeightPreservation, AnIntervalStartingAtTheCeilingIsKeptOneCellLowerIsNot)
{
    PillarUpdater ours(oursModel(), 1000);
    const std::vector<Span> t{{0, 5}};
    Pillar at = pillar(0.5, {iv(0, 5, 0.7), iv(30, 40, 0.7)});
    ours.update(at, t.data(), t.size(), /*ceiling=*/30);
    EXPECT_NEAR(probOf(at.intervals[1]), 0.7, kTol);  // [30, 40) is all out of view
    Pillar below = pillar(0.5, {iv(0, 5, 0.7), iv(29, 40, 0.7)});
    ours.update(below, t.data(), t.size(), /*ceiling=*/30);
    ASSERT_GE(below.intervals.size(), 2u);
    EXPECT_NEAR(probOf(below.intervals[1]), 0.629213483, kTol);  // cell 29 was in view
}

TEST(UnseenHeightPrior, AnIntervalStartingAtSeenTopIsUnseen)
{
    // seen_top is exclusive: cell 20 was never in view, so a new interval from it starts from
    // p_empty_init (0.5 -> 0.571), not from the pillar's p_empty (0.3 -> 0.364).
    Pillar g = pillar(0.3, {});
    g.seen_top = 20;
    PillarUpdater ours(oursModel(), 1000);
    const std::vector<Span> at{{20, 25}};
    ours.update(g, at.data(), at.size(), /*ceiling=*/40);
    EXPECT_NEAR(probOf(g.intervals[0]), 0.571428571, kTol);
    Pillar h = pillar(0.3, {});
    h.seen_top = 20;
    const std::vector<Span> below{{19, 25}};  // starts in view: p_empty
    ours.update(h, below.data(), below.size(), /*ceiling=*/40);
    EXPECT_NEAR(probOf(h.intervals[0]), 0.363636364, kTol);
}

TEST(UnseenHeightPrior, NewIntervalsAboveSeenTopStartFromPEmptyInit)
{
    Pillar g = pillar(0.3, {});
    g.seen_top = 20;
    PillarUpdater ours(oursModel(), 1000);
    const std::vector<Span> t{{10, 15}, {25, 30}};
    ours.update(g, t.data(), t.size(), /*ceiling=*/40);
    ASSERT_EQ(g.intervals.size(), 2u);
    // Below seen_top: prior p_empty = 0.3 (Eq. 14): 0.18 / 0.495.
    EXPECT_NEAR(probOf(g.intervals[0]), 0.363636364, kTol);
    // Above: never in view, prior p_empty_init = 0.5: 0.3 / 0.525.
    EXPECT_NEAR(probOf(g.intervals[1]), 0.571428571, kTol);
    // The scan could see up to cell 40: seen_top grows, and never shrinks.
    EXPECT_EQ(g.seen_top, 40);
    ours.update(g, t.data(), t.size(), /*ceiling=*/35);
    EXPECT_EQ(g.seen_top, 40);
}

TEST(ParamsPaper, TurnsOffEveryAddition)
{
    const Params p = Params::paper();
    EXPECT_FALSE(p.high_height_preservation);
    EXPECT_FALSE(p.unseen_height_prior);
    EXPECT_EQ(p.beam_spacing_deg, 0.0);
    EXPECT_FALSE(p.sensor_from_scans);
    EXPECT_FALSE(p.miss_needs_beam);
    EXPECT_FALSE(p.online);  // the paper cleans a sequence offline
    Params q = p;
    q.high_height_preservation = q.unseen_height_prior = q.sensor_from_scans = true;
    q.miss_needs_beam = q.online = true;
    q.beam_spacing_deg = Params().beam_spacing_deg;
    EXPECT_EQ(q, Params());  // and nothing else differs from the defaults
}

TEST(RangeAdaptiveIntervals, FarPillarsMergeHeightsOneBeamApart)
{
    // Sensor at the origin; a pillar 25.5 m away holds heights in cells 0 and 4 (three empty
    // cells, 0.15 m, between them). One beam of 0.44 deg spans 25.5 * tan(0.44 deg) = 0.196 m
    // there: merged into one interval with range-adaptive intervals; two intervals with the
    // paper's fixed 0.1 m gap and 0.05 m padding ([-1, 2) and [3, 6)).
    const std::vector<float> x{25.3f, 25.3f, 1.0f}, y{0.5f, 0.5f, 0.0f}, z{0.01f, 0.22f, 0.0f};
    Params ours;
    ours.high_height_preservation = false;
    ours.unseen_height_prior = false;
    Params paper = Params::paper();
    for (const Params& prm : {ours, paper})
    {
        PillarGrid grid(GridGeometry(), prm);
        grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        const Pillar* p = grid.findPillar({25, 0});
        ASSERT_NE(p, nullptr);
        EXPECT_EQ(p->intervals.size(), prm.beam_spacing_deg > 0 ? 1u : 2u);
        // A pillar 1 m away is unaffected: one interval either way.
        EXPECT_EQ(grid.findPillar({1, 0})->intervals.size(), 1u);
    }
}

TEST(HighHeightPreservation, GridMeasuresTheTopBeamFromTheScan)
{
    // Scan 1, from 30 m away: a wall 3 m high, seen whole. Then scans from 5 m away, whose top
    // beam (measured from their own points) cannot see the wall above about 0.46 m. Every
    // miss counts (Eq. 13 as the paper has it): the few points here pass no beam through the
    // wall's top, so with miss_needs_beam it would be kept either way.
    Params prm;
    prm.miss_needs_beam = false;
    PillarGrid grid(GridGeometry(), prm);
    std::vector<float> x, y, z;
    for (int k = 0; k <= 30; ++k)
    {
        x.push_back(30.5f);
        y.push_back(0.5f);
        z.push_back(0.1f * float(k));  // 0 .. 3 m
    }
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    // Scan 2: sensor at x = 25.5, 5 m from the wall; sees the wall up to 0.5 m, and far away
    // (x = 80) a point 5 m up: top slope 5 / 54.5, ceiling at the wall 5 * 5 / 54.5 = 0.46 m.
    std::vector<float> x2{5.0f, 5.0f, 5.0f, 54.5f}, y2{0.0f, 0.0f, 0.0f, 0.0f},
        z2{0.0f, 0.2f, 0.4f, 5.0f};
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(25.5, 0.5, 0.0);
    for (int s = 0; s < 5; ++s) grid.insertScan({x2.data(), y2.data(), z2.data(), x2.size()}, T);
    EXPECT_TRUE(grid.isStatic(30.5, 0.5, 2.5)) << "the wall top, out of view, was kept";
    Params paper = prm;
    paper.high_height_preservation = false;
    PillarGrid g2(GridGeometry(), paper);
    g2.insertScan({x.data(), y.data(), z.data(), x.size()});
    for (int s = 0; s < 5; ++s) g2.insertScan({x2.data(), y2.data(), z2.data(), x2.size()}, T);
    EXPECT_FALSE(g2.isStatic(30.5, 0.5, 2.5)) << "without HHP the wall top is lost";
}

namespace
{
/** Points at `range` from the origin in the direction of (x, y), at elevations covering the
 *  heights [z0, z1] at horizontal distance hypot(x, y), every 0.1 degree. */
void beamsToward(double x, double y, double z0, double z1, double range, std::vector<float>& px,
                 std::vector<float>& py, std::vector<float>& pz)
{
    const double d = std::hypot(x, y), az = std::atan2(y, x);
    const double e0 = std::atan2(z0, d), e1 = std::atan2(z1, d);
    for (double e = e0; e <= e1; e += 0.1 * M_PI / 180.0)
    {
        px.push_back(float(range * std::cos(e) * std::cos(az)));
        py.push_back(float(range * std::cos(e) * std::sin(az)));
        pz.push_back(float(range * std::sin(e)));
    }
}

/** Beams toward the car's pillar between heights z0 and z1, returning at `range`. */
struct Beams
{
    double z0, z1, range;
};

/** A "car" in pillar (20, 0) seen once; then one scan whose beams toward it return as
 *  `beams` say. Is the car still static? */
bool carStaticAfter(double see_through_range, const std::vector<Beams>& beams);

/** carStaticAfter() with every beam toward the car returning at each of `returns`. */
bool carStaticAfterReturns(double see_through_range, const std::vector<double>& returns)
{
    std::vector<Beams> beams;
    for (double r : returns) beams.push_back({-1.1, -0.3, r});
    return carStaticAfter(see_through_range, beams);
}

bool carStaticAfter(double see_through_range, const std::vector<Beams>& beams)
{
    Params prm;
    prm.see_through_range = see_through_range;
    PillarGrid grid(GridGeometry(), prm);
    std::vector<float> x, y, z;
    for (double h = -1.2; h <= -0.2; h += 0.05)
    {
        x.push_back(20.5f);
        y.push_back(0.5f);
        z.push_back(float(h));
    }
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    EXPECT_TRUE(grid.isStatic(20.5, 0.5, -0.7));
    x.clear(), y.clear(), z.clear();
    for (const Beams& b : beams) beamsToward(20.5, 0.5, b.z0, b.z1, b.range, x, y, z);
    const InsertStats st = grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    EXPECT_EQ(grid.findPillar({20, 0})->intervals.size(), 1u);
    EXPECT_GT(st.pillars_created, 0u);  // the returns landed in other pillars
    return grid.isStatic(20.5, 0.5, -0.7);
}
}  // namespace

TEST(PassedCells, RecordsTheCellsBeamsCrossedInAWindowFromTheLowest)
{
    PassedCells p;
    EXPECT_FALSE(p.any(-1000, 1000));  // nothing recorded yet
    p.add(10, 12);
    EXPECT_TRUE(p.any(11, 20));
    EXPECT_FALSE(p.any(12, 20));  // exclusive end
    EXPECT_FALSE(p.any(0, 10));
    // A lower cell moves the window down; what was recorded stays.
    p.add(-5, -4);
    EXPECT_EQ(p.base, -5);
    EXPECT_TRUE(p.any(-5, -4));
    EXPECT_TRUE(p.any(10, 11));
    EXPECT_FALSE(p.any(-4, 10));
    // Above the window (kCells from the lowest): not recorded.
    p.add(-5 + PassedCells::kCells, -5 + PassedCells::kCells + 3);
    EXPECT_FALSE(p.any(-5 + PassedCells::kCells, 1000));
    p.add(-5 + PassedCells::kCells - 1, -5 + PassedCells::kCells + 3);  // its last cell is in
    EXPECT_TRUE(p.any(-5 + PassedCells::kCells - 1, -5 + PassedCells::kCells));
    // Moving down by more than the window drops everything above it.
    p.add(-500, -499);
    EXPECT_TRUE(p.any(-500, -499));
    EXPECT_FALSE(p.any(-499, 1000));
    // The lowest cell of all is kNone's value: a record from it starts one cell above, and
    // stays a record (a map that saves it loads again).
    PassedCells q;
    q.add(PassedCells::kNone, PassedCells::kNone + 3);
    EXPECT_EQ(q.base, PassedCells::kNone + 1);
    EXPECT_TRUE(q.any(PassedCells::kNone, PassedCells::kNone + 3));
    q.add(PassedCells::kNone, PassedCells::kNone + 1);  // nothing left of it
    EXPECT_EQ(q.base, PassedCells::kNone + 1);
}

// p_empty is evidence only of the heights beams were seen passing through (with
// miss_needs_beam): a pillar whose ground was seen under beams that passed 1.5-2 m above it,
// scan after scan, has a low p_empty; a low wall then seen at 0.4-0.7 m, where no beam passed
// (a sparse LiDAR's rings pass above it, something hid it before), starts from p_empty_init
// and is kept; something seen where the beams passed starts from the low p_empty.
TEST(EmptyPrior, ANewIntervalStartsFromPEmptyOnlyWhereBeamsWereSeenPassing)
{
    auto staticAfter = [](bool gate, double object_z)
    {
        Params prm;
        prm.miss_needs_beam = gate;
        prm.sensor_from_scans = false;
        prm.p_empty_init = 0.42;  // a second sighting wanted, as offline
        PillarGrid grid(GridGeometry(), prm);
        // The sensor 1.7 m above the ground; the pillar (20, 0) ahead.
        const double ground = -1.7;
        for (int s = 0; s < 6; ++s)
        {
            std::vector<float> x{20.5f}, y{0.5f}, z{float(ground)};
            beamsToward(20.5, 0.5, ground + 1.5, ground + 2.0, 40.0, x, y, z);
            grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        }
        EXPECT_LT(grid.findPillar({20, 0})->logodds_empty, logit(0.3)) << "seen empty";
        // Seen twice (p_empty_init 0.42 wants a second sighting).
        std::vector<float> x{20.5f, 20.5f}, y{0.5f, 0.5f}, z{float(ground), float(object_z)};
        for (int s = 0; s < 2; ++s) grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        EXPECT_TRUE(grid.isStatic(20.5, 0.5, ground));
        return grid.isStatic(20.5, 0.5, object_z);
    };
    EXPECT_TRUE(staticAfter(true, -1.7 + 0.55)) << "where no beam passed: p_empty_init";
    EXPECT_FALSE(staticAfter(true, -1.7 + 1.75)) << "where the beams passed: p_empty";
    // The paper's Eq. 14 (no gate): the pillar's p_empty at every height.
    EXPECT_FALSE(staticAfter(false, -1.7 + 0.55));
}

// A facade met at grazing incidence cuts pillar (20, -9) along its back strip (y = -8.9, the
// sensor at the origin, 23 degrees off it): beams pass the pillar's free part and land on the
// facade just beyond it. They show that part empty, not the strip the facade stands in, which the
// scan did not hit at those heights (a non-repetitive pattern's beams went elsewhere; a ring would
// have gone on to hit it): the facade seen there later starts from p_empty_init, not from the
// pillar's p_empty, and is kept. Beams that land on a surface facing them beyond the pillar (a
// car's back) are evidence: what then appears in the pillar at those heights starts from p_empty.
TEST(EmptyPrior, BeamsThatMetASurfaceRunningIntoThePillarShowOnlyItsFreePartEmpty)
{
    const double ground = -1.7, z0 = -1.0, z1 = -0.3;  // the heights the beams cross
    // Returns at (x, y) on rows of a 64-beam-like sensor (0.44 degrees apart) within [z0, z1].
    auto rows = [&](double x, double y, std::vector<float>& px, std::vector<float>& py,
                    std::vector<float>& pz)
    {
        const double d = std::hypot(x, y);
        for (int k = -40; k <= 0; ++k)
        {
            const double zk = d * std::tan(k * 0.44 * M_PI / 180.0);
            if (zk < z0 || zk > z1) continue;
            px.push_back(float(x)), py.push_back(float(y)), pz.push_back(float(zk));
        }
    };
    // Whether what the last two scans saw in the pillar at z0..z1 is static, after three
    // scans whose beams passed it and landed on a facade along y = -8.9 (`facade`), or on a
    // surface facing them 1.3 m behind the pillar's centre (about as near as the facade).
    auto staticAfter = [&](bool facade)
    {
        Params prm;
        prm.sensor_from_scans = false;
        prm.p_empty_init = 0.42;  // a second sighting wanted, as offline
        PillarGrid grid(GridGeometry(), prm);
        grid.setSensorModel(SensorModel::fromPattern(-30.0, 15.0, 0.44, 360.0));  // no rings
        const Eigen::Vector2d centre(20.5, -8.5), dir = centre.normalized();
        std::vector<float> ax, ay, az;
        if (facade)
            for (double fx = 21.0; fx < 30.0; fx += 0.05) rows(fx, -8.9, ax, ay, az);
        else
            for (double t = -1.5; t <= 1.5; t += 0.02)
            {
                const Eigen::Vector2d p =
                    (centre.norm() + 1.3) * dir + t * Eigen::Vector2d(-dir.y(), dir.x());
                rows(p.x(), p.y(), ax, ay, az);
            }
        // The pillar's ground, so that the scan updates the pillar.
        for (double gx = 20.1; gx < 21.0; gx += 0.2)
            ax.push_back(float(gx)), ay.push_back(-8.5f), az.push_back(float(ground));
        for (int s = 0; s < 3; ++s) grid.insertScan({ax.data(), ay.data(), az.data(), ax.size()});
        EXPECT_LT(grid.findPillar({20, -9})->logodds_empty, logit(0.3)) << "seen empty";
        // Then twice: the same, and the pillar's strip of the facade (or something in the
        // pillar) at those heights.
        std::vector<float> bx = ax, by = ay, bz = az;
        for (double fx = 20.05; fx < 21.0; fx += 0.05) rows(fx, facade ? -8.9 : -8.5, bx, by, bz);
        for (int s = 0; s < 2; ++s) grid.insertScan({bx.data(), by.data(), bz.data(), bx.size()});
        return grid.isStatic(20.5, facade ? -8.9 : -8.5, 0.5 * (z0 + z1));
    };
    EXPECT_TRUE(staticAfter(true)) << "the facade's strip of the pillar: p_empty_init";
    EXPECT_FALSE(staticAfter(false)) << "where beams were seen passing to a surface facing them";
}

TEST(SeeThroughMisses, BeamsThatPassedThroughAPillarEmptyIt)
{
    // Off (the paper): a pillar no return falls in is untouched.
    EXPECT_TRUE(carStaticAfterReturns(0.0, {40.0}));
    // On: the beams returned 20 m beyond the car's pillar, so it is free now.
    EXPECT_FALSE(carStaticAfterReturns(40.0, {40.0}));
    // A return near the pillar (within the 2.5 m margin) vetoes: something is there.
    EXPECT_TRUE(carStaticAfterReturns(40.0, {40.0, 22.0}));
    // Returns in front of it (occlusion) say nothing about it.
    EXPECT_TRUE(carStaticAfterReturns(40.0, {10.0}));
    // Beyond see_through_range the pillar is not considered.
    EXPECT_TRUE(carStaticAfterReturns(15.0, {40.0}));
}

TEST(SeeThroughMisses, ABeamThroughAnIntervalsPaddingEmptiesOnlyTheHeightsItCrossed)
{
    // A sparse LiDAR (beams 2 degrees apart): at 20.5 m, ground hit by one beam becomes an
    // interval padded by half the 0.72 m gap between beams, above and below. A beam of the
    // next scan that passes 0.25 m above the ground (to land farther on) crosses that padding,
    // not the ground: it shows only the heights it crossed empty.
    Params prm;
    prm.sensor_from_scans = false;
    prm.beam_spacing_deg = 2.0;
    prm.see_through_range = 40.0;
    PillarGrid grid(GridGeometry(), prm);
    std::vector<float> x, y, z;
    for (double dy = 0.05; dy < 1.0; dy += 0.1)
    {
        x.push_back(20.5f);
        y.push_back(float(dy));
        z.push_back(-1.7f);
    }
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    const Pillar& ground = *grid.findPillar({20, 0});
    ASSERT_EQ(ground.intervals.size(), 1u);
    EXPECT_GT(ground.intervals[0].hi * 0.05, -1.7 + 0.3) << "padded by the beams' gap";
    x.clear(), y.clear(), z.clear();
    beamsToward(20.5, 0.5, -1.45, -1.45, 40.0, x, y, z);
    ASSERT_EQ(x.size(), 1u);
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    EXPECT_TRUE(grid.isStatic(20.5, 0.5, -1.7)) << "the ground, which the beam did not reach";
    EXPECT_FALSE(grid.isStatic(20.5, 0.5, -1.45)) << "the heights the beam crossed";
    EXPECT_TRUE(grid.isStatic(20.5, 0.5, -1.55)) << "padding the beam did not cross";
}

namespace
{
/** Pillar (20, 0) of a sparse LiDAR's map (rings 2 degrees apart: padding 0.36 m at 20.5 m)
 *  holding `intervals`; then one scan of a beam at height `beam_z` at the pillar, returning
 *  40 m away (the pillar is not hit: a see-through miss). Is height `z` still static? The
 *  ground rule (Params::ground_max_slope_deg) takes ground up to `ground_slope_deg` steep. */
bool staticAfterSeeThrough(std::vector<Interval> intervals, double beam_z, double z,
                           double ground_slope_deg = 0.0)
{
    Params prm;
    prm.sensor_from_scans = false;
    prm.see_through_range = 40.0;
    prm.ground_max_slope_deg = ground_slope_deg;
    PillarGrid grid(GridGeometry(), prm);
    std::vector<double> rings;
    for (int e = -16; e <= 16; e += 2) rings.push_back(e);
    grid.setSensorModel(SensorModel::fromBeams(rings, 0.2));
    grid.setPillar({20, 0}, pillar(0.3, std::move(intervals)));
    std::vector<float> x, y, z_;
    beamsToward(20.5, 0.5, beam_z, beam_z, 40.0, x, y, z_);
    EXPECT_EQ(x.size(), 1u);
    grid.insertScan({x.data(), y.data(), z_.data(), x.size()});
    return grid.isStatic(20.5, 0.5, z);
}
}  // namespace

TEST(SeeThroughMisses, APaddingSliverUnderTheGroundLeavesTheGroundAFloor)
{
    // Ground seen at -1.75..-1.65 m (cells -35..-33) padded by 8 cells: [-43, -25). A later
    // scan, whose ground there lay a cell lower, added a sliver of padding under it,
    // [-44, -43). A beam passing 0.25 m above the ground (cell -29) crosses its padding.
    const std::vector<Interval> ground{iv(-43, -25, 0.56)};
    const std::vector<Interval> sliver_under{iv(-44, -43, 0.49), iv(-43, -25, 0.56)};
    EXPECT_TRUE(staticAfterSeeThrough(ground, -1.45, -1.7));
    EXPECT_FALSE(staticAfterSeeThrough(ground, -1.45, -1.45)) << "the heights it crossed";
    // The sliver (seen once, no wider than the padding) and the ground touch, below the
    // sensor: one floor, which the beam passed over, not through (the ground itself would be
    // an object, all of it gone, otherwise).
    EXPECT_TRUE(staticAfterSeeThrough(sliver_under, -1.45, -1.7));
    EXPECT_FALSE(staticAfterSeeThrough(sliver_under, -1.45, -1.45));
    // Seen twice, or wider than the padding, the lowest piece is content of its own (a
    // walker's feet, a car's sill): what stands on it is an object.
    EXPECT_FALSE(staticAfterSeeThrough({iv(-44, -43, 0.6), iv(-43, -25, 0.56)}, -1.45, -1.7));
    EXPECT_FALSE(staticAfterSeeThrough({iv(-60, -43, 0.49), iv(-43, -25, 0.56)}, -1.45, -1.7));
    // A beam through what was seen of the floor shows it gone, sliver and all.
    EXPECT_FALSE(staticAfterSeeThrough(sliver_under, -1.7, -1.7));
    EXPECT_FALSE(staticAfterSeeThrough(sliver_under, -1.7, -2.18));
    // Above the sensor two touching intervals are not one floor under the beams: the upper
    // one is an object, gone when a beam passes through any part of it.
    const std::vector<Interval> above{iv(2, 3, 0.49), iv(3, 21, 0.56)};
    EXPECT_TRUE(staticAfterSeeThrough(above, 1.6, 0.6)) << "a beam above it, through nothing";
    EXPECT_FALSE(staticAfterSeeThrough(above, 0.3, 0.6));
}

TEST(SeeThroughMisses, TheGroundSeenAgainALittleHigherStaysPartOfTheFloor)
{
    // Ground seen at -1.70..-1.65 m (cell -34) padded by 8 cells, [-42, -25), and seen again
    // by other scans: a cell higher (-1.65..-1.60 m, in the padding above it) and a little
    // lower, so the pieces differ in log-odds. A beam passing 0.25 m above the ground (cell
    // -29) crosses the upper padding: it empties the heights it crossed, not the ground seen
    // a cell higher in the same piece.
    const std::vector<Interval> seen_again{iv(-42, -35, 0.56), iv(-35, -33, 0.64),
                                           iv(-33, -25, 0.56)};
    EXPECT_TRUE(staticAfterSeeThrough(seen_again, -1.45, -1.63)) << "the ground seen higher";
    EXPECT_TRUE(staticAfterSeeThrough(seen_again, -1.45, -1.68)) << "the ground";
    EXPECT_FALSE(staticAfterSeeThrough(seen_again, -1.45, -1.45)) << "the heights it crossed";
    // A beam through the ground itself shows all of the floor gone.
    EXPECT_FALSE(staticAfterSeeThrough(seen_again, -1.68, -1.63));
    // What stands on the ground reaches above one sighting of it: an object, all of it gone
    // when a beam passes through any part of it (a walker's legs, a car's sill).
    const std::vector<Interval> standing{iv(-42, -35, 0.56), iv(-35, -33, 0.64), iv(-33, 0, 0.56)};
    EXPECT_FALSE(staticAfterSeeThrough(standing, -1.45, -1.63));
    EXPECT_TRUE(staticAfterSeeThrough(standing, -1.45, -1.68)) << "the ground under it";
}

TEST(SeeThroughMisses, OneSightingOfSlopedGroundSpansTheSlopeAcrossThePillar)
{
    // A ring crossing the pillar saw ground rising across it, -1.80..-1.70 m (cells -36..-35),
    // padded by 8 cells: [-44, -26). Other scans saw it a little higher and lower, so it is in
    // pieces; the top one, [-34, -26), was hit twice, like the ground under it. A beam 0.2 m
    // above the ground (cell -31) crosses it.
    const std::vector<Interval> ground{iv(-44, -41, 0.49), iv(-41, -36, 0.56), iv(-36, -34, 0.64),
                                       iv(-34, -26, 0.56)};
    // Ground as steep as 5 degrees rises 0.12 m (3 cells) across the pillar's diagonal: one
    // sighting of it spans up to 2 x 8 + 1 + 3 cells, so the top piece is still the floor, and
    // the beam empties only the heights it crossed, not the ground seen at -1.70 m.
    EXPECT_TRUE(staticAfterSeeThrough(ground, -1.55, -1.69, 5.0));
    EXPECT_FALSE(staticAfterSeeThrough(ground, -1.55, -1.55, 5.0)) << "the heights it crossed";
    // Without the ground rule a sighting is 2 x 8 + 1 cells from the floor's bottom: the top
    // piece reaches past it, an object, emptied whole.
    EXPECT_FALSE(staticAfterSeeThrough(ground, -1.55, -1.69));
    // What stands on the ground reaches above a sighting of it even on a slope.
    const std::vector<Interval> standing{iv(-44, -41, 0.49), iv(-41, -36, 0.56), iv(-36, -34, 0.64),
                                         iv(-34, 0, 0.56)};
    EXPECT_FALSE(staticAfterSeeThrough(standing, -1.55, -1.69, 5.0));
    EXPECT_TRUE(staticAfterSeeThrough(standing, -1.55, -1.75, 5.0)) << "the ground under it";
    // The same pieces with more touching above them (a walker whose feet no ring saw, seen
    // from the knees up and split by other scans): the slope does not stretch the floor into
    // the walker, whose piece through the beam is an object.
    std::vector<Interval> walker = ground;
    walker.push_back(iv(-26, 0, 0.56));
    EXPECT_FALSE(staticAfterSeeThrough(walker, -1.55, -1.69, 5.0));
}

namespace
{
/** A wall from -1.5 m to 1.5 m in pillar (20, 0), hit by a dense scan, under a sparse model
 *  (beams 2 degrees apart: padded by 0.36 m at 20.5 m); then one scan of beams at `heights`
 *  (at the pillar), each returning 40 m away. Is height `z` of the wall still static? */
bool wallStaticAfter(const std::vector<double>& heights, double z)
{
    Params prm;
    prm.sensor_from_scans = false;
    prm.beam_spacing_deg = 2.0;
    prm.see_through_range = 40.0;
    PillarGrid grid(GridGeometry(), prm);
    std::vector<float> x, y, z_;
    for (double h = -1.5; h <= 1.5; h += 0.05)
    {
        x.push_back(20.5f);
        y.push_back(0.5f);
        z_.push_back(float(h));
    }
    grid.insertScan({x.data(), y.data(), z_.data(), x.size()});
    EXPECT_EQ(grid.findPillar({20, 0})->intervals.size(), 1u);
    x.clear(), y.clear(), z_.clear();
    for (const double h : heights) beamsToward(20.5, 0.5, h, h, 40.0, x, y, z_);
    grid.insertScan({x.data(), y.data(), z_.data(), x.size()});
    return grid.isStatic(20.5, 0.5, z);
}
}  // namespace

TEST(SeeThroughMisses, NeighbouringBeamsThatBothPassedEmptyTheHeightsBetweenThem)
{
    // Beams 0.2 m apart (0.56 degrees: neighbours for a 2-degree sensor) through the padding
    // above the wall's top: what lies between them is empty too. One of them alone shows
    // only its own heights.
    EXPECT_FALSE(wallStaticAfter({1.6, 1.8}, 1.7));
    EXPECT_TRUE(wallStaticAfter({1.6}, 1.7));
    EXPECT_FALSE(wallStaticAfter({1.6}, 1.6));
    // A beam through what was seen of the wall (its core, inside the padding) shows all of
    // it gone: one object, seen through.
    EXPECT_FALSE(wallStaticAfter({0.0}, -1.2));
    EXPECT_TRUE(wallStaticAfter({1.6}, 1.2)) << "the padding's beam says nothing of the wall";
}

TEST(SeeThroughMisses, AReturnNearThePillarVetoesBeamsThatPassedThroughIt)
{
    // The lower beams pass through (return 20 m beyond); the upper ones return just behind the
    // pillar, within the margin: something is there, so no miss.
    const Beams through{-1.1, -0.75, 40.0}, near{-0.6, -0.3, 22.0};
    EXPECT_FALSE(carStaticAfter(40.0, std::vector<Beams>{through}));
    EXPECT_TRUE(carStaticAfter(40.0, std::vector<Beams>{through, near}));
    // Just beyond the margin (22.0 + 2.5 behind the axis at 20.5 m), the same return counts
    // as passing through.
    EXPECT_FALSE(carStaticAfter(40.0, std::vector<Beams>{through, {-0.6, -0.3, 23.5}}));
}

namespace
{
/** Rings every degree from -10 to +10 degrees at a 0.5-degree step, as a sensor model. */
SensorModel ringsEveryDegree()
{
    std::vector<double> el;
    for (int e = -10; e <= 10; ++e) el.push_back(e);
    return SensorModel::fromBeams(el, 0.5);
}

/** Points of the rings of `model` at azimuth `az_deg` whose beams reach heights [z0, z1] at
 *  horizontal distance `d`, each `range` m away (or at the point itself when range is 0). */
void ringsToward(const SensorModel& model, double az_deg, double d, double z0, double z1,
                 double range, std::vector<float>& x, std::vector<float>& y, std::vector<float>& z)
{
    const double az = az_deg * M_PI / 180.0;
    for (const double e_deg : model.beam_elevations_deg)
    {
        const double e = e_deg * M_PI / 180.0, h = d * std::tan(e);
        if (h < z0 || h > z1) continue;
        const double r = range > 0 ? range : std::hypot(d, h);
        x.push_back(float(r * std::cos(e) * std::cos(az)));
        y.push_back(float(r * std::cos(e) * std::sin(az)));
        z.push_back(float(r * std::sin(e)));
    }
}
}  // namespace

// A car on a road that climbs above the sensor, 20 m away, seen by the rings above the horizon;
// when it has gone, those rings return nothing in its direction (the sky), while they return
// from a far hill a degree aside: they were fired. Seen once, the car is taken for gone; seen
// twice, it is kept (a surface seen twice that returns nothing now may be glass, or dark).
TEST(SeeThroughMisses, RingsThatReturnedNothingWhereAHeightSeenOnceWasShowItGone)
{
    const SensorModel model = ringsEveryDegree();
    for (const int sightings : {1, 2})
    {
        SCOPED_TRACE(sightings);
        Params prm;
        prm.see_through_range = 40.0;
        PillarGrid grid(GridGeometry(), prm);
        grid.setSensorModel(model);
        std::vector<float> x, y, z;
        // The car, in pillar (20, 0) at azimuth 1.4 degrees: heights 0.2 to 1.2 m above the
        // sensor.
        ringsToward(model, 1.4, 20.5, 0.2, 1.2, 0.0, x, y, z);
        ASSERT_GE(x.size(), 3u);
        for (int s = 0; s < sightings; ++s)
            grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        ASSERT_TRUE(grid.isStatic(20.5, 0.5, 0.7));
        // Gone: the same rings return from a hill 200 m away a degree aside, and nothing toward
        // the car's pillar.
        x.clear(), y.clear(), z.clear();
        ringsToward(model, 2.6, 20.5, 0.2, 1.2, 200.0, x, y, z);
        grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        EXPECT_EQ(grid.isStatic(20.5, 0.5, 0.7), sightings == 2);
    }
    // Without rings (a non-repetitive pattern) a cell without a return may have had no beam:
    // nothing is taken from it.
    Params prm;
    prm.see_through_range = 40.0;
    PillarGrid grid(GridGeometry(), prm);
    grid.setSensorModel(SensorModel::fromPattern(-10, 10, 1.0, 360));
    std::vector<float> x, y, z;
    ringsToward(model, 1.4, 20.5, 0.2, 1.2, 0.0, x, y, z);
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    x.clear(), y.clear(), z.clear();
    ringsToward(model, 2.6, 20.5, 0.2, 1.2, 200.0, x, y, z);
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    EXPECT_TRUE(grid.isStatic(20.5, 0.5, 0.7));
}

namespace
{
constexpr double kSensorZ = 1.7410;  // 19.9 m * tan(5 degrees)

/** Rings every 2 degrees from -15 to +15 (a 16-ring LiDAR). */
std::vector<double> sixteenRings()
{
    std::vector<double> el;
    for (int e = -15; e <= 15; e += 2) el.push_back(e);
    return el;
}

/** One scan of a LiDAR with rings at elevations `el` (degrees; by default sixteenRings()), 0.2
 *  degrees apart in azimuth, over azimuths -10 to +10 degrees, kSensorZ above flat ground (ring
 *  -5 lands at 19.9 m): `reach(a, t)` is the horizontal distance at which the beam of azimuth
 *  step `a` (of 0.2 degrees) and elevation tangent `t` returns, infinity for none. Is each of
 *  `probes` static once the scan is inserted (offline p_empty_init) with ground_max_slope_deg
 *  `slope`? */
template <class Reach>
std::vector<bool> staticAfterOneRingScan(double slope, const Reach& reach,
                                         const std::vector<Eigen::Vector3d>& probes,
                                         const std::vector<double>& el = sixteenRings())
{
    Params prm;
    prm.p_empty_init = 0.42;  // offline: a height seen once needs a second sighting
    prm.ground_max_slope_deg = slope;
    PillarGrid grid(GridGeometry(), prm);
    grid.setSensorModel(SensorModel::fromBeams(el, 0.2));
    std::vector<float> x, y, z;
    for (int a = -50; a <= 50; ++a)
    {
        const double az = a * 0.2 * M_PI / 180.0;
        for (const double e_deg : el)
        {
            const double t = std::tan(e_deg * M_PI / 180.0);
            const double d = reach(a, t);
            if (!std::isfinite(d)) continue;
            x.push_back(float(d * std::cos(az)));
            y.push_back(float(d * std::sin(az)));
            z.push_back(float(d * t));
        }
    }
    grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    std::vector<bool> out;
    for (const Eigen::Vector3d& p : probes) out.push_back(grid.isStatic(p.x(), p.y(), p.z()));
    return out;
}

/** staticAfterOneRingScan() with a car's rear (a face at x = 20.1 m, y within 1 m, up to 1.5 m
 *  above the ground), a raised platform (1 m high, from x = 18 m to 50 m, at azimuths 6 to 10
 *  degrees) and a wall at x = 16 m (azimuths -10 to -6 degrees); a wall 100 m away stops the
 *  beams above. */
std::vector<bool> staticAfterOneSparseScan(double slope, const std::vector<Eigen::Vector3d>& probes)
{
    const double ground = -kSensorZ;
    const auto reach = [&](int a, double t)
    {
        const double az = a * 0.2 * M_PI / 180.0, c = std::cos(az);
        double d = 100.0 / c;  // the far wall
        if (t < 0) d = std::min(d, ground / t);
        const auto face = [&](double at, double z0, double z1)
        {
            const double r = at / c;
            if (r * t >= z0 && r * t <= z1) d = std::min(d, r);
        };
        if (std::abs(20.1 * std::tan(az)) < 1.0) face(20.1, ground, ground + 1.5);  // the car
        if (a >= 30)  // the platform: its face, then its top
        {
            face(18.0, ground, ground + 1.0);
            const double top = t < 0 ? (ground + 1.0) / t : 1e9;
            if (top * c >= 18.0 && top * c <= 50.0) d = std::min(d, top);
        }
        if (a <= -30) face(16.0, ground, 5.0);  // the wall
        return d;
    };
    return staticAfterOneRingScan(slope, reach, probes);
}

/** staticAfterOneRingScan() (ground seen once on) over ground that returns only to `range`
 *  metres (ring -1 would land at 99.7 m), with a low crate (0.8 m high, its face at x = 25 m,
 *  azimuths 4 to 8 degrees) and, if `far_wall`, a wall 150 m away at azimuths -10 to -8 degrees
 *  that does return (the scan's farthest return). */
std::vector<bool> staticAfterOneScanOutOfReach(double range, bool far_wall,
                                               const std::vector<Eigen::Vector3d>& probes)
{
    const auto reach = [&](int a, double t)
    {
        const double c = std::cos(a * 0.2 * M_PI / 180.0);
        const double inf = std::numeric_limits<double>::infinity();
        double d = t < 0 ? -kSensorZ / t : inf;
        if (a >= 20 && a <= 40 && 25.0 * t >= -kSensorZ && 25.0 * t <= 0.8 - kSensorZ)
            d = std::min(d, 25.0 / c);  // the crate's face
        if (far_wall && a <= -40) d = std::min(d, 150.0 / c);
        const bool wall = far_wall && a <= -40;
        return d * std::sqrt(1.0 + t * t) > (wall ? 200.0 : range) ? inf : d;
    };
    return staticAfterOneRingScan(5.0, reach, probes);
}
}  // namespace

// A sensor's last ring on the ground: the next beam up returns nothing because the ground it
// would meet lies beyond the sensor's reach. That is what ground running on gives, so one
// sighting keeps it, but only when the scan reached no farther than where that beam would
// land, and only on the line of the ground below it: a crate there, 0.4 m above that line with
// nothing above it either, still needs a second sighting.
TEST(GroundSeenOnce, TheLastRingOnTheGroundIsKeptWhenTheNextBeamUpLandsOutOfReach)
{
    const auto rad = [](double deg) { return deg * M_PI / 180.0; };
    const double last = kSensorZ / std::tan(rad(3.0));  // ring -3: 33.2 m
    const auto at = [&](double d, double az_deg, double z)
    { return Eigen::Vector3d(d * std::cos(rad(az_deg)), d * std::sin(rad(az_deg)), z); };
    const std::vector<Eigen::Vector3d> probes{
        at(last, -2.0, -kSensorZ),                         // the ground, last ring
        at(25.0, 6.0, 25.0 * std::tan(rad(-3.0)) + 0.01),  // the crate (ring -3)
    };
    const std::vector<bool> out_of_reach = staticAfterOneScanOutOfReach(60.0, false, probes);
    EXPECT_TRUE(out_of_reach[0]) << "ground whose next beam up lands beyond 60 m of reach";
    EXPECT_FALSE(out_of_reach[1]) << "a crate off the ground's line";
    // The same, but the scan reaches a wall 150 m away: ring -1 could have returned from the
    // ground at 99.7 m, and did not (the ground does not run on that way, as far as it shows).
    const std::vector<bool> reached = staticAfterOneScanOutOfReach(60.0, true, probes);
    EXPECT_FALSE(reached[0]);
    EXPECT_FALSE(reached[1]);
}

// A sparse LiDAR crosses ground 33 m away with one ring in one scan; offline settings
// (p_empty_init 0.42) want a second sighting of every height, which that ground never gets in a
// short clip. Ground that runs on both ways along its beams is kept after one, and so is ground
// before a wall (the beam above returns higher, but beyond the pillar). What stands on the
// ground still needs a second sighting: a car (the beam below returns from its foot at the
// same distance), the road at its foot (the beam above returns from the car 0.2 m behind,
// within the pillar), a raised platform (the face below it breaks the run down to the sensor,
// though the one beam below looks level with its top); and so does the padding above the
// ground, where nothing was seen.
TEST(GroundSeenOnce, AFloorThatRunsOnBothWaysIsKeptWhatStandsOnItIsNot)
{
    const auto rad = [](double deg) { return deg * M_PI / 180.0; };
    const double far = kSensorZ / std::tan(rad(3.0));          // ring -3: 33.2 m
    const double wall = kSensorZ / std::tan(rad(7.0));         // ring -7: 14.2 m, before the wall
    const double top = (kSensorZ - 1.0) / std::tan(rad(1.0));  // ring -1 on the platform
    const auto at = [&](double d, double az_deg, double z)
    { return Eigen::Vector3d(d * std::cos(rad(az_deg)), d * std::sin(rad(az_deg)), z); };
    const std::vector<Eigen::Vector3d> probes{
        at(far, -5.0, -kSensorZ),       // ground, far
        at(wall, -8.0, -kSensorZ),      // ground before the wall
        at(19.9, 0.0, -kSensorZ),       // the road at the car's foot
        at(20.15, 0.0, -1.05),          // the car (ring -3)
        at(20.15, 0.0, -0.35),          // the car (ring -1)
        at(top, 8.0, 1.0 - kSensorZ),   // the platform's top
        at(far, -5.0, 0.4 - kSensorZ),  // 0.4 m above the far ground: its padding
    };
    const std::vector<bool> on = staticAfterOneSparseScan(5.0, probes);
    const std::vector<bool> off = staticAfterOneSparseScan(0.0, probes);
    for (std::size_t k = 0; k < 2; ++k)
    {
        EXPECT_TRUE(on[k]) << "probe " << k << ": ground seen once";
        EXPECT_FALSE(off[k]) << "probe " << k << ": without the rule, a second sighting";
    }
    for (std::size_t k = 2; k < probes.size(); ++k)
    {
        EXPECT_FALSE(on[k]) << "probe " << k;
        EXPECT_FALSE(off[k]) << "probe " << k;
    }
}

// A LiDAR whose beams crowd near the horizon (a VLP-32C: a third of a degree apart from +1.67
// to -4 degrees, then 0.67, 0.82, 1.1, 1.6, 2.5, 4.3 and 9.4 degrees apart down to -25) sees
// far ground with its dense beams, each ring once, and the run of returns down to its lowest
// crosses the sparse beams below. Each of them is the next beam below the one above it, though
// several median spacings away: the run goes on, and the ground is kept after one sighting.
TEST(GroundSeenOnce, GroundIsKeptUnderBeamsThatCrowdNearTheHorizon)
{
    const std::vector<double> vlp32c = hif::test::vlp32cBeams();
    const auto rad = [](double deg) { return deg * M_PI / 180.0; };
    const auto ground = [](int, double t)
    { return t < 0 ? -kSensorZ / t : std::numeric_limits<double>::infinity(); };
    const auto onGroundAt = [&](double el_deg)
    {
        const double d = kSensorZ / std::tan(rad(-el_deg));
        return Eigen::Vector3d(d * std::cos(rad(3.0)), d * std::sin(rad(3.0)), -kSensorZ);
    };
    // Rings -2 (49.9 m), -3 (33.2 m) and -4.667 (21.3 m): each run down crosses the gaps of
    // 0.82 degrees and more below -5.333.
    const std::vector<Eigen::Vector3d> probes{onGroundAt(-2.0), onGroundAt(-3.0),
                                              onGroundAt(-4.667)};
    const std::vector<bool> on = staticAfterOneRingScan(5.0, ground, probes, vlp32c);
    const std::vector<bool> off = staticAfterOneRingScan(0.0, ground, probes, vlp32c);
    for (std::size_t k = 0; k < probes.size(); ++k)
    {
        EXPECT_TRUE(on[k]) << "probe " << k << ": ground seen once";
        EXPECT_FALSE(off[k]) << "probe " << k << ": without the rule, a second sighting";
    }
}

// A facade 30 m ahead of a VLP-32C driving towards it at 1 m a scan. Its beams near the horizon
// are a third of a degree apart, its top ones 4.7 degrees: the top beam meets the facade 0.27 m
// lower in each scan, 2.5 m below the next beam up. The facade's foot pillar holds heights of
// both spacings; each height's interval takes the widths of the beams around it, so the top
// beam's sightings overlap and confirm one another, as one surface seen again; with the widths
// of the pillar's middle height (the dense beams) each would be seen once.
TEST(RangeAdaptiveIntervals, EachHeightTakesTheGapOfTheBeamsAroundIt)
{
    const std::vector<double> vlp32c = hif::test::vlp32cBeams();
    Params prm;
    prm.p_empty_init = 0.42;  // offline: a height seen once needs a second sighting
    PillarGrid grid(GridGeometry(), prm);
    grid.setSensorModel(SensorModel::fromBeams(vlp32c, 0.2));
    const double wall = 30.5;  // the facade, 12 m tall, across the middle of pillar 30
    for (int k = 0; k < 3; ++k)
    {
        const double at = k;  // the sensor's x
        std::vector<float> x, y, z;
        for (int a = -25; a <= 25; ++a)
        {
            const double az = a * 0.2 * M_PI / 180.0;
            for (const double e_deg : vlp32c)
            {
                const double t = std::tan(e_deg * M_PI / 180.0);
                double d = (wall - at) / std::cos(az);  // horizontal, to the facade
                if (t < 0) d = std::min(d, kSensorZ / -t);
                if (d * t > 12.0 - kSensorZ) continue;  // over the roof
                x.push_back(float(d * std::cos(az)));
                y.push_back(float(d * std::sin(az)));
                z.push_back(float(d * t));
            }
        }
        Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
        T.translation() = Eigen::Vector3d(at, 0.0, kSensorZ);
        grid.insertScan({x.data(), y.data(), z.data(), x.size()}, T);
    }
    // The top beam met the facade at 9.8, 9.5 and 9.3 m (pillar (30, 0), 0.1 m to the side).
    for (int k = 0; k < 3; ++k)
    {
        const double h = kSensorZ + (wall - k) * std::tan(15.0 * M_PI / 180.0);
        EXPECT_TRUE(grid.isStatic(wall, 0.1, h)) << "the top beam's sighting of scan " << k;
    }
}

// A pole astride the edge between pillars (20, 0) and (20, 1), seen first from the side of
// (20, 0) (its points there, 3 cm from the edge), then from the other side: its points all in
// (20, 1), while the beams toward the centre of (20, 0) pass beside it at its heights. The half
// in (20, 0) is still there; only the surface seen at the edge says so
// (Params::pillar_edge_margin). Near a corner, the pillar across the corner takes it too.
TEST(PillarEdge, APoleAstrideAnEdgeKeepsTheHalfTheScanSawOnlyAcrossTheEdge)
{
    struct Xy
    {
        float x, y;
    };
    // The pole seen at `first` twice, then at `later` (none: gone) four times; is it still
    // static at `first`?
    auto poleStaticAfter = [](double margin, Xy first, std::optional<Xy> later)
    {
        Params prm;
        prm.sensor_from_scans = false;
        prm.pillar_edge_margin = margin;
        PillarGrid grid(GridGeometry(), prm);
        const float ground = -1.7f;
        auto pole = [](Xy at, std::vector<float>& x, std::vector<float>& y, std::vector<float>& z)
        {
            for (double h = -1.0; h <= 0.5; h += 0.05)
            {
                x.push_back(at.x);
                y.push_back(at.y);
                z.push_back(float(h));
            }
        };
        for (int s = 0; s < 2; ++s)
        {
            std::vector<float> x{20.5f}, y{0.5f}, z{ground};
            pole(first, x, y, z);
            grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        }
        EXPECT_TRUE(grid.isStatic(first.x, first.y, -0.5));
        for (int s = 0; s < 4; ++s)
        {
            std::vector<float> x{20.5f}, y{0.5f}, z{ground};  // (20, 0) is hit: its ground
            if (later) pole(*later, x, y, z);
            beamsToward(20.5, 0.5, -1.0, 0.5, 40.0, x, y, z);  // beside the pole, 20 m beyond
            grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        }
        EXPECT_TRUE(grid.isStatic(20.5, 0.5, ground));
        return grid.isStatic(first.x, first.y, -0.5);
    };
    const Xy here{20.5f, 0.97f};
    EXPECT_FALSE(poleStaticAfter(0.0, here, Xy{20.5f, 1.03f})) << "without the margin";
    EXPECT_TRUE(poleStaticAfter(0.1, here, Xy{20.5f, 1.03f})) << "seen 3 cm past the edge";
    EXPECT_FALSE(poleStaticAfter(0.1, here, Xy{20.5f, 1.15f})) << "a surface 0.15 m past it";
    EXPECT_FALSE(poleStaticAfter(0.1, here, std::nullopt)) << "gone: nothing at the edge";
    const Xy corner{20.97f, 0.97f};
    EXPECT_FALSE(poleStaticAfter(0.0, corner, Xy{21.03f, 1.03f}));
    EXPECT_TRUE(poleStaticAfter(0.1, corner, Xy{21.03f, 1.03f})) << "across the corner";
}

// What stands off the centre of its pillar (a box on a post, in one corner), held static
// firmly, is judged by the beams toward where it was seen: beams that pass the pillar's free
// part, toward its centre, leave it as it is; those toward the box, which meet nothing there
// now, show it gone.
TEST(ObjectAxis, WhatStandsOffThePillarsCentreIsJudgedByTheBeamsTowardIt)
{
    auto boxStaticAfter = [](bool toward_box)
    {
        Params prm;
        prm.sensor_from_scans = false;
        PillarGrid grid(GridGeometry(), prm);
        const float ground = -1.7f;
        // A box 0.7 to 1.4 m above the ground, its face at x = 20.75 between y = 0.75 and
        // 0.95, in the corner of pillar (20, 0), seen until the map holds it at p_max.
        for (int s = 0; s < 10; ++s)
        {
            std::vector<float> x{20.3f}, y{0.3f}, z{ground};
            for (const float by : {0.75f, 0.85f, 0.95f})
                for (double h = -1.0; h <= -0.3; h += 0.05)
                {
                    x.push_back(20.75f);
                    y.push_back(by);
                    z.push_back(float(h));
                }
            grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        }
        EXPECT_TRUE(grid.isStatic(20.75, 0.85, -0.6));
        for (int s = 0; s < 8; ++s)  // a miss a scan takes p_max under 0.5 in 7
        {
            std::vector<float> x{20.3f}, y{0.3f}, z{ground};    // (20, 0) is hit: its ground
            beamsToward(20.5, 0.5, -1.0, -0.3, 40.0, x, y, z);  // through the free part
            if (toward_box) beamsToward(20.75, 0.85, -1.0, -0.3, 40.0, x, y, z);
            grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        }
        EXPECT_TRUE(grid.isStatic(20.3, 0.3, ground));
        return grid.isStatic(20.75, 0.85, -0.6);
    };
    EXPECT_TRUE(boxStaticAfter(false)) << "beams through the pillar's free part, at its centre";
    EXPECT_FALSE(boxStaticAfter(true)) << "and beams through where the box stood";
}

// The margin is a distance inside a pillar: under half of it, or every point would be near
// two opposite edges.
TEST(PillarEdge, TheMarginIsUnderHalfAPillar)
{
    Params prm;
    prm.pillar_edge_margin = 0.5;
    EXPECT_THROW(PillarGrid(GridGeometry(), prm), std::invalid_argument);
    prm.pillar_edge_margin = 0.2;
    GridGeometry small;
    small.pillar_size = 0.4;
    EXPECT_THROW(PillarGrid(small, prm), std::invalid_argument);
    EXPECT_NO_THROW(PillarGrid(GridGeometry(), prm));
    prm.pillar_edge_margin = -0.1;
    EXPECT_THROW(PillarGrid(GridGeometry(), prm), std::invalid_argument);
}

// The heights each pillar takes from the points near its edges in the pillars beside it,
// against a reference that checks every point: the same whether the scan's pillars are grouped
// by the counting sort or, with a point millions of metres away, by the comparison sort.
TEST(PillarEdge, EachPillarTakesTheCellsOfThePointsNearItsEdgesBesideIt)
{
    Params prm;
    prm.sensor_from_scans = false;
    prm.pillar_edge_margin = 0.1;
    const PillarGrid grid(GridGeometry(), prm);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<float> x, y, z;
    for (int i = 0; i < 20000; ++i)
    {
        // Runs of three points in a cell of a pillar (repeats), some ending near an edge.
        const double px = -6.0 + 12.0 * u(rng), py = -6.0 + 12.0 * u(rng), pz = 2.0 * u(rng);
        for (int k = 0; k < 3; ++k)
        {
            x.push_back(float(px + 0.02 * k));
            y.push_back(float(py));
            z.push_back(float(pz));
        }
    }
    // What the reference expects: per pillar of the scan, the distinct cells.
    std::map<std::pair<int32_t, int32_t>, std::set<int32_t>> expected;
    std::set<std::pair<int32_t, int32_t>> hit;
    for (std::size_t i = 0; i < x.size(); ++i)
        hit.insert({int32_t(std::floor(double(x[i]))), int32_t(std::floor(double(y[i])))});
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        const int32_t m = int32_t(std::floor(double(x[i]))), n = int32_t(std::floor(double(y[i])));
        const double fu = double(x[i]) - m, fv = double(y[i]) - n;
        const int dm = fu < 0.1 ? -1 : fu > 0.9 ? 1 : 0, dn = fv < 0.1 ? -1 : fv > 0.9 ? 1 : 0;
        const int32_t cell = int32_t(std::floor(double(z[i]) * (1.0 / 0.05)));  // as the pass
        for (const auto& [a, b] : {std::pair{dm, 0}, std::pair{0, dn}, std::pair{dm, dn}})
            if ((a != 0 || b != 0) && hit.count({m + a, n + b}) &&
                !(a != 0 && b != 0 && (dm == 0 || dn == 0)))
                expected[{m + a, n + b}].insert(cell);
    }
    ASSERT_GT(expected.size(), 100u);
    for (const bool far : {false, true})
    {
        std::vector<float> fx = x, fy = y, fz = z;
        if (far)
        {
            fx.push_back(3.0e6f);
            fy.push_back(-2.0e6f);
            fz.push_back(1.0f);
        }
        ScanBuckets scan;
        bucketPoints(grid, {fx.data(), fy.data(), fz.data(), fx.size()},
                     Eigen::Isometry3d::Identity(), scan);
        std::size_t with_cells = 0;
        for (std::size_t p = 0; p < scan.pillarCount(); ++p)
        {
            const PillarIndex idx = unpackKey(scan.keys[p]);
            std::set<int32_t> got;
            for (uint32_t k = scan.edge_offsets[p]; k < scan.edge_offsets[p + 1]; ++k)
                got.insert(scan.edge_cells[k]);
            const auto it = expected.find({idx.m, idx.n});
            EXPECT_EQ(got, it == expected.end() ? std::set<int32_t>() : it->second)
                << "pillar (" << idx.m << ", " << idx.n << ")" << (far ? ", comparison sort" : "");
            with_cells += !got.empty();
        }
        EXPECT_EQ(with_cells, expected.size());
    }
}
