// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_sensor_model.cpp
 * @brief  The sensor model recovered from synthetic and real scans: a spinning LiDAR's beams
 *         and resolution, a rosette's lack of rings, KITTI's HDL-64E and its sparser copies;
 *         and misses that need a beam.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "hif/PillarGrid.h"
#include "hif/SensorModel.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Rings.h"
#include "kitti_fixture.h"
#include "lidar_beams.h"

using namespace hif;

namespace
{
struct Cloud
{
    std::vector<float> x, y, z;
    void add(double el_deg, double az_deg, double range)
    {
        const double el = el_deg * M_PI / 180.0, az = az_deg * M_PI / 180.0;
        x.push_back(static_cast<float>(range * std::cos(el) * std::cos(az)));
        y.push_back(static_cast<float>(range * std::cos(el) * std::sin(az)));
        z.push_back(static_cast<float>(range * std::sin(el)));
    }
    [[nodiscard]] PointsView view() const { return {x.data(), y.data(), z.data(), x.size()}; }
};
}  // namespace

TEST(SensorModel, RecoversTheBeamsAndStepOfASpinningLidar)
{
    // 32 beams from -30.67 to +10.67 degrees, 1800 columns, every return 20 to 30 m away.
    Cloud c;
    std::vector<double> beams;
    for (int b = 0; b < 32; ++b) beams.push_back(-30.67 + b * (41.34 / 31.0));
    for (int col = 0; col < 1800; ++col)
        for (double e : beams) c.add(e, col * 0.2, 20.0 + 10.0 * ((col * 7) % 13) / 13.0);
    const auto m = SensorModel::estimate(c.view());
    ASSERT_TRUE(m);
    ASSERT_EQ(m->beam_elevations_deg.size(), 32u) << m->describe();
    for (std::size_t b = 0; b < 32; ++b) EXPECT_NEAR(m->beam_elevations_deg[b], beams[b], 0.02);
    EXPECT_NEAR(m->vertical_spacing_deg, 41.34 / 31.0, 0.02);
    EXPECT_NE(m->describe().find("deg apart (median), 0.200 deg horizontally"), std::string::npos)
        << m->describe();
    EXPECT_NEAR(m->horizontal_resolution_deg, 0.2, 0.01);
    EXPECT_EQ(m->azimuth_coverage_deg, 360.0);
    EXPECT_FALSE(m->contradiction(*m));
    // A 16-beam scan is another sensor.
    Cloud sparse;
    for (int col = 0; col < 1800; ++col)
        for (int b = 0; b < 32; b += 2) sparse.add(beams[b], col * 0.2, 25.0);
    const auto m16 = SensorModel::estimate(sparse.view());
    ASSERT_TRUE(m16);
    EXPECT_EQ(m16->beam_elevations_deg.size(), 16u);
    EXPECT_TRUE(m->contradiction(*m16));
}

// A VLP-32C's beams: a third of a degree apart near the horizon, up to 9 degrees apart at the
// bottom of its view. Each is recovered; the median spacing is the dense one, and the gap
// between two beams (PillarGrid::beamGapSlope(), the interval widths) is the local one.
TEST(SensorModel, RecoversUnevenBeamsThatCrowdNearTheHorizon)
{
    std::vector<double> beams = hif::test::vlp32cBeams();
    std::sort(beams.begin(), beams.end());  // ascending, as the model holds them
    Cloud c;
    for (int col = 0; col < 1800; ++col)
        for (double e : beams) c.add(e, col * 0.2, 20.0 + 10.0 * ((col * 7) % 13) / 13.0);
    const auto m = SensorModel::estimate(c.view());
    ASSERT_TRUE(m);
    ASSERT_EQ(m->beam_elevations_deg.size(), beams.size()) << m->describe();
    for (std::size_t b = 0; b < beams.size(); ++b)
        EXPECT_NEAR(m->beam_elevations_deg[b], beams[b], 0.02);
    EXPECT_NEAR(m->vertical_spacing_deg, 1.0 / 3.0, 0.01);
    // The log line says the beams are uneven: their widest gap beside the median.
    EXPECT_NE(m->describe().find("apart (median; 9.36"), std::string::npos) << m->describe();
    Params prm;
    PillarGrid grid(GridGeometry(), prm);
    grid.setSensorModel(*m);
    const auto gap = [&](double el_deg)
    { return grid.beamGapSlope(std::tan(el_deg * M_PI / 180.0)); };
    const auto tan_gap = [](double a, double b)
    { return std::tan(b * M_PI / 180.0) - std::tan(a * M_PI / 180.0); };
    EXPECT_NEAR(gap(-20.0), tan_gap(-25.0, -15.639), 1e-3);
    EXPECT_NEAR(gap(-2.5), tan_gap(-2.667, -2.333), 1e-3);
}

TEST(SensorModel, ARosetteHasNoRingsAndALimitedFieldOfView)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    Cloud c;
    while (c.x.size() < 10000)
    {
        const double a = 35.0 * u(rng), b = 35.0 * u(rng);
        if (a * a + b * b <= 35.0 * 35.0) c.add(a, b, 15.0 + 5.0 * u(rng));
    }
    const auto m = SensorModel::estimate(c.view());
    ASSERT_TRUE(m);
    EXPECT_FALSE(m->hasRings()) << m->describe();
    EXPECT_NEAR(m->elevation_min_deg, -35.0, 1.0);
    EXPECT_NEAR(m->elevation_max_deg, 35.0, 1.0);
    EXPECT_LE(m->azimuth_coverage_deg, 72.0);
    // A 70-degree cone of 10,000 points: about 0.6 degrees between points.
    EXPECT_NEAR(m->vertical_spacing_deg, 0.6, 0.1);
}

TEST(SensorModel, AFewPointsGiveNoModelAndTheGridEstimatesFromItsFirstScan)
{
    Cloud few;
    for (int k = 0; k < 50; ++k) few.add(0.0, k, 10.0);
    EXPECT_FALSE(SensorModel::estimate(few.view()));
    Cloud c;
    for (int col = 0; col < 1800; ++col)
        for (int b = 0; b < 16; ++b) c.add(-15.0 + 2.0 * b, col * 0.2, 12.0);
    PillarGrid grid;
    EXPECT_FALSE(grid.insertScan(few.view()).sensor_estimated);
    EXPECT_FALSE(grid.sensorModel());
    EXPECT_TRUE(grid.insertScan(c.view()).sensor_estimated);
    ASSERT_TRUE(grid.sensorModel());
    EXPECT_EQ(grid.sensorModel()->beam_elevations_deg.size(), 16u);
    // The gap of the beams at -1 and +1 degrees around the horizon, not beam_spacing_deg's 0.44.
    EXPECT_NEAR(grid.beamGapSlope(0.0), std::tan(M_PI / 180.0) - std::tan(-M_PI / 180.0), 1e-4);
    EXPECT_EQ(grid.imageLayout(), RangeImageLayout::forSensor(grid.sensorModel()));
    Params paper = Params::paper();
    PillarGrid p(GridGeometry(), paper);
    EXPECT_FALSE(p.insertScan(c.view()).sensor_estimated);
    EXPECT_FALSE(p.sensorModel());
}

// A first scan that is part of a sweep (a driver's first message: a quarter of the azimuth, or
// the upper rings only) gives a model of part of the sensor; the next whole sweep, within
// kSensorSettleScans, replaces it. Scans that see less, or another sensor, do not.
TEST(SensorModel, AFirstScanThatIsPartOfASweepGivesWayToTheNextWholeOne)
{
    auto sweep = [](double az_to, int first_beam)
    {
        Cloud c;
        for (int col = 0; col * 0.2 < az_to; ++col)
            for (int b = first_beam; b < 16; ++b) c.add(-15.0 + 2.0 * b, col * 0.2, 12.0);
        return c;
    };
    const Cloud whole = sweep(360.0, 0), quarter = sweep(90.0, 0), upper = sweep(360.0, 10);
    for (const Cloud* part : {&quarter, &upper})
    {
        PillarGrid grid;
        EXPECT_TRUE(grid.insertScan(part->view()).sensor_estimated);
        const SensorModel first = *grid.sensorModel();
        EXPECT_TRUE(first.seesLessThan(*SensorModel::estimate(whole.view())));
        EXPECT_TRUE(grid.insertScan(whole.view()).sensor_estimated);  // replaced
        ASSERT_TRUE(grid.sensorModel());
        EXPECT_EQ(grid.sensorModel()->beam_elevations_deg.size(), 16u);
        EXPECT_EQ(grid.sensorModel()->azimuth_coverage_deg, 360.0);
        EXPECT_EQ(grid.imageLayout(), RangeImageLayout::forSensor(grid.sensorModel()));
        // Part of a sweep again: the whole one's model stays.
        EXPECT_FALSE(grid.insertScan(part->view()).sensor_estimated);
        EXPECT_EQ(grid.sensorModel()->azimuth_coverage_deg, 360.0);
    }
    // Whole from the start: the next scans of the same sensor leave it.
    PillarGrid grid;
    EXPECT_TRUE(grid.insertScan(whole.view()).sensor_estimated);
    EXPECT_FALSE(grid.insertScan(whole.view()).sensor_estimated);
    EXPECT_FALSE(grid.sensorModel()->seesLessThan(*grid.sensorModel()));
    // After kSensorSettleScans, a scan that sees more is only checked (every
    // kSensorCheckInterval scans): the model is not replaced mid-run.
    PillarGrid late;
    EXPECT_TRUE(late.insertScan(quarter.view()).sensor_estimated);
    for (std::size_t k = 0; k < PillarGrid::kSensorSettleScans; ++k)
        EXPECT_FALSE(late.insertScan(quarter.view()).sensor_estimated);
    EXPECT_FALSE(late.insertScan(whole.view()).sensor_estimated);
    EXPECT_EQ(late.sensorModel()->azimuth_coverage_deg, 90.0);
    // A model given (the .ini, a map read back) is not replaced: only checked.
    PillarGrid given;
    given.setSensorModel(SensorModel::estimate(quarter.view()));
    EXPECT_FALSE(given.insertScan(whole.view()).sensor_estimated);
    EXPECT_EQ(given.sensorModel()->azimuth_coverage_deg, 90.0);
}

// The range images' rows and columns follow the sensor's spacing, but no finer than 0.05
// degrees: a spacing of a millionth of a degree (valid for validate()) asks for a few thousand
// rows, not billions.
TEST(SensorModel, RangeImagesAreNoFinerThanFiveHundredthsOfADegree)
{
    const RangeImageLayout fine =
        RangeImageLayout::forSensor(SensorModel::fromPattern(-35.0, 35.0, 1e-6, 70.0));
    EXPECT_EQ(fine.cols, 7200);  // 360 / 0.05
    // (tan 35 deg - tan -35 deg) / (0.05 deg in radians) + 1 = 1605 rows.
    EXPECT_EQ(fine.rows, 1605);
    // A real sensor's spacing is coarser: its rows are half of it.
    const RangeImageLayout vlp16 =
        RangeImageLayout::forSensor(SensorModel::fromPattern(-15.0, 15.0, 2.0, 360.0));
    EXPECT_NEAR(vlp16.tan_res, 1.0 * M_PI / 180.0, 1e-12);
}

TEST(SensorModel, RecoversKittisHdl64eAndItsSparserCopies)
{
    for (const char* seq : {"01", "03", "04", "08"})
    {
        SCOPED_TRACE(seq);
        const std::string dir = test::kittiRoot() + "/sequences/" + seq;
        HIF_REQUIRE_KITTI_SEQUENCE(dir);
        const io::KittiSequence kitti(dir);
        const io::Cloud scan = kitti.readScan(0);
        const auto m =
            SensorModel::estimate({scan.x.data(), scan.y.data(), scan.z.data(), scan.size()});
        ASSERT_TRUE(m);
        // The HDL-64E: 64 beams from -24.9 to +2 degrees, 0.33 to 0.5 apart; about 2,000
        // points a turn. Its lowest beams reach the ground within 2 m of the car, and go
        // unused, hence the lowest ring found above -24.9.
        EXPECT_NEAR(static_cast<double>(m->beam_elevations_deg.size()), 64.0, 1.0) << m->describe();
        EXPECT_NEAR(m->vertical_spacing_deg, 0.4, 0.05);
        EXPECT_NEAR(m->horizontal_resolution_deg, 0.175, 0.02);
        EXPECT_NEAR(m->elevation_min_deg, -24.0, 1.0);
        EXPECT_NEAR(m->elevation_max_deg, 2.3, 1.0);
        EXPECT_EQ(m->azimuth_coverage_deg, 360.0);
        // Every 4th ring kept (as a 16-beam LiDAR): 16 beams, four times as far apart.
        const std::vector<uint32_t> ring = io::ringOfEachPoint(scan);
        io::Cloud sparse;
        for (std::size_t i = 0; i < scan.size(); ++i)
            if (ring[i] % 4 == 0)
            {
                sparse.x.push_back(scan.x[i]);
                sparse.y.push_back(scan.y[i]);
                sparse.z.push_back(scan.z[i]);
            }
        const auto m16 = SensorModel::estimate(
            {sparse.x.data(), sparse.y.data(), sparse.z.data(), sparse.x.size()});
        ASSERT_TRUE(m16);
        EXPECT_NEAR(static_cast<double>(m16->beam_elevations_deg.size()), 16.0, 1.0)
            << m16->describe();
        EXPECT_NEAR(m16->vertical_spacing_deg, 1.6, 0.25);
        EXPECT_TRUE(m->contradiction(*m16)) << "a 16-beam scan is not the 64-beam sensor";
    }
}

namespace
{
/** Scan 0: the ground and a box at 1 m in pillar (10, 0). Scans 1-5: the ground there, and
 *  either nothing in the box's direction (no beam passed) or, `through`, a return twice as far
 *  along it. */
PillarGrid boxThenGround(bool through)
{
    PillarGrid grid;
    const std::vector<float> x0{10.5f, 10.5f}, y0{0.5f, 0.5f}, z0{0.0f, 1.0f};
    grid.insertScan({x0.data(), y0.data(), z0.data(), x0.size()});
    std::vector<float> x{10.5f}, y{0.5f}, z{0.0f};
    if (through)
    {
        x.push_back(21.0f);
        y.push_back(1.0f);
        z.push_back(2.0f);
    }
    for (int s = 0; s < 5; ++s) grid.insertScan({x.data(), y.data(), z.data(), x.size()});
    return grid;
}
}  // namespace

TEST(MissNeedsBeam, AnIntervalNoBeamPassedIsKeptAndOneSeenThroughDecays)
{
    for (const bool through : {false, true})
    {
        const PillarGrid grid = boxThenGround(through);
        EXPECT_EQ(grid.isStatic(10.5, 0.5, 1.0), !through) << "through " << through;
        EXPECT_TRUE(grid.isStatic(10.5, 0.5, 0.0));
    }
}

TEST(MissNeedsBeam, PEmptyFallsOnlyWhenABeamPassedThroughThePillar)
{
    // With nothing beyond the box, no beam passes through the pillar and its p_empty (the
    // prior of heights seen there for the first time, Eq. 14) stays; a return twice as far
    // along the box's direction lowers it, as Eq. 8 always does without the gate.
    const float kept = boxThenGround(false).findPillar({10, 0})->logodds_empty;
    const float lowered = boxThenGround(true).findPillar({10, 0})->logodds_empty;
    const Params p;
    EXPECT_FLOAT_EQ(kept, static_cast<float>(std::log(p.p_empty_init / (1 - p.p_empty_init))))
        << "never lowered: no scan passed a beam through the pillar";
    EXPECT_FLOAT_EQ(lowered,
                    kept + 5.0f * static_cast<float>(std::log((1 - p.alpha) / (1 - p.beta))))
        << "lowered by each of the 5 scans that saw through it (Eq. 8)";
}

// A spinning LiDAR samples a static surface at the same heights scan after scan, so offline
// (p_empty_init 0.42) a height seen once is dynamic until a second sighting. A non-repetitive
// sensor (a model without rings) samples it at new heights in every scan: there a height seen
// once is no sign that it moved, and a new pillar starts from 0.5 (never lower, never raised
// above p_empty_init).
TEST(SensorModel, WithoutRingsAHeightSeenOnceIsNoSignOfMotion)
{
    Params p;
    p.p_empty_init = 0.42;
    p.sensor_from_scans = false;  // the models below are given
    const SensorModel rosette = SensorModel::fromPattern(-35.0, 35.0, 0.27, 70.0);
    const SensorModel rings =
        SensorModel::fromBeams({-15.0, -13.0, -11.0, -9.0, -7.0, -5.0, -3.0, -1.0, 1.0, 3.0, 5.0,
                                7.0, 9.0, 11.0, 13.0, 15.0},
                               0.2);
    const std::vector<float> x{10.5f, 10.5f}, y{0.5f, 0.5f}, z{-1.7f, -0.7f};
    auto seenOnce = [&](const SensorModel& m, double p_empty_init)
    {
        Params q = p;
        q.p_empty_init = p_empty_init;
        PillarGrid grid(GridGeometry(), q);
        grid.setSensorModel(m);
        grid.insertScan({x.data(), y.data(), z.data(), x.size()});
        return grid;
    };
    const PillarGrid without = seenOnce(rosette, 0.42), with = seenOnce(rings, 0.42);
    EXPECT_DOUBLE_EQ(without.pEmptyInit(), 0.5);
    EXPECT_DOUBLE_EQ(with.pEmptyInit(), 0.42);
    EXPECT_TRUE(without.isStatic(10.5, 0.5, -0.7));
    EXPECT_FALSE(with.isStatic(10.5, 0.5, -0.7));
    EXPECT_DOUBLE_EQ(without.staticProbability(50.5, 50.5, 0.0), 0.5);  // never observed
    EXPECT_DOUBLE_EQ(with.staticProbability(50.5, 50.5, 0.0), 0.42);
    EXPECT_DOUBLE_EQ(seenOnce(rosette, 0.6).pEmptyInit(), 0.6);
    PillarGrid none(GridGeometry(), p);  // no model: p_empty_init as given
    EXPECT_DOUBLE_EQ(none.pEmptyInit(), 0.42);
}
