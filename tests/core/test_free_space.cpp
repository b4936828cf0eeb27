// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_free_space.cpp
 * @brief  The free-space test (Params::free_space_window) on a ray-cast scene: a person walks
 *         across in front of a wall, past a pole, for ten scans; the map alone keeps the person,
 *         the test removes it, and the ground, the wall and the pole stay; a cyclist's wheels go
 *         with it into the pillars next to its rider; a walker seen by sparse rings is tested
 *         from the floor the map holds under it; a car behind a barrier goes down to its
 *         lowest ring over it. Also which scans judge (a scan is no
 *         evidence about itself, only scans within the window count, online sees the past
 *         only), the test's scans (FreeSpaceTest) and the minimum range.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <utility>

#include "hif/FreeSpaceTest.h"
#include "hif/PillarGrid.h"
#include "hif/SensorModel.h"

using namespace hif;

namespace
{
/** The tests' images use the layout of a map without a sensor model. */
const RangeImageLayout kLayout = RangeImageLayout::forSensor(std::nullopt);

enum What : uint8_t
{
    kNothing,
    kGround,
    kWall,
    kPole,
    kPerson,
    kHedge,    ///< there in every scan but one in the middle (a gap in foliage, a flicker)
    kLow,      ///< a mover 0.3 m tall
    kRider,    ///< a cyclist's body, from 0.4 m up
    kWheels,   ///< its bicycle's low part, 1.6 m long: beyond the rider, alone in its pillars
    kBarrier,  ///< a barrier between the lanes, 1 m tall
    kParked,   ///< a car standing behind the barrier
    kFence     ///< a garden wall a walker passes behind
};
constexpr int kKinds = 12;

constexpr double kGroundZ = -1.7;  // the sensor 1.7 m above the ground

/** One scan: sensor-frame points (the sensor looks along +x, unrotated) and what each hit. */
struct Scan
{
    std::vector<float> x, y, z;
    std::vector<What> what;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    [[nodiscard]] PointsView view() const { return {x.data(), y.data(), z.data(), x.size()}; }
};

/** A ray-box intersection: `take(s, w)` with the entry distance if the ray hits it. */
template <typename Take>
void hitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
            const Eigen::Vector3d& hi, What w, double range, Take&& take)
{
    double s0 = 0, s1 = range;
    for (int k = 0; k < 3; ++k)
    {
        double a = (lo[k] - o[k]) / d[k], c = (hi[k] - o[k]) / d[k];
        if (a > c) std::swap(a, c);
        s0 = std::max(s0, a);
        s1 = std::min(s1, c);
    }
    if (s0 <= s1) take(s0, w);
}

/** Where the ray o + s d enters a vertical cylinder of radius `radius` around (cx, cy) between
 *  the ground and `height` above it: `take(s, w)`. */
template <typename Take>
void hitCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double cx, double cy,
                 double radius, double height, What w, Take&& take)
{
    const double ox = o.x() - cx, oy = o.y() - cy;
    const double a = d.x() * d.x() + d.y() * d.y(), b = 2 * (ox * d.x() + oy * d.y());
    const double disc = b * b - 4 * a * (ox * ox + oy * oy - radius * radius);
    if (a <= 0 || disc < 0) return;
    const double s = (-b - std::sqrt(disc)) / (2 * a);
    const double z = o.z() + s * d.z();
    if (z >= kGroundZ && z <= kGroundZ + height) take(s, w);
}

/** First hit along the ray o + s d of the ground (z = kGroundZ + crossfall y), a wall across
 *  the view at x = `wall_x` and, if given, a person's box `person` (lo, hi corners), or
 *  kNothing; its range in `range`. */
What groundWallAndPerson(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double wall_x,
                         const std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>>& person,
                         double& range, double crossfall = 0.0)
{
    range = 80.0;
    What what = kNothing;
    auto take = [&](double s, What w)
    {
        if (s > 1e-6 && s < range) range = s, what = w;
    };
    const double down = d.z() - crossfall * d.y();  // toward the ground plane
    if (down < 0) take((kGroundZ + crossfall * o.y() - o.z()) / down, kGround);
    if (d.x() > 0) take((wall_x - o.x()) / d.x(), kWall);
    if (person) hitBox(o, d, person->first, person->second, kPerson, range, take);
    return what;
}

/** First hit along the ray o + s d, at scan `i`, of the ground, a wall at x = 25.5, a pole of
 *  radius 0.1 at (12, -3), a person (a 0.4 m square box, 1.7 m tall) crossing at x = 15, a
 *  hedge at (18, 6) missing from scan 5 only, a mover 0.3 m tall crossing at x = 10, and a
 *  cyclist crossing at x = 21, 0.4 m per scan, the other way. */
What cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, int i, double& range)
{
    const double person_y = -1.0 + 0.15 * i;
    range = 60.0;
    What what = kNothing;
    auto take = [&](double s, What w)
    {
        if (s > 1e-6 && s < range)
        {
            range = s;
            what = w;
        }
    };
    if (d.z() < 0) take((kGroundZ - o.z()) / d.z(), kGround);
    if (d.x() > 0)
    {
        const double s = (25.5 - o.x()) / d.x();
        const Eigen::Vector3d p = o + s * d;
        if (std::abs(p.y()) < 20 && p.z() < kGroundZ + 3.0) take(s, kWall);
    }
    hitCylinder(o, d, 12.0, -3.0, 0.1, 3.0, kPole, take);
    hitBox(o, d, {14.8, person_y - 0.2, kGroundZ}, {15.2, person_y + 0.2, kGroundZ + 1.7}, kPerson,
           range, take);
    if (i != 5)
        hitBox(o, d, {17.5, 5.5, kGroundZ}, {18.5, 6.5, kGroundZ + 1.5}, kHedge, range, take);
    const double low_y = -4.0 + 0.15 * i;
    hitBox(o, d, {9.8, low_y - 0.2, kGroundZ}, {10.2, low_y + 0.2, kGroundZ + 0.3}, kLow, range,
           take);
    const double cyclist_y = 6.0 - 0.4 * i;
    hitBox(o, d, {20.8, cyclist_y - 0.2, kGroundZ + 0.4}, {21.2, cyclist_y + 0.2, kGroundZ + 1.7},
           kRider, range, take);
    hitBox(o, d, {20.95, cyclist_y - 0.8, kGroundZ}, {21.05, cyclist_y + 0.8, kGroundZ + 0.4},
           kWheels, range, take);
    return what;
}

/** One scan of a sensor at `pose` (a translation), rows `row_deg` apart from -20 to +4
 *  degrees, columns 0.2 degrees apart over `half_az` degrees on each side of +x: `cast(d, r)`
 *  gives what the ray of direction `d` hits first (kNothing: no return) and its range `r`. */
template <typename Cast>
Scan rayScan(const Eigen::Isometry3d& pose, double half_az, Cast&& cast, double row_deg = 0.4)
{
    Scan s;
    s.pose = pose;
    for (double el = -20.0; el <= 4.0; el += row_deg)
        for (double az = -half_az; az <= half_az; az += 0.2)
        {
            const double e = el * M_PI / 180.0, a = az * M_PI / 180.0;
            const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a),
                                    std::sin(e));
            double r = 0;
            const What w = cast(d, r);
            if (w == kNothing) continue;
            const Eigen::Vector3d p = d * r;  // sensor frame (no rotation)
            s.x.push_back(float(p.x()));
            s.y.push_back(float(p.y()));
            s.z.push_back(float(p.z()));
            s.what.push_back(w);
        }
    return s;
}

/** Ten scans of rayScan() over `half_az` degrees on each side of ahead, rows `row_deg` apart,
 *  from a sensor moving `ego` m per scan along x: scan i casts its rays from its origin o with
 *  `cast(i, o, d, range)`. */
template <typename Cast>
std::vector<Scan> movingSensorScans(double ego, double half_az, Cast&& cast, double row_deg = 0.4)
{
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation().x() = ego * i;
        const Eigen::Vector3d o = pose.translation();
        scans.push_back(rayScan(
            pose, half_az,
            [&](const Eigen::Vector3d& d, double& range) { return cast(i, o, d, range); },
            row_deg));
    }
    return scans;
}

/** Ten scans of a sensor that stands still (or moves `ego` m per scan along x) over the 120
 *  degrees ahead (rayScan()); the person crosses at 0.15 m per scan. */
std::vector<Scan> makeScans(double ego = 0.0)
{
    return movingSensorScans(ego, 60.0,
                             [](int i, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                double& r) { return cast(o, d, i, r); });
}

/** A sensor model whose rings lie `spacing` degrees apart from -20 to +4 degrees (the rows of
 *  rayScan() with that row spacing), 0.2 degrees apart horizontally. */
SensorModel ringsEvery(double spacing)
{
    std::vector<double> rings;
    for (double el = -20.0; el <= 4.0; el += spacing) rings.push_back(el);
    return SensorModel::fromBeams(rings, 0.2);
}

Params freeSpaceParams()
{
    Params p;
    p.p_empty_init = 0.42;
    p.free_space_window = 10;
    p.free_space_fraction = 0.6;
    return p;
}

/** freeSpaceParams() online: each scan classified with the past only, a new height starting
 *  from kitti-online.ini's p_empty_init. */
Params onlineParams()
{
    Params prm = freeSpaceParams();
    prm.online = true;
    prm.p_empty_init = 0.5;  // kitti-online.ini's
    return prm;
}

/** Share of the points of each kind classified dynamic. */
struct Removed
{
    std::size_t n[kKinds] = {}, removed[kKinds] = {};
    double pct(What w) const
    {
        return 100.0 * double(removed[w]) / double(std::max<std::size_t>(1, n[w]));
    }
    void add(const Scan& s, const std::vector<uint8_t>& dyn)
    {
        for (std::size_t k = 0; k < dyn.size(); ++k)
        {
            ++n[s.what[k]];
            removed[s.what[k]] += dyn[k];
        }
    }
};

/** A test holding all of `scans`. */
FreeSpaceTest holding(const std::vector<Scan>& scans)
{
    FreeSpaceTest test(scans.size());
    for (const Scan& s : scans) test.add(s.view(), s.pose, kLayout);
    return test;
}

/** Offline: the map of all scans; each scan classified with the test holding all of them. */
Removed offline(const std::vector<Scan>& scans, const Params& prm, bool with_test)
{
    PillarGrid grid(GridGeometry(), prm);
    for (const Scan& s : scans) grid.insertScan(s.view(), s.pose);
    const FreeSpaceTest test = holding(scans);
    Removed r;
    for (const Scan& s : scans)
    {
        std::vector<uint8_t> dyn;
        grid.classify(s.view(), dyn, s.pose, with_test ? &test : nullptr);
        r.add(s, dyn);
    }
    return r;
}

/** The scans cleaned offline with freeSpaceParams(), without the free-space test and with it. */
struct WithAndWithout
{
    Removed without, with;
};
/** The static scene as the map alone has it: the test removes exactly the ground and wall
 *  points the map does. */
void expectGroundAndWallAsTheMapHasThem(const Removed& with, const Removed& without)
{
    for (const What w : {kGround, kWall})
        EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
}
/** The mover of kind `w` (more than `min_points` points) removed `min_pct` % or more with the
 *  test, 5 % at most by the map alone; the static scene as the map has it. */
void expectTheMoverGoes(const Removed& with, const Removed& without, What w, std::size_t min_points,
                        double min_pct)
{
    EXPECT_GT(with.n[w], min_points);
    EXPECT_GE(with.pct(w), min_pct);
    EXPECT_LE(without.pct(w), 5.0);
    expectGroundAndWallAsTheMapHasThem(with, without);
}
WithAndWithout withAndWithoutTheTest(const std::vector<Scan>& scans)
{
    return {offline(scans, freeSpaceParams(), false), offline(scans, freeSpaceParams(), true)};
}

/** Each of `scans` classified by `grid` without the free-space test and with `test`. */
WithAndWithout classifyWithAndWithout(const PillarGrid& grid, const FreeSpaceTest& test,
                                      const std::vector<Scan>& scans)
{
    WithAndWithout r;
    for (const Scan& s : scans)
    {
        std::vector<uint8_t> dyn, dyn_map;
        grid.classify(s.view(), dyn, s.pose, &test);
        grid.classify(s.view(), dyn_map, s.pose);
        r.with.add(s, dyn);
        r.without.add(s, dyn_map);
    }
    return r;
}

/** Online with `prm`: each of `scans` inserted, then classified with the past only, without the
 *  free-space test and with it (a test holding the scans before it); each scan's own into
 *  `per_scan` when given. With `model`, the map's sensor model and its images' layout. */
WithAndWithout onlineWithAndWithout(const std::vector<Scan>& scans, const Params& prm,
                                    std::vector<WithAndWithout>* per_scan = nullptr,
                                    const std::optional<SensorModel>& model = std::nullopt)
{
    PillarGrid grid(GridGeometry(), prm);
    if (model) grid.setSensorModel(*model);
    const RangeImageLayout layout = RangeImageLayout::forSensor(model);
    FreeSpaceTest past(FreeSpaceTest::capacityFor(prm));
    WithAndWithout r;
    for (const Scan& s : scans)
    {
        grid.insertScan(s.view(), s.pose);
        std::vector<uint8_t> dyn, dyn_map;
        grid.classify(s.view(), dyn, s.pose, &past);
        grid.classify(s.view(), dyn_map, s.pose);
        r.with.add(s, dyn);
        r.without.add(s, dyn_map);
        if (per_scan)
        {
            per_scan->emplace_back();
            per_scan->back().with.add(s, dyn);
            per_scan->back().without.add(s, dyn_map);
        }
        past.add(s.view(), s.pose, layout);
    }
    return r;
}

/** Offline with freeSpaceParams() and the sensor model `model`: the map of `scans`, each scan
 *  classified without the free-space test and with one holding all of them; and, with the
 *  test, how many of the mover's points (kPerson) lie less than `below` metres above the
 *  ground and how many of those were removed. */
struct WithAndWithoutLow
{
    WithAndWithout all;
    std::size_t low = 0, low_removed = 0;
};
WithAndWithoutLow offlineWithModel(const std::vector<Scan>& scans, const SensorModel& model,
                                   double below)
{
    PillarGrid grid(GridGeometry(), freeSpaceParams());
    grid.setSensorModel(model);
    for (const Scan& s : scans) grid.insertScan(s.view(), s.pose);
    const RangeImageLayout layout = RangeImageLayout::forSensor(model);
    FreeSpaceTest test(scans.size());
    for (const Scan& s : scans) test.add(s.view(), s.pose, layout);
    WithAndWithoutLow r{classifyWithAndWithout(grid, test, scans)};
    for (const Scan& s : scans)
    {
        std::vector<uint8_t> dyn;
        grid.classify(s.view(), dyn, s.pose, &test);
        for (std::size_t k = 0; k < dyn.size(); ++k)
            if (s.what[k] == kPerson && s.z[k] < kGroundZ + below)
            {
                ++r.low;
                r.low_removed += dyn[k];
            }
    }
    return r;
}

}  // namespace

TEST(FreeSpaceTest, AWalkerIsRemovedGroundWallAndPoleStay)
{
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = makeScans(ego);
        const auto [without, with] = withAndWithoutTheTest(scans);
        // Measured: the map alone removes 34 % (standing) and 38 % (moving) of the walker, with
        // the test 98 %; it adds no removal of the ground, the wall or the pole.
        EXPECT_LT(without.pct(kPerson), 50.0) << "the map alone should keep the walker";
        EXPECT_GE(with.pct(kPerson), 90.0);
        // What the test must not remove: static things, a hedge with a gap in one scan (seen
        // occupied on both sides of it in time), and a mover too low to tell from the ground.
        for (const What w : {kGround, kWall, kPole, kHedge, kLow})
        {
            EXPECT_GT(with.n[w], 100u);
            EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
            if (w != kLow)
            {
                EXPECT_LE(with.pct(w), 2.0) << "kind " << int(w);
            }
        }
    }
}

// Rings 2 degrees apart (a VLP-16's): for two scans the sensor sees a wall 39 m away and puts a
// ring on the ground 24 m away, in a pillar the map then holds a floor in. Then it stands 1 m
// farther back, and a walker who hardly moves stands in that pillar for eight scans: the ring
// below its lowest one now meets the ground before the pillar, so the lowest return there is
// the walker's own ring 0.8 m up, which the clearance would take for the ground; with the ring
// above it, too little is left clear of it to make an object. The floor lies more than
// free_space_min_extent below that ring, and the walker is tested from the floor up.
TEST(FreeSpaceTest, AWalkersLowestRingIsTestedWhereTheMapHoldsTheFloorBelowIt)
{
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        const bool walker = i >= 2;
        Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        pose.translation().x() = walker ? -10.0 : -9.0;
        const Eigen::Vector3d o = pose.translation();
        const double y = -1.0 + 0.05 * i;
        std::optional<std::pair<Eigen::Vector3d, Eigen::Vector3d>> person;
        if (walker)
            person.emplace(Eigen::Vector3d(15.05, y - 0.2, kGroundZ),
                           Eigen::Vector3d(15.45, y + 0.2, kGroundZ + 1.7));
        scans.push_back(rayScan(
            pose, 20.0,
            [&](const Eigen::Vector3d& d, double& range)
            { return groundWallAndPerson(o, d, 30.0, person, range); },
            2.0));
    }
    const Params prm = freeSpaceParams();
    PillarGrid grid(GridGeometry(), prm);
    for (const Scan& s : scans) grid.insertScan(s.view(), s.pose);
    const FreeSpaceTest test = holding(scans);
    const auto [without, with] = classifyWithAndWithout(grid, test, scans);
    // Measured: the map alone removes 5 % of the walker (76 points), the test 100 % (5 %, no
    // more than the map, with the lowest return taken for the ground).
    EXPECT_GT(with.n[kPerson], 20u);
    EXPECT_LT(without.pct(kPerson), 50.0);
    EXPECT_GE(with.pct(kPerson), 90.0);
    expectGroundAndWallAsTheMapHasThem(with, without);
}

// The bicycle's low part reaches 0.6 m beyond its rider on both sides, into pillars where it
// is all there is above the ground: 0.3 m above the clearance, too little to make an object
// there (free_space_min_extent 0.5). Next to a pillar of a mover (here the map already removes
// the rider, which runs into its own shadow), it is tested as part of it; and so is what lies
// under the rider, in the rider's own pillars, where the map kept it.
TEST(FreeSpaceTest, TheLowPartsOfAMoverGoWithItIntoTheNextPillars)
{
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = makeScans(ego);
        const auto [without, with] = withAndWithoutTheTest(scans);
        // Measured: the map alone removes 16 % (standing) and 36 % (moving) of the wheels, with
        // the test 87 % either way (56 % and 79 % with the neighbours only, the map alone's
        // when only the pillars the test itself shows gone count as a mover's); the rider
        // 99.7-100 % (98.6-100 % without its own pillars).
        EXPECT_GT(with.n[kWheels], 300u);
        EXPECT_GE(with.pct(kRider), 95.0);
        EXPECT_GE(with.pct(kWheels), 80.0);
        EXPECT_GE(with.pct(kWheels), without.pct(kWheels) + 30.0);
        for (const What w : {kGround, kWall, kPole, kHedge, kLow})
            EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
    }
}

// Rings 1.7 degrees apart (a 16-beam LiDAR's), the sensor moving 0.5 m per scan toward a walker
// who crosses 10 m ahead, over ground with a 10 % crossfall (terrain). Next to the walker's
// pillars, a pillar holding one ring of ground has nothing clear of it and is tested from its
// ground up; that ring runs along the beams (the scan's own beam above it lands beyond it, the one
// below in front of it), so other scans' beams a little above it land beyond it on the same
// ground: they say nothing of it, and it is not judged. The same map online, judging the last
// scan with a test that holds it and with one that does not, gives the same classes.
TEST(FreeSpaceTest, GroundAlongTheBeamsNextToAWalkerIsNotJudged)
{
    const SensorModel model = ringsEvery(1.7);
    const RangeImageLayout layout = RangeImageLayout::forSensor(model);
    const std::vector<Scan> scans = movingSensorScans(
        0.5, 60.0,
        [](int i, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
        {
            const double y = -1.5 + 0.3 * i;
            const std::pair<Eigen::Vector3d, Eigen::Vector3d> person{
                Eigen::Vector3d(10.3, y - 0.2, kGroundZ),
                Eigen::Vector3d(10.7, y + 0.2, kGroundZ + 1.7)};
            return groundWallAndPerson(o, d, 45.0, person, range, 0.1);
        },
        1.7);
    Params prm = freeSpaceParams();
    PillarGrid grid(GridGeometry(), prm);
    grid.setSensorModel(model);
    for (const Scan& s : scans) grid.insertScan(s.view(), s.pose);
    FreeSpaceTest test(scans.size());
    for (const Scan& s : scans) test.add(s.view(), s.pose, layout);
    const auto [without, with] = classifyWithAndWithout(grid, test, scans);
    // Measured: the map alone removes 87 % of the walker and 737 of 65,981 ground points (seen
    // once, 1.1 %); with the test, 96 % of the walker and 322 more ground points (0.5 %), 792
    // more (1.2 %) when such ground was judged.
    EXPECT_GE(with.pct(kPerson), 95.0);
    EXPECT_GT(with.n[kGround], 50000u);
    EXPECT_LE(with.removed[kGround] - without.removed[kGround], with.n[kGround] * 8 / 1000);

    prm.online = true;
    PillarGrid online(GridGeometry(), prm);
    online.setSensorModel(model);
    FreeSpaceTest past(FreeSpaceTest::capacityFor(prm));
    for (const Scan& s : scans)
    {
        online.insertScan(s.view(), s.pose);
        if (&s != &scans.back()) past.add(s.view(), s.pose, layout);
    }
    FreeSpaceTest with_last = past;
    with_last.add(scans.back().view(), scans.back().pose, layout);
    std::vector<uint8_t> held, unheld;
    online.classify(scans.back().view(), held, scans.back().pose, &with_last);
    online.classify(scans.back().view(), unheld, scans.back().pose, &past);
    EXPECT_EQ(held, unheld);
}

// Rings 0.85 degrees apart (a 32-beam LiDAR's); a car 1.5 m tall crosses 31 m ahead at 1.5 m
// per scan, over flat ground. The ring 3 degrees down meets its face 0.08 m above the road, and
// is the lowest return of the car's pillars (the road in front of them lies between two rings):
// their ground for the free-space test, within whose clearance nothing is tested. With the car
// shown gone above it, that ring goes too, each of its points on its own evidence: the scans
// before and after the car passed saw the road 1.5 m behind it. The road stays (the scans' beams
// through its points meet it).
TEST(FreeSpaceTest, AMoversLowestRingAtTheRoadsHeightGoesWithIt)
{
    const SensorModel model = ringsEvery(0.85);
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = movingSensorScans(
            ego, 60.0,
            [&](int i, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
            {
                const double y = -8.0 + 1.5 * i;
                const std::pair<Eigen::Vector3d, Eigen::Vector3d> car{
                    Eigen::Vector3d(30.9 + ego * i, y - 2.0, kGroundZ),
                    Eigen::Vector3d(32.7 + ego * i, y + 2.0, kGroundZ + 1.5)};
                return groundWallAndPerson(o, d, 60.0, car, range);
            },
            0.85);
        // The car's points less than 0.3 m above the road: its lowest ring.
        const auto [all, low, low_removed] = offlineWithModel(scans, model, 0.3);
        const auto& [without, with] = all;
        // Measured: 89 % (standing) and 74 % (moving) of the lowest ring's 368 points removed,
        // the car 97 % and 94 %; without this rule 6 % and 20 %, the car 77 % and 80 %. The test
        // removes 0 and 6 ground points of 133,500 more than the map alone.
        EXPECT_GE(low, 300u);
        EXPECT_GE(low_removed * 100, low * 65);
        EXPECT_GE(with.pct(kPerson), 90.0);
        EXPECT_GT(with.n[kGround], 100000u);
        EXPECT_LE(with.removed[kGround] - without.removed[kGround], with.n[kGround] / 1000);
        EXPECT_EQ(with.removed[kWall], without.removed[kWall]);
    }
}

/** Ten scans, rings 1.7 degrees apart (a 16-beam LiDAR's), of a sensor standing before the
 *  ground and a wall 45 m ahead: a box 0.4 m deep, 0.3-1.4 m above the road, crosses 22.2 m
 *  ahead at 1.2 m per scan, its back at y = `back` in the first scan, `length` m long (kPerson). */
std::vector<Scan> crossingBoxScans(double back, double length)
{
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        const double y = back + 1.2 * i;
        const std::pair<Eigen::Vector3d, Eigen::Vector3d> box{
            Eigen::Vector3d(22.2, y, kGroundZ + 0.3),
            Eigen::Vector3d(22.6, y + length, kGroundZ + 1.4)};
        scans.push_back(rayScan(
            pose, 60.0,
            [&](const Eigen::Vector3d& d, double& range)
            { return groundWallAndPerson(pose.translation(), d, 45.0, box, range); },
            1.7));
    }
    return scans;
}

// Online, rings 1.7 degrees apart (a 16-beam LiDAR's), the sensor standing: a box 0.3-1.4 m
// above the road crosses 22.2 m ahead at 1.2 m per scan, between the rings that meet the road
// (20.7 and 32.4 m away), so two rings meet it, 0.54 and 1.20 m up, and the lower is its
// pillars' ground for the test. No pillar of it is an object (one entry clear of the ground),
// none is next to one, and the map holds each entry static after its one sighting (p_empty_init
// 0.5, a pillar no scan had hit): the pillars new in the map show it, the beams of the scans
// before it having passed where it stands. The road and the wall stay.
TEST(FreeSpaceTest, OnlineAMoverTooSmallForAnObjectIsShownWhereItIsNew)
{
    const SensorModel model = ringsEvery(1.7);
    const auto [without, with] =
        onlineWithAndWithout(crossingBoxScans(-6.4, 0.8), onlineParams(), nullptr, model);
    // Measured: 81 % of the box's 208 points removed (none in the first scan, which has no past;
    // none before new pillars were tested), the map alone none; no ground or wall point.
    EXPECT_GT(with.n[kGround], 10000u);
    expectTheMoverGoes(with, without, kPerson, 150u, 70.0);
}

// Online, as above (rings 1.7 degrees apart, the sensor standing), a car 2 m long crossing 22.2
// m ahead at 1.2 m per scan, 0.3-1.4 m above the road: two rings meet it, the lower its pillars'
// ground to the test. Its front pillars are new in the map and shown gone as such; its back
// ones held part of it the scan before too, so they are not new, and nothing there made them
// a mover's neighbours. They are next to the front's, and are tested with that mover.
TEST(FreeSpaceTest, OnlineWhatIsNextToAMoverShownNewGoesWithIt)
{
    const SensorModel model = ringsEvery(1.7);
    const auto [without, with] =
        onlineWithAndWithout(crossingBoxScans(-8.0, 2.0), onlineParams(), nullptr, model);
    // Measured: 82.4 % of the car's 512 points removed (77.3 % with only the pillars next to a
    // mover shown otherwise tested with it; none in the first scan, which has no past), the
    // map alone none; no ground or wall point.
    expectTheMoverGoes(with, without, kPerson, 400u, 80.0);
}

// Online, rings 0.4 degrees apart, the sensor standing at the foot of a road that climbs 9 %
// from 10 m ahead to a crest 32 m ahead, flat beyond it; a row of buildings 70 m ahead, 10 m
// tall, with a gap 5 m wide. A low trailer (0.45 m tall, 2 m long) crosses 30 m ahead at 1.2 m
// per scan on the slope, all of it above the sensor's height: the road under it is out of
// sight, and two rings meet it in each pillar, too little for an object. Where it stands, the
// beams of the scans before it returned from the buildings behind it, or, through the gap,
// nothing: they passed over the crest into the sky. Its pillars are new in the map, and a
// beam into the sky is evidence there too: the same rings returned from the buildings within
// a pillar's width of it, so they were firing there and would have returned from the trailer.
TEST(FreeSpaceTest, OnlineASkyBehindWhatIsNewIsSeenThrough)
{
    const SensorModel model = ringsEvery(0.4);
    constexpr double kSlope = 0.09, kFoot = 10.0, kCrest = 32.0, kGap = 5.0;
    const double top = kGroundZ + kSlope * (kCrest - kFoot);    // the flat beyond the crest
    const double floor_z = kGroundZ + kSlope * (30.0 - kFoot);  // the road under the trailer
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        const double y = -6.0 + 1.2 * i;  // the trailer's back
        scans.push_back(rayScan(
            pose, 60.0,
            [&](const Eigen::Vector3d& d, double& range)
            {
                range = 80.0;
                What w = kNothing;
                auto take = [&](double s, What hit)
                {
                    if (s > 1e-6 && s < range) range = s, w = hit;
                };
                if (d.z() < 0.0)  // the flat road to the foot
                {
                    const double s = kGroundZ / d.z();
                    if (s * d.x() <= kFoot) take(s, kGround);
                }
                if (d.z() - kSlope * d.x() < 0.0)  // the slope
                {
                    const double s = (kGroundZ - kSlope * kFoot) / (d.z() - kSlope * d.x());
                    if (s * d.x() > kFoot && s * d.x() <= kCrest) take(s, kGround);
                }
                if (d.z() > 0.0)  // beyond the crest
                {
                    const double s = top / d.z();
                    if (s * d.x() > kCrest) take(s, kGround);
                }
                if (d.x() > 0.0)  // the buildings, but their gap
                {
                    const double s = 70.0 / d.x();
                    const Eigen::Vector3d p = s * d;
                    if (std::abs(p.y()) > 0.5 * kGap && p.z() < top + 10.0) take(s, kWall);
                }
                hitBox(Eigen::Vector3d::Zero(), d, Eigen::Vector3d(30.0, y, floor_z + 0.3),
                       Eigen::Vector3d(30.4, y + 2.0, floor_z + 0.75), kPerson, range, take);
                return w;
            }));
    }
    const auto [without, with] = onlineWithAndWithout(scans, onlineParams(), nullptr, model);
    // Measured: 60.6 % of the trailer's 545 points removed (49.9 % with the beams into the sky
    // no evidence: the scans in which it stands before the gap; none in the first scan, which
    // has no past), the map alone none; no ground or wall point.
    EXPECT_GT(with.n[kWall], 10000u);
    expectTheMoverGoes(with, without, kPerson, 400u, 57.0);
}

// Online, the sensor standing (rings 0.4 degrees apart): two cyclists ride one behind the other
// across the view 15 m ahead at 0.3 m per scan (3 m/s), each 0.6 m long, 1.5 m apart. Where the
// second one stands in the last scans, the first one stood in the first scans, and the scans
// between saw through that place. Walking in from the farthest scan of the past, the first one
// settles the place as occupied all along; but two scans in a row right before the second one
// came saw it empty, and its side faces the beams (no flicker in foliage): it came, it did not
// stand there. Straight ahead, where the image's columns are densest, the ring's neighbouring
// returns lie three to four columns apart: facesBeams() reads a horizontal step of the sensor.
TEST(FreeSpaceTest, OnlineAPlaceSeenEmptyJustBeforeWhatStandsThereShowsItCame)
{
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        const double front = 0.3 * i;  // the first cyclist's front
        scans.push_back(rayScan(
            pose, 60.0,
            [&](const Eigen::Vector3d& d, double& range)
            {
                What w =
                    groundWallAndPerson(pose.translation(), d, 45.0,
                                        std::pair{Eigen::Vector3d(14.8, front - 0.6, kGroundZ),
                                                  Eigen::Vector3d(15.2, front, kGroundZ + 1.7)},
                                        range);
                hitBox(pose.translation(), d, Eigen::Vector3d(14.8, front - 2.7, kGroundZ),
                       Eigen::Vector3d(15.2, front - 2.1, kGroundZ + 1.7), kRider, range,
                       [&](double s, What hit)
                       {
                           if (s > 1e-6 && s < range) range = s, w = hit;
                       });
                return w;
            }));
    }
    const auto [without, with] =
        onlineWithAndWithout(scans, onlineParams(), nullptr, ringsEvery(0.4));
    // Measured: the second cyclist 89.9 % of 2,021 points removed (76.4 % without the rule, or
    // with facesBeams() reading two columns: none of its eighth scan), the first 85.2 %; the
    // map alone none of the second; no ground or wall point.
    EXPECT_GE(with.pct(kPerson), 80.0);
    expectTheMoverGoes(with, without, kRider, 1500u, 85.0);
}

TEST(FreeSpaceTest, OffByDefaultAndOnlyScansWithinTheWindowCount)
{
    const std::vector<Scan> scans = makeScans();
    Params off = freeSpaceParams();
    off.free_space_window = 0;
    EXPECT_EQ(offline(scans, off, true).removed[kPerson],
              offline(scans, freeSpaceParams(), false).removed[kPerson]);
    // The first scan with one scan after it: the walker moved 0.15 m, less than its width, so
    // about half of it was seen through; with the whole clip, all of it (measured 47 % and
    // 97 %).
    Params near = freeSpaceParams();
    near.free_space_window = 1;
    PillarGrid grid(GridGeometry(), freeSpaceParams()), grid1(GridGeometry(), near);
    for (const Scan& s : scans)
    {
        grid.insertScan(s.view(), s.pose);
        grid1.insertScan(s.view(), s.pose);
    }
    const FreeSpaceTest test = holding(scans);
    std::vector<uint8_t> dyn;
    Removed all, one;
    EXPECT_EQ(grid.classify(scans[0].view(), dyn, scans[0].pose, &test).free_space_scans, 9u);
    all.add(scans[0], dyn);
    EXPECT_EQ(grid1.classify(scans[0].view(), dyn, scans[0].pose, &test).free_space_scans, 1u);
    one.add(scans[0], dyn);
    EXPECT_GE(all.pct(kPerson), 90.0);
    EXPECT_LT(one.pct(kPerson), 70.0);
}

TEST(FreeSpaceTest, AScanIsNoEvidenceAboutItselfAndOnlineSeesThePastOnly)
{
    const std::vector<Scan> scans = makeScans();
    PillarGrid grid(GridGeometry(), freeSpaceParams());
    for (const Scan& s : scans) grid.insertScan(s.view(), s.pose);
    std::vector<uint8_t> dyn;

    // A test holding the scan alone says nothing about it.
    FreeSpaceTest alone(1);
    alone.add(scans[4].view(), scans[4].pose, kLayout);
    const ClassifyStats st = grid.classify(scans[4].view(), dyn, scans[4].pose, &alone);
    EXPECT_EQ(st.seen_through_points, 0u);
    EXPECT_EQ(st.free_space_scans, 0u);

    // Online: the map and the test of the scans up to scan 6. Scan 6 added to the test (as an
    // online map does when inserting it) is judged by the scans before it, the same as when the
    // test does not hold it (a scan newer than all it holds).
    Params online_prm = freeSpaceParams();
    online_prm.online = true;
    PillarGrid online_grid(GridGeometry(), online_prm);
    FreeSpaceTest past(FreeSpaceTest::capacityFor(online_prm));
    EXPECT_EQ(past.capacity(), 11u);
    for (std::size_t i = 0; i < 6; ++i)
    {
        online_grid.insertScan(scans[i].view(), scans[i].pose);
        past.add(scans[i].view(), scans[i].pose, kLayout);
    }
    const Scan& now = scans[6];
    online_grid.insertScan(now.view(), now.pose);
    std::vector<uint8_t> map_only;
    online_grid.classify(now.view(), map_only, now.pose);
    const ClassifyStats online = online_grid.classify(now.view(), dyn, now.pose, &past);
    EXPECT_EQ(online.free_space_scans, 6u);
    FreeSpaceTest with_now = past;
    with_now.add(now.view(), now.pose, kLayout);
    std::vector<uint8_t> dyn_held;
    EXPECT_EQ(online_grid.classify(now.view(), dyn_held, now.pose, &with_now).free_space_scans, 6u);
    EXPECT_EQ(dyn_held, dyn);
    Removed before, after;
    before.add(now, map_only);
    after.add(now, dyn);
    EXPECT_GT(online.seen_through_points, 0u);
    // Every point the test turned dynamic is counted, the repeats of a marked point included.
    std::size_t turned = 0;
    for (std::size_t i = 0; i < dyn.size(); ++i) turned += dyn[i] == 1 && map_only[i] == 0;
    EXPECT_EQ(online.seen_through_points, turned);
    EXPECT_EQ(online.dynamic_points - online.seen_through_points,
              static_cast<std::size_t>(std::count(map_only.begin(), map_only.end(), 1)));
    EXPECT_GE(after.pct(kPerson), 90.0);
    EXPECT_LT(before.pct(kPerson), after.pct(kPerson) - 20.0);
    // The first scan has no past: nothing shows its walker gone.
    const FreeSpaceTest none(11);
    EXPECT_EQ(grid.classify(scans[0].view(), dyn, scans[0].pose, &none).seen_through_points, 0u);
}

// The walker crosses in the direction of the sweep (azimuth increasing, y increasing), so the
// first point of each of its rows in a pillar is its trailing edge, the rest repeats of it.
// The test reads both ends of a row: one scan after it appeared, the leading edge, where the
// scan before saw through, shows it gone, whichever way the sensor sweeps.
TEST(FreeSpaceTest, AWalkerIsShownByItsLeadingEdgeWhicheverWayTheSweepGoes)
{
    const std::vector<Scan> forward = makeScans();
    std::vector<Scan> backward = forward;
    for (Scan& s : backward)
    {
        std::reverse(s.x.begin(), s.x.end());
        std::reverse(s.y.begin(), s.y.end());
        std::reverse(s.z.begin(), s.z.end());
        std::reverse(s.what.begin(), s.what.end());
    }
    Params prm = freeSpaceParams();
    prm.free_space_fraction = 0.4;  // kitti-online.ini
    auto secondScanOnline = [&](const std::vector<Scan>& scans)
    {
        PillarGrid grid(GridGeometry(), prm);
        FreeSpaceTest past(1);
        grid.insertScan(scans[0].view(), scans[0].pose);
        past.add(scans[0].view(), scans[0].pose, kLayout);
        grid.insertScan(scans[1].view(), scans[1].pose);
        std::vector<uint8_t> dyn;
        grid.classify(scans[1].view(), dyn, scans[1].pose, &past);
        Removed r;
        r.add(scans[1], dyn);
        return r;
    };
    const Removed fwd = secondScanOnline(forward), bwd = secondScanOnline(backward);
    // Measured: 87.5 % either way (0 % reading the first point of each row alone, forward).
    EXPECT_GE(fwd.pct(kPerson), 80.0);
    EXPECT_EQ(fwd.removed[kPerson], bwd.removed[kPerson]);
    for (const What w : {kGround, kWall, kPole, kHedge})
        EXPECT_LE(fwd.pct(w), 2.0) << "kind " << int(w);
}

// A person walking towards the sensor along its line of sight at 0.08 m per scan (0.8 m/s),
// 15 m away, in front of the wall: every other scan's beam toward a point of the person lands on
// the person again, within the margin (0.6 m there) of the point, so "seen through" never
// holds; but judge after judge the beam returns farther beyond the point, on the same surface.
// The ground and the wall behind stay (their beams scatter around the point).
/** Ten scans of a person `start` m ahead (15.2 by default) walking towards the sensor at `step`
 *  m per scan (away from it for a negative one) along its line of sight, a wall behind, the
 *  sensor moving `ego` m per scan along x. With a `stride`, the person's front and the wall
 *  swing that far back and forth from one scan to the next. */
std::vector<Scan> radialWalkerScans(double ego, double step = 0.08, double start = 15.2,
                                    double stride = 0.0)
{
    return movingSensorScans(
        ego, 30.0,
        [&](int i, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
        {
            const double swing = (i % 2 == 0 ? 0.5 : -0.5) * stride;
            const double x = start - step * i + swing;
            const std::pair<Eigen::Vector3d, Eigen::Vector3d> person{
                Eigen::Vector3d(x - 0.2, 0.8, kGroundZ),
                Eigen::Vector3d(x + 0.2, 1.2, kGroundZ + 1.7)};
            return groundWallAndPerson(o, d, 25.5 + swing, person, range);
        });
}

TEST(FreeSpaceTest, APersonWalkingAlongTheLineOfSightIsShownByASteadyDrift)
{
    // Standing, and moving towards the person (from each pose the person's points lie at other
    // elevations, often between two rows of beams).
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = radialWalkerScans(ego);
        const auto [without, with] = withAndWithoutTheTest(scans);
        // Measured, standing (moving): the map alone removes 10 % of the person (7 %); the test
        // 40 % before the steady drift was followed, 80 % (54 %) with the drift read from each
        // judge's own cell only, 80 % (99.8 %) with the beam nearest the point's elevation.
        EXPECT_GT(with.n[kPerson], 1000u);
        EXPECT_LT(without.pct(kPerson), 20.0);
        EXPECT_GE(with.pct(kPerson), 70.0);
        expectGroundAndWallAsTheMapHasThem(with, without);
    }
}

// The same at 0.05 m per scan (0.5 m/s): the person drifts a drift's size where a beam beside
// the point may land on a slanted surface (0.45 m at 15 m) only nine scans away, more than most
// scans of the clip have on either side. The person's own scan shows a surface facing its beams
// and flat to them (its neighbouring returns at its range), where a drift beyond the margin's
// share for range noise and pose error (0.15 m, four scans away) has its size.
TEST(FreeSpaceTest, ASlowWalkerIsShownWhereItsSurfaceFacesTheBeams)
{
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = radialWalkerScans(ego, 0.05);
        const auto [without, with] = withAndWithoutTheTest(scans);
        // Measured, standing (moving): the map alone 11.4 % (8.5 %); the test 22.1 % (47.1 %)
        // with a drift's size the same on every surface, 80.2 % (66.8 %) with the margin's
        // base as the size on a surface facing the beams, 100 % (100 %) now.
        EXPECT_GT(with.n[kPerson], 1000u);
        EXPECT_GE(with.pct(kPerson), 95.0);
        for (const What w : {kGround, kWall})
        {
            EXPECT_GT(with.n[w], 1000u);
            EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
        }
    }
}

// Online, a person walking towards the sensor along its line of sight at 0.16 m per scan (1.6
// m/s), 15 m away: the third scan has two scans of past, whose beams toward a point of the
// person land on it again 0.16 and 0.32 m beyond the point, within the margin (0.6 m there). A
// steady drift, the second judge's offset beyond the margin's share for range noise and pose
// error; on a surface that faces the beams (the person's front) two judges are enough.
TEST(FreeSpaceTest, OnlineTwoPastScansShowAWalkerFacingTheBeamsDrifting)
{
    const std::vector<Scan> scans = radialWalkerScans(0.0, 0.16);
    std::vector<WithAndWithout> per_scan;
    const WithAndWithout all = onlineWithAndWithout(scans, onlineParams(), &per_scan);
    ASSERT_EQ(per_scan.size(), scans.size());
    const Removed& third = per_scan[2].with;
    // Measured: all 136 points of the third scan's person (none when three judges were
    // needed, none by the map alone), 85.5 % of the clip's (76.1 %; the map alone 19.0 %).
    EXPECT_GT(third.n[kPerson], 100u);
    EXPECT_EQ(per_scan[2].without.removed[kPerson], 0u);
    EXPECT_GE(third.pct(kPerson), 90.0);
    EXPECT_GE(all.with.pct(kPerson), 80.0);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(all.with.n[w], 1000u);
        EXPECT_EQ(all.with.removed[w], all.without.removed[w]) << "kind " << int(w);
    }
}

/** Online, the mover (kPerson) of each scan `ks` of `per_scan` (more than `min_points` points)
 *  removed 90 % or more with the free-space test, none of it by the map alone. */
void expectTheMoverShownIn(const std::vector<WithAndWithout>& per_scan,
                           std::initializer_list<std::size_t> ks, std::size_t min_points)
{
    for (const std::size_t k : ks)
    {
        SCOPED_TRACE("scan " + std::to_string(k));
        ASSERT_LT(k, per_scan.size());
        EXPECT_GT(per_scan[k].with.n[kPerson], min_points);
        EXPECT_EQ(per_scan[k].without.removed[kPerson], 0u);
        EXPECT_GE(per_scan[k].with.pct(kPerson), 90.0);
    }
}

// Online, the same person at half that pace, 0.08 m per scan (0.8 m/s): the past's beams toward
// a point of the person's front land on it again 0.08 and 0.16 m beyond the point in the third
// scan, 0.08 to 0.24 m in the fourth. The front is flat to the beams (its neighbouring returns
// at the point's range), so a beam a little off the point's direction lands where one toward
// it would: a drift beyond the margin's share for range noise and pose error (0.15 m) is a
// drift there, from the third scan on; the base of the margin (0.3 m) would wait for the fifth.
TEST(FreeSpaceTest, OnlineASlowWalkerFlatToTheBeamsIsShownOnceItsDriftPassesTheNoise)
{
    const std::vector<Scan> scans = radialWalkerScans(0.0, 0.08);
    std::vector<WithAndWithout> per_scan;
    const WithAndWithout all = onlineWithAndWithout(scans, onlineParams(), &per_scan);
    ASSERT_EQ(per_scan.size(), scans.size());
    // Measured: the third and fourth scans' person 100 % each (none with the margin's base as
    // the size, which shows it from the fifth scan on), the clip's 85.0 % (65.2 %); the map
    // alone none of those two scans' (4.7 % of the clip's).
    expectTheMoverShownIn(per_scan, {2, 3}, 100);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(all.with.n[w], 1000u);
        EXPECT_EQ(all.with.removed[w], all.without.removed[w]) << "kind " << int(w);
    }
}

/** Ten scans of a standing sensor over the 60 degrees ahead: the ground, a wall at x = 25.5
 *  and a mover (kPerson), a vertical cylinder of radius `radius` and 1.7 m tall, walking away
 *  along the line of sight at azimuth `az_deg`, `step` m per scan from 15.2 m; with `pole`, a
 *  standing one of the same shape 14 m away at azimuth -`az_deg`. */
std::vector<Scan> awayWalkerScans(double step, double radius, double az_deg, bool pole)
{
    const double a = az_deg * M_PI / 180.0;
    return movingSensorScans(
        0.0, 30.0,
        [&](int i, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
        {
            What what = groundWallAndPerson(o, d, 25.5, std::nullopt, range);
            auto take = [&](double s, What w)
            {
                if (s > 1e-6 && s < range) range = s, what = w;
            };
            const double rho = 15.2 + step * i;
            hitCylinder(o, d, rho * std::cos(a), rho * std::sin(a), radius, 1.7, kPerson, take);
            if (pole)
                hitCylinder(o, d, 14.0 * std::cos(a), -14.0 * std::sin(a), radius, 1.7, kPole,
                            take);
            return what;
        });
}

// Online, a thing one beam wide (a post 0.06 m across, 15-16 m away along the azimuth of a
// column of beams 0.2 degrees, 0.05 m, apart: a leg, an arm or a head of a walker seen by a
// sparser sensor) walking away along the line of sight at 0.12 m per scan. It faces the beams in
// its column, and what lies beside it in its row is the wall 10 m behind, so another scan's beam
// that returned within the margin of it met the same post: two judges and the margin's share for
// range noise show its drift, from the third scan on. A pole of the same shape standing 2 m beside
// it stays.
TEST(FreeSpaceTest, OnlineAThingOneBeamWideIsShownByItsDrift)
{
    const std::vector<Scan> scans = awayWalkerScans(0.12, 0.03, 4.0, true);
    std::vector<WithAndWithout> per_scan;
    const WithAndWithout all = onlineWithAndWithout(scans, onlineParams(), &per_scan);
    ASSERT_EQ(per_scan.size(), scans.size());
    // Measured: the third and fourth scans' post all removed (none where a thing one beam wide
    // did not face the beams: three judges and most of the margin), 79.9 % of the clip's (the
    // map alone 18.9 %).
    expectTheMoverShownIn(per_scan, {2, 3}, 12);
    EXPECT_GT(all.with.n[kPole], 150u);
    for (const What w : {kGround, kWall, kPole})
        EXPECT_EQ(all.with.removed[w], all.without.removed[w]) << "kind " << int(w);
}

// Online, a rounded walker (a cylinder 0.4 m across, 15 m away) walking away along the line of
// sight at 0.08 m per scan. The ends of each ring's run across it lie where the body turns
// away from the beams: the returns beside them step 0.1 m and more in range, so a drift there
// must pass the noise share and half that step. The middle of the run faces the beams flat:
// from the third scan on, two judges show it 0.16 m off, past the noise share alone.
TEST(FreeSpaceTest, OnlineTheMiddleOfARoundedWalkerShowsItsDriftBeforeItsEdges)
{
    const std::vector<Scan> scans = awayWalkerScans(0.08, 0.2, 5.6, false);
    std::vector<WithAndWithout> per_scan;
    const WithAndWithout all = onlineWithAndWithout(scans, onlineParams(), &per_scan);
    ASSERT_EQ(per_scan.size(), scans.size());
    // Measured: the third scan's walker 90 % or more (none with the ends of the runs tested
    // alone), 79.2 % of the clip's (none by the map alone).
    expectTheMoverShownIn(per_scan, {2}, 100);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(all.with.n[w], 1000u);
        EXPECT_EQ(all.with.removed[w], all.without.removed[w]) << "kind " << int(w);
    }
}

// A person walking along the line of sight at 0.08 m per scan, away from the sensor or towards
// it, whose front swings 0.12 m back and forth from one scan to the next (a stride: arms and
// legs): most judges see it within the margin, and the swing breaks the steady drift (each beam
// no nearer to the point than the previous one), but the scans before see it on one side of the
// point and those after on the other, by more than the margin between them. A wall that swings
// as much but stays where it is stays.
TEST(FreeSpaceTest, AWalkerSeenNearerBeforeAndFartherAfterIsShownWhateverItsStride)
{
    for (const double step : {-0.08, 0.08})  // away, then towards: 14.4 m away mid-clip
        for (const double ego : {0.0, 0.3})
        {
            SCOPED_TRACE(std::string(step < 0.0 ? "away" : "towards") + ", sensor moving " +
                         std::to_string(ego) + " m per scan");
            const std::vector<Scan> scans = radialWalkerScans(ego, step, 14.4 + 5.0 * step, 0.12);
            const auto [without, with] = withAndWithoutTheTest(scans);
            EXPECT_GT(with.n[kPerson], 1000u);
            // Measured, away (towards), standing and moving: the map alone 13.8 and 12.3 % (18.5
            // and 21.4 %); the test 53.5 and 43.9 % (68.9 and 67.5 %) before the two sides were
            // compared, 99.2 and 88.6 % (98.9 and 93.4 %) with it.
            EXPECT_GE(with.pct(kPerson), 80.0);
            for (const What w : {kGround, kWall})
            {
                EXPECT_GT(with.n[w], 1000u);
                EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
            }
        }
}

TEST(FreeSpaceTestScans, TheNewestAreKeptAndAScanIsFoundByItsPointsAndPose)
{
    const std::vector<Scan> scans = makeScans();
    Params p = freeSpaceParams();
    p.online = false;
    EXPECT_EQ(FreeSpaceTest::capacityFor(p), 21u);  // 10 on each side of the one classified
    p.free_space_window = 0;
    EXPECT_EQ(FreeSpaceTest::capacityFor(p), 0u);
    FreeSpaceTest off;  // capacity 0: keeps nothing
    off.add(scans[0].view(), scans[0].pose, kLayout);
    EXPECT_TRUE(off.empty());

    FreeSpaceTest t(3);
    for (std::size_t i = 0; i < 5; ++i) t.add(scans[i].view(), scans[i].pose, kLayout);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_FALSE(t.find(scans[1].view(), scans[1].pose));
    EXPECT_EQ(t.find(scans[2].view(), scans[2].pose), std::optional<std::size_t>(0));
    EXPECT_EQ(t.find(scans[4].view(), scans[4].pose), std::optional<std::size_t>(2));
    // The same points at another pose, one point fewer, or a point the fingerprint reads moved
    // by a float's last bit, are another scan.
    Eigen::Isometry3d moved = scans[4].pose;
    moved.translation().x() += 1e-9;
    EXPECT_FALSE(t.find(scans[4].view(), moved));
    Scan nudged = scans[4];
    nudged.z[0] = std::nextafter(nudged.z[0], 1.0f);
    EXPECT_FALSE(t.find(nudged.view(), nudged.pose));
    PointsView fewer = scans[4].view();
    --fewer.size;
    EXPECT_FALSE(t.find(fewer, scans[4].pose));
    EXPECT_EQ(FreeSpaceTest::fingerprint(scans[4].view(), scans[4].pose),
              t.scans().back().fingerprint);
    std::size_t image_bytes = 0;  // the test holds at least its three images
    for (const FreeSpaceTest::Scan& s : t.scans()) image_bytes += s.image.memoryBytes();
    EXPECT_GT(image_bytes, 3 * 2 * 32u);  // each has at least one block with a return
    EXPECT_GE(t.memoryBytes(), image_bytes);

    // A test sliding over many scans holds the same memory; a smaller capacity drops the
    // oldest; a scan as kept by another test is taken whole, one of the wrong size refused.
    std::size_t bytes_at_20 = 0;
    for (std::size_t id = 0; id < 60; ++id)
    {
        t.add(scans[id % scans.size()].view(), scans[id % scans.size()].pose, kLayout);
        if (id == 20) bytes_at_20 = t.memoryBytes();
    }
    EXPECT_EQ(t.memoryBytes(), bytes_at_20);
    t.setCapacity(2);
    EXPECT_EQ(t.size(), 2u);
    FreeSpaceTest copy(2);
    for (const FreeSpaceTest::Scan& s : t.scans()) copy.add(s);
    EXPECT_TRUE(copy == t);
    FreeSpaceTest::Scan bad = t.scans().front();
    bad.image.assign(bad.layout.rows - 1, bad.layout.cols,
                     std::vector<uint16_t>(static_cast<std::size_t>(bad.layout.rows - 1) *
                                               static_cast<std::size_t>(bad.layout.cols),
                                           FreeSpaceTest::kNoReturn));
    EXPECT_THROW(copy.add(bad), std::invalid_argument);
}

// A scan made apart (ScanMaker, as hif-clean's second pass does on another thread) is the scan
// the test makes from the same points: the same fingerprint, pose and cells, whichever scan the
// maker made before.
TEST(FreeSpaceTestScans, AScanMadeApartIsTheOneAddedByItsPoints)
{
    const std::vector<Scan> scans = makeScans(0.3);
    ASSERT_GE(scans.size(), 4u);
    FreeSpaceTest by_points(3), made(3);
    FreeSpaceTest::ScanMaker maker;
    for (std::size_t i = 0; i < scans.size(); ++i)
    {
        by_points.add(scans[i].view(), scans[i].pose, kLayout);
        made.add(maker.make(scans[i].view(), scans[i].pose, kLayout));
    }
    ASSERT_EQ(made.size(), 3u);
    EXPECT_TRUE(made == by_points);
    const FreeSpaceTest::Scan again = maker.make(scans[0].view(), scans[0].pose, kLayout);
    EXPECT_EQ(again.fingerprint, FreeSpaceTest::fingerprint(scans[0].view(), scans[0].pose));
    FreeSpaceTest first(1), first_made(1);
    first.add(scans[0].view(), scans[0].pose, kLayout);
    first_made.add(again);
    EXPECT_TRUE(first_made == first);
    FreeSpaceTest second(1);  // another scan: the comparison can fail
    second.add(scans[1].view(), scans[1].pose, kLayout);
    EXPECT_FALSE(first_made == second);
    EXPECT_GT(maker.memoryBytes(), 0u);
}

// Online, the test keeps the scan just inserted with the image its insertion built for the
// see-through gate, converted once: the same cells as an image built from the points, returns
// a cell cannot hold (from 655.34 m on) and invalid points read as none in both. A scan other
// than the one inserted, or one an offline grid inserted, has its image built from its points.
TEST(FreeSpaceTestScans, TheScanJustInsertedKeepsTheImageItsInsertionBuilt)
{
    std::vector<Scan> scans = makeScans(0.3);
    for (Scan& s : scans)
    {
        double az = 0.0;  // each in a cell of its own
        for (const double r : {655.33, 655.342, 700.0, std::numeric_limits<double>::quiet_NaN()})
        {
            az += 0.01;
            s.x.push_back(static_cast<float>(r * std::cos(az)));
            s.y.push_back(static_cast<float>(r * std::sin(az)));
            s.z.push_back(0.0f);
            s.what.push_back(kNothing);
        }
    }
    const Params online = freeSpaceParams();
    ASSERT_TRUE(online.online);
    PillarGrid grid(GridGeometry(), online);
    FreeSpaceTest from_insertion(FreeSpaceTest::capacityFor(online));
    FreeSpaceTest from_points(FreeSpaceTest::capacityFor(online));
    for (const Scan& s : scans)
    {
        grid.insertScan(s.view(), s.pose);
        from_insertion.add(s.view(), s.pose, grid);
        from_points.add(s.view(), s.pose, grid.imageLayout());
        EXPECT_TRUE(from_insertion == from_points);
    }
    ASSERT_EQ(from_insertion.size(), scans.size());

    // A return moved nearer after the insertion, where the fingerprint does not read (it reads
    // every 8th point of these scans): the image kept is the insertion's.
    const Scan& last = scans.back();
    ASSERT_GT(last.x.size() / FreeSpaceTest::kFingerprintPoints, 1u);
    Scan moved = last;
    moved.x[1] *= 0.5f;
    moved.y[1] *= 0.5f;
    moved.z[1] *= 0.5f;
    ASSERT_EQ(FreeSpaceTest::fingerprint(moved.view(), moved.pose),
              FreeSpaceTest::fingerprint(last.view(), last.pose));
    FreeSpaceTest kept(1), of_last(1), of_moved(1);
    kept.add(moved.view(), moved.pose, grid);
    of_last.add(last.view(), last.pose, grid.imageLayout());
    of_moved.add(moved.view(), moved.pose, grid.imageLayout());
    EXPECT_TRUE(kept == of_last);
    EXPECT_FALSE(kept == of_moved);

    // Not the scan inserted last: built from its points.
    FreeSpaceTest other(1), other_from_points(1);
    other.add(scans[3].view(), scans[3].pose, grid);
    other_from_points.add(scans[3].view(), scans[3].pose, grid.imageLayout());
    EXPECT_TRUE(other == other_from_points);

    // An offline grid keeps no image for the test: built from the points, the moved one too.
    Params offline = online;
    offline.online = false;
    PillarGrid offline_grid(GridGeometry(), offline);
    offline_grid.insertScan(last.view(), last.pose);
    FreeSpaceTest built(1), moved_offline(1);
    built.add(moved.view(), moved.pose, offline_grid);
    moved_offline.add(moved.view(), moved.pose, offline_grid.imageLayout());
    EXPECT_TRUE(built == moved_offline);
}

// An image keeps every cell, whole blocks of "no return" aside: a cell reads what it was, the
// returns are visited in order, and a sparse image takes less than its cells would.
TEST(FreeSpaceTestImage, EveryCellReadsWhatItWasAndEmptyBlocksTakeNoRoom)
{
    const int rows = 9, cols = 100;  // not a whole number of blocks a row
    std::vector<uint16_t> dense(static_cast<std::size_t>(rows) * cols, FreeSpaceTest::kNoReturn);
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> value(0, FreeSpaceTest::kNoReturn - 1);
    std::vector<std::pair<std::size_t, uint16_t>> want;
    for (int r = 0; r < rows; r += 2)  // returns on every other row, in a third of the columns
        for (int c = 0; c < cols; c += 3)
            dense[static_cast<std::size_t>(r) * cols + c] = static_cast<uint16_t>(value(rng));
    dense.back() = 7;  // the last cell of the last, partial block
    for (std::size_t k = 0; k < dense.size(); ++k)
        if (dense[k] != FreeSpaceTest::kNoReturn) want.emplace_back(k, dense[k]);

    FreeSpaceTest::Image img;
    img.assign(rows, cols, dense);
    ASSERT_EQ(img.rows(), rows);
    ASSERT_EQ(img.cols(), cols);
    for (int r = 0; r < rows; ++r)
        for (int c = 0; c < cols; ++c)
            ASSERT_EQ(img.at(r, c), dense[static_cast<std::size_t>(r) * cols + c]) << r << "," << c;
    std::vector<std::pair<std::size_t, uint16_t>> got;
    img.forEachReturn([&](std::size_t cell, uint16_t v) { got.emplace_back(cell, v); });
    EXPECT_EQ(got, want);
    EXPECT_LT(img.memoryBytes(), dense.size() * sizeof(uint16_t));

    FreeSpaceTest::Image same, other;
    same.assign(rows, cols, dense);
    EXPECT_TRUE(same == img);
    dense[5] = 1;  // a cell of a block without returns
    other.assign(rows, cols, dense);
    EXPECT_FALSE(other == img);
    EXPECT_THROW(other.assign(rows, cols + 1, dense), std::invalid_argument);
}

TEST(MinRange, NearPointsAreNotInsertedAndAreDynamic)
{
    Params prm;
    prm.min_range = 3.0;
    PillarGrid grid(GridGeometry(), prm);
    // 2.9 m away (in the sensor frame, whatever the pose), 3.1 m, and a NaN.
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<float> x = {2.9f, 3.1f, nan}, y = {0.0f, 0.0f, 0.0f}, z = {0.0f, 0.0f, 0.0f};
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(100.0, 50.0, 0.0);
    const PointsView v{x.data(), y.data(), z.data(), 3};
    const InsertStats ins = grid.insertScan(v, T);
    EXPECT_EQ(ins.points_used, 1u);
    EXPECT_EQ(ins.points_near, 1u);
    EXPECT_EQ(ins.points_invalid, 1u);
    EXPECT_EQ(grid.findPillar({102, 50}), nullptr) << "the near point was inserted";
    std::vector<uint8_t> dyn;
    const ClassifyStats st = grid.classify(v, dyn, T);
    EXPECT_EQ(dyn, (std::vector<uint8_t>{1, 0, 1}));
    EXPECT_EQ(st.near_points, 1u);
    EXPECT_EQ(st.invalid_points, 1u);
    // Off (0): the near point is an ordinary one.
    PillarGrid all;
    EXPECT_EQ(all.insertScan(v, T).points_used, 2u);
}

// Online, a van (taller than the sensor, so no beam passes over it) drives 18 m ahead of the
// sensor at its speed, 1.3 m a scan. Every scan before saw the van's place now hidden behind
// the van as it was then: the beam toward a point of its back stopped 1.3 m short of it one scan
// before, 2.6 m two scans before, and so on, so no scan saw through it and none saw it there.
// That is a surface moving along the beams at a constant speed, found from the third scan with
// a past; a static surface hidden from other places keeps its offset. (The van is labelled as
// the helper's box, kPerson.)
std::vector<Scan> vanAheadScans()
{
    constexpr double kStep = 1.3;  // metres a scan, the sensor's and the van's
    return movingSensorScans(
        kStep, 30.0,
        [](int, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
        {
            const std::pair<Eigen::Vector3d, Eigen::Vector3d> van{
                Eigen::Vector3d(o.x() + 18.0, -0.9, kGroundZ + 0.2),
                Eigen::Vector3d(o.x() + 22.5, 0.9, kGroundZ + 2.6)};
            return groundWallAndPerson(o, d, 80.0, van, range);
        });
}

TEST(FreeSpaceTest, AVanDrivingAheadIsShownByItsConstantSpeedAlongTheBeams)
{
    const auto [without, with] = onlineWithAndWithout(vanAheadScans(), onlineParams());
    // Measured: the map alone removes 30 % of the van (the test as well, before this rule),
    // the test 78.4 % (every scan from the third, which has two scans of past; 68.9 % when
    // three were needed).
    EXPECT_GT(with.n[kPerson], 1000u);
    EXPECT_GE(with.pct(kPerson), 60.0);
    EXPECT_GE(with.pct(kPerson), without.pct(kPerson) + 30.0);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(with.n[w], 1000u);
        EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
    }
}

// The same van, online, scan by scan: scan `k` (0-based) of the run, with k scans of past, shows
// the van gone (90 % of its points at least) where the map alone shows none of it, and leaves
// the ground and the wall, which nothing hides, as the map does.
void expectTheVanShownIn(std::size_t k)
{
    std::vector<WithAndWithout> per_scan;
    onlineWithAndWithout(vanAheadScans(), onlineParams(), &per_scan);
    ASSERT_EQ(per_scan.size(), 10u);
    const WithAndWithout& scan = per_scan[k];
    EXPECT_GT(scan.with.n[kPerson], 500u);
    EXPECT_EQ(scan.without.removed[kPerson], 0u);
    EXPECT_GE(scan.with.pct(kPerson), 90.0);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(scan.with.n[w], 100u);
        EXPECT_EQ(scan.with.removed[w], scan.without.removed[w]) << "kind " << int(w);
    }
}

// The third scan has two scans of past, whose beams toward the van's back returned one and two
// steps in front of it. An offset that stays the same cannot be twice itself, so two such
// judges show the van moving. Measured: 94.7 % of the van in that scan (0 % with three judges
// needed, as before).
TEST(FreeSpaceTest, TwoScansOfPastShowAVanDrivingAhead) { expectTheVanShownIn(2); }

// The second scan has one scan of past, whose beams toward the van's back returned a step (1.3
// m) in front of it, at the van's back as it was then. The second scan's own beams pass through
// that place now, to the van's back farther on, and the map does not hold it static (the van was
// there once): what hid the point has left. Measured: 100 % of the van in that scan; 0 % without
// that rule (the one judge neither saw through the van's back nor saw it there).
TEST(FreeSpaceTest, OneScanOfPastShowsAVanDrivingAheadWhereItsBackWas) { expectTheVanShownIn(1); }

/** A box standing before a sensor at the origin: its corners and what it is, in the scans from
 *  `from` on, but `gap` (-1: none). */
struct StandingBox
{
    Eigen::Vector3d lo, hi;
    What what;
    int from = 0;
    int gap = -1;
};

/** `n` scans of a sensor standing at the origin over the 40 degrees on each side of +x: the
 *  ground, a wall 40 m ahead and `boxes`. */
std::vector<Scan> standingScans(int n, const std::vector<StandingBox>& boxes)
{
    std::vector<Scan> scans;
    for (int i = 0; i < n; ++i)
        scans.push_back(rayScan(Eigen::Isometry3d::Identity(), 40.0,
                                [&](const Eigen::Vector3d& d, double& range)
                                {
                                    const Eigen::Vector3d o = Eigen::Vector3d::Zero();
                                    What w = groundWallAndPerson(o, d, 40.0, std::nullopt, range);
                                    auto take = [&](double s, What hit)
                                    {
                                        if (s > 1e-6 && s < range) range = s, w = hit;
                                    };
                                    for (const StandingBox& b : boxes)
                                        if (i >= b.from && i != b.gap)
                                            hitBox(o, d, b.lo, b.hi, b.what, range, take);
                                    return w;
                                }));
    return scans;
}

// Online, the sensor standing still: a hedge 1.5 m tall, 18 m ahead, there in every scan but
// the sixth (a gap in foliage), hides a car parked 3 m behind it, which the sixth scan sees for
// the first time. The scan before saw the hedge in front of the car, and the sixth sees through
// where the hedge was; but the map holds the hedge static there (five scans saw it), so what hid
// the car was part of the static scene, and the car stays (with the map not asked, the test
// removed 114 of its 115 points in that scan).
TEST(FreeSpaceTest, ACarSeenThroughAGapInAHedgeStays)
{
    const std::vector<Scan> scans =
        standingScans(10, {{{17.5, 4.5, kGroundZ}, {18.5, 7.5, kGroundZ + 1.5}, kHedge, 0, 5},
                           {{21.0, 5.5, kGroundZ}, {22.5, 6.5, kGroundZ + 1.0}, kParked}});
    std::vector<WithAndWithout> per_scan;
    onlineWithAndWithout(scans, onlineParams(), &per_scan);
    ASSERT_EQ(per_scan.size(), 10u);
    EXPECT_EQ(per_scan[4].with.n[kParked], 0u);  // hidden until the gap
    const WithAndWithout& sixth = per_scan[5];
    EXPECT_EQ(sixth.with.n[kHedge], 0u);
    EXPECT_GT(sixth.with.n[kParked], 100u);
    EXPECT_EQ(sixth.without.removed[kParked], 0u);
    EXPECT_EQ(sixth.with.removed[kParked], 0u);
}

// Online, the sensor standing 1.7 m up: a car 1.6 m tall drives across 24 m ahead, 1.2 m a scan,
// behind a barrier 0.8 m tall 20 m ahead (the barrier between a highway's lanes), with another
// car parked behind the barrier 8 m to the side. Over the barrier the scan sees the cars' upper
// 0.6 m; their lowest ring there is no ground: the beam below it met the barrier's face, and the
// ground behind is out of sight. Where the test shows the moving car gone, that ring goes with
// it. The parked car, the barrier, the ground and the wall stay.
TEST(FreeSpaceTest, WhatStandsBehindABarrierIsTestedDownToItsLowestRing)
{
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        const Eigen::Vector3d o = Eigen::Vector3d::Zero();
        const double y = -8.0 + 1.2 * i;
        scans.push_back(rayScan(Eigen::Isometry3d::Identity(), 40.0,
                                [&](const Eigen::Vector3d& d, double& range)
                                {
                                    What what =
                                        groundWallAndPerson(o, d, 45.0, std::nullopt, range);
                                    auto take = [&](double s, What w)
                                    {
                                        if (s > 1e-6 && s < range) range = s, what = w;
                                    };
                                    hitBox(o, d, {20.0, -15.0, kGroundZ},
                                           {20.3, 15.0, kGroundZ + 0.8}, kBarrier, range, take);
                                    hitBox(o, d, {24.0, y - 2.2, kGroundZ + 0.2},
                                           {25.8, y + 2.2, kGroundZ + 1.6}, kPerson, range, take);
                                    hitBox(o, d, {24.0, 10.0, kGroundZ + 0.2},
                                           {25.8, 14.4, kGroundZ + 1.6}, kParked, range, take);
                                    return what;
                                }));
    }
    Params prm = onlineParams();
    prm.free_space_fraction = 0.4;
    const auto [without, with] = onlineWithAndWithout(scans, prm);
    // Measured: the map alone removes none of the moving car, the test 79.6 % (66.6 % with its
    // lowest ring over the barrier taken for the ground; the first scan has no past).
    EXPECT_GT(with.n[kPerson], 2000u);
    EXPECT_GE(with.pct(kPerson), 75.0);
    for (const What w : {kGround, kWall, kBarrier, kParked})
    {
        EXPECT_GT(with.n[w], 1000u);
        EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
    }
}

/** Ten scans, the sensor standing (`ego` 0) or moving along x, rows `row_deg` apart, of the
 *  ground, a wall at x = 25 and a walker 1.75 m tall passing at 1.4 m/s along x from x = 11,
 *  5-5.6 m to the right, behind `obstacle` (its box's corners, `lo` and `hi`). */
std::vector<Scan> walkerBehindScans(double ego, What obstacle, const Eigen::Vector3d& lo,
                                    const Eigen::Vector3d& hi, double row_deg = 0.4)
{
    return movingSensorScans(
        ego, 60.0,
        [&](int i, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
        {
            What what = groundWallAndPerson(o, d, 25.0, std::nullopt, range);
            auto take = [&](double s, What w)
            {
                if (s > 1e-6 && s < range) range = s, what = w;
            };
            const double x = 11.0 + 0.14 * i;
            hitBox(o, d, lo, hi, obstacle, range, take);
            hitBox(o, d, {x, -5.6, kGroundZ}, {x + 0.6, -5.0, kGroundZ + 1.75}, kPerson, range,
                   take);
            return what;
        },
        row_deg);
}

/** walkerBehindScans() cleaned with and without the test. */
WithAndWithout walkerBehind(double ego, What obstacle, const Eigen::Vector3d& lo,
                            const Eigen::Vector3d& hi)
{
    return withAndWithoutTheTest(walkerBehindScans(ego, obstacle, lo, hi));
}

/** walkerBehind()'s outcome: at least `min_pct` % of the walker's points (more than `min_n` of
 *  them) removed, the ground as the map has it, and at most 1 % of the obstacle and of the wall
 *  more than the map removes. */
void expectTheWalkerGoes(const WithAndWithout& both, What obstacle, std::size_t min_n,
                         double min_pct)
{
    const auto& [without, with] = both;
    EXPECT_GT(with.n[kPerson], min_n);
    EXPECT_GE(with.pct(kPerson), min_pct);
    EXPECT_GT(with.n[kGround], 1000u);
    EXPECT_EQ(with.removed[kGround], without.removed[kGround]);
    for (const What w : {kWall, obstacle})
    {
        EXPECT_GT(with.n[w], 1000u);
        EXPECT_LE(with.removed[w], without.removed[w] + with.n[w] / 100) << "kind " << int(w);
    }
}

// A walker on the far side of a garden wall 1.4 m tall, 13 m away: only the head and shoulders
// show above it, three or four rings 0.3 m tall, too little for an object on ground in sight.
// But the scan cannot see below them (the beams below met the wall's face in front), and they
// face the beams: the top of what stands behind, tested at any height.
TEST(FreeSpaceTest, AWalkersHeadAboveAWallIsTestedWhateverHeightShows)
{
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        // Measured, standing and moving: the map alone and the test without this rule 0 %,
        // with it 100 %. With the sensor moving, the garden wall's top beside the walker's
        // pillar (a mover's neighbour, tested: step 5 of the free-space test in
        // doc/algorithm.md), where the beams that reach the head skim it, 36 of 34,801 points;
        // the wall 25 m away 14 points more than the map, with or without this rule.
        expectTheWalkerGoes(
            walkerBehind(ego, kFence, {6.0, -4.2, kGroundZ}, {20.0, -4.0, kGroundZ + 1.4}), kFence,
            500, 90.0);
    }
}

// The same walker behind a row of parked cars 1.3 m tall and 1.8 m wide: the head and shoulders
// show over the cars' roofs, 0.45 m of them. The beams just below them meet the roofs, which lie
// nearly level, and only under the roofs the cars' sides stand: what hides the walker's lower
// part is found by walking on down the scan's column to a face an object tall, under the roof.
// The cars, the ground and the wall stay as the map has them.
TEST(FreeSpaceTest, AWalkersHeadOverParkedCarsRoofsIsTestedWhateverHeightShows)
{
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        // Measured, standing and moving: 9.5 and 10.6 % with the first two beams below asked
        // for a face (before 2026-12-06), 100 % now.
        expectTheWalkerGoes(
            walkerBehind(ego, kParked, {4.0, -4.0, kGroundZ}, {22.0, -2.2, kGroundZ + 1.3}),
            kParked, 300, 80.0);
    }
}

// Rings 1.33 degrees apart (a 32-beam LiDAR's), one of them level with the sensor: the same
// walker behind parked cars 1.5 m tall shows one ring over their roofs, its head at the
// sensor's height. One ring is too little for an object, and with no ring above or below on
// it, it is not known to face the beams. But the scan could not see below it (the rings below
// met the cars' sides), it stands far above the road in front of them, and its returns run
// smooth along the ring: the top of what stands behind, judged by the beams through its own
// cells.
TEST(FreeSpaceTest, AWalkersHeadSeenByOneRingOverParkedCarsIsTested)
{
    constexpr double kSpacing = 4.0 / 3.0;
    const SensorModel model = ringsEvery(kSpacing);
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = walkerBehindScans(ego, kParked, {4.0, -4.0, kGroundZ},
                                                          {22.0, -2.2, kGroundZ + 1.5}, kSpacing);
        // Measured, standing and moving: 0 and 58.3 % of the walker's 173 and 242 points without
        // this rule, 85.5 and 77.3 % with it. Asked to lie off a surface along the beams, as
        // the ground is, 0 % standing; judged by beams above it too, the parked cars' roofs
        // go with it (133 points more than the map removes, moving).
        expectTheWalkerGoes(offlineWithModel(scans, model, 0.0).all, kParked, 150, 70.0);
    }
}

// Offline, rings 1.7 degrees apart (a 16-beam LiDAR's), the sensor driving 1.3 m a scan: a car
// 4.5 m long keeps pace 27 m ahead in the next lane, 0.2-1.5 m above the road, met by two rings
// (0.3 and 1.1 m up). The car covers each pillar for three or four scans, so the map holds its
// lower ring static there, and the lower ring is the pillar's ground for the test: nothing clear
// of it makes an object. Where the map found the rest of such a pillar dynamic because earlier
// beams had seen that place empty, what is left is tested as part of a mover. The road and the
// wall stay as the map has them.
TEST(FreeSpaceTest, ACarKeepingPaceIsTestedWhereTheMapSawPartOfItsPillarEmpty)
{
    const SensorModel model = ringsEvery(1.7);
    const std::vector<Scan> scans = movingSensorScans(
        1.3, 40.0,
        [](int, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& range)
        {
            const std::pair<Eigen::Vector3d, Eigen::Vector3d> car{
                Eigen::Vector3d(o.x() + 27.0, -4.4, kGroundZ + 0.2),
                Eigen::Vector3d(o.x() + 31.5, -2.6, kGroundZ + 1.5)};
            return groundWallAndPerson(o, d, 80.0, car, range);
        },
        1.7);
    // The car's lower ring (its points less than 0.7 m above the road).
    const auto [all, low, low_removed] = offlineWithModel(scans, model, 0.7);
    const auto& [without, with] = all;
    // Measured: the lower ring's 200 points 93 % removed (76 % before this rule, the map alone
    // 51 %), the car's 430 points 90.5 % (81.6 %; the map alone 62.1 %).
    EXPECT_GE(low, 150u);
    EXPECT_GE(low_removed * 100, low * 85);
    EXPECT_GE(with.pct(kPerson), 86.0);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(with.n[w], 200u);
        EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
    }
}

// Rings 1.7 degrees apart (a 16-beam LiDAR's), the sensor standing 1.7 m up: a car 1.5 m tall
// crosses 24 m ahead at 1.2 m a scan, met by two rings, 0.44 and 1.16 m above the road. The
// lower ring is its pillars' lowest return; the ring below it meets the road 3 m in front, so
// nothing there hides the ground. But it lies on the car's side, which faces the beams (its
// neighbours in its row and in its column return at its range) and rises from it, 0.44 m above
// the road carried on from the two rings below: the road at its foot is behind it, and the two
// rings make an object. Offline and online, the test shows the car gone; the road and the wall
// stay as the map has them (the walkers' tests above hold the ground at a mover's foot, on the
// road's line, as the map has it).
TEST(FreeSpaceTest, ALowestReturnThatFacesTheBeamsIsNoGround)
{
    const SensorModel model = ringsEvery(1.7);
    std::vector<Scan> scans;
    for (int i = 0; i < 10; ++i)
    {
        const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
        const double y = -8.0 + 1.2 * i;
        const std::pair<Eigen::Vector3d, Eigen::Vector3d> car{
            Eigen::Vector3d(24.0, y - 2.2, kGroundZ),
            Eigen::Vector3d(25.8, y + 2.2, kGroundZ + 1.5)};
        scans.push_back(rayScan(
            pose, 60.0,
            [&](const Eigen::Vector3d& d, double& range)
            { return groundWallAndPerson(pose.translation(), d, 45.0, car, range); },
            1.7));
    }
    const Params online = onlineParams();
    // Measured: offline 85.2 % of the car's 1,042 points removed (24.6 % before this rule, the
    // map alone 5.8 %), online 65.6 % (16.7 %, the map alone none; the first scan has no past).
    const WithAndWithout offline = offlineWithModel(scans, model, 0.0).all;
    const WithAndWithout past = onlineWithAndWithout(scans, online);
    EXPECT_GT(offline.with.n[kPerson], 900u);
    EXPECT_GE(offline.with.pct(kPerson), 75.0);
    EXPECT_GE(past.with.pct(kPerson), 55.0);
    for (const WithAndWithout* r : {&offline, &past})
        for (const What w : {kGround, kWall})
        {
            EXPECT_GT(r->with.n[w], 1000u);
            EXPECT_EQ(r->with.removed[w], r->without.removed[w]) << "kind " << int(w);
        }
}

// Online, the sensor standing still: a car 4.5 m long drives across the view 20 m ahead, 2.5 m
// a scan, its side toward the sensor. The second scan's one scan of past saw through where the
// car's front half is now, but saw the car's side where its back half is: the side slid along
// itself. The scan's own beams show one surface from the front half to the back, so the back
// half goes with the front. Measured: 98.1 % of the car in that scan; 65.9 % (the front half
// and the trailing end) without carrying the surface on, the map alone 22.3 %.
TEST(FreeSpaceTest, ACarCrossingTheViewGoesWholeWhereItsSideSlidAlongItself)
{
    std::vector<Scan> scans;
    for (int i = 0; i < 4; ++i)
    {
        const double y = -8.0 + 2.5 * i;  // the car's centre
        const std::pair<Eigen::Vector3d, Eigen::Vector3d> car{
            Eigen::Vector3d(19.5, y - 2.25, kGroundZ + 0.3),
            Eigen::Vector3d(21.3, y + 2.25, kGroundZ + 1.5)};
        scans.push_back(
            rayScan(Eigen::Isometry3d::Identity(), 40.0,
                    [&](const Eigen::Vector3d& d, double& range)
                    { return groundWallAndPerson(Eigen::Vector3d::Zero(), d, 40.0, car, range); }));
    }
    Params prm = onlineParams();
    prm.free_space_fraction = 0.4;  // kitti-online.ini's
    std::vector<WithAndWithout> per_scan;
    onlineWithAndWithout(scans, prm, &per_scan);
    ASSERT_EQ(per_scan.size(), 4u);
    const WithAndWithout& second = per_scan[1];
    EXPECT_GT(second.with.n[kPerson], 200u);
    EXPECT_LE(second.without.pct(kPerson), 60.0);
    EXPECT_GE(second.with.pct(kPerson), 95.0);
    for (const What w : {kGround, kWall})
    {
        EXPECT_GT(second.with.n[w], 100u);
        EXPECT_EQ(second.with.removed[w], second.without.removed[w]) << "kind " << int(w);
    }
}

// Online, the sensor standing still: a board 4 m wide stands 20 m ahead, facing the sensor; its
// left three metres (labelled as the hedge) arrived after the first scan and stay, its right
// metre (labelled as the parked car) stood there from the start. Later scans' one judge that
// saw through the left part, the first scan, shows it gone; the board is one surface, three
// quarters of it shown gone, but its right metre was seen by every scan, as nothing that moved:
// it stays. Measured: none of it removed in scans 2-6; all of it without asking how often the
// map saw it.
TEST(FreeSpaceTest, WhatStoodThereAllAlongStaysBesideWhatArrivedOnTheSameSurface)
{
    const std::vector<Scan> scans =
        standingScans(6, {{{20.0, -2.0, kGroundZ + 0.3}, {20.2, 1.0, kGroundZ + 1.8}, kHedge, 1},
                          {{20.0, 1.0, kGroundZ + 0.3}, {20.2, 2.0, kGroundZ + 1.8}, kParked}});
    Params prm = onlineParams();
    prm.free_space_fraction = 0.4;
    std::vector<WithAndWithout> per_scan;
    onlineWithAndWithout(scans, prm, &per_scan);
    ASSERT_EQ(per_scan.size(), 6u);
    std::size_t arrived = 0, arrived_removed = 0, stood = 0, stood_removed = 0;
    for (std::size_t k = 2; k < per_scan.size(); ++k)
    {
        arrived += per_scan[k].with.n[kHedge];
        arrived_removed += per_scan[k].with.removed[kHedge];
        stood += per_scan[k].with.n[kParked];
        stood_removed += per_scan[k].with.removed[kParked];
    }
    EXPECT_GT(stood, 100u);
    EXPECT_GT(arrived_removed * 2, arrived);  // the part that arrived: shown gone
    EXPECT_EQ(stood_removed, 0u);
}
