// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_free_space.cpp
 * @brief  The free-space test (Params::free_space_window) on a ray-cast scene: a person walks
 *         across in front of a wall, past a pole, for ten scans; the map alone keeps the person,
 *         the test removes it, and the ground, the wall and the pole stay; a cyclist's wheels go
 *         with it into the pillars next to its rider. Also the window's rules (its own scan is
 *         no evidence, only scans within the window count, online sees the past only) and the
 *         minimum range.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "hif/PillarGrid.h"
#include "hif/ScanWindow.h"

using namespace hif;

namespace
{
/** The windows of these tests use the layout of a map without a sensor model. */
const RangeImageLayout kLayout = RangeImageLayout::forSensor(std::nullopt);

enum What : uint8_t
{
    kNothing,
    kGround,
    kWall,
    kPole,
    kPerson,
    kHedge,  ///< there in every scan but one in the middle (a gap in foliage, a flicker)
    kLow,    ///< a mover 0.3 m tall
    kRider,  ///< a cyclist's body, from 0.4 m up
    kWheels  ///< its bicycle's low part, 1.6 m long: beyond the rider, alone in its pillars
};
constexpr int kKinds = 9;

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
    {  // vertical cylinder
        const double ox = o.x() - 12.0, oy = o.y() + 3.0;
        const double a = d.x() * d.x() + d.y() * d.y(), b = 2 * (ox * d.x() + oy * d.y());
        const double disc = b * b - 4 * a * (ox * ox + oy * oy - 0.01);
        if (a > 0 && disc >= 0)
        {
            const double s = (-b - std::sqrt(disc)) / (2 * a);
            if ((o + s * d).z() < kGroundZ + 3.0) take(s, kPole);
        }
    }
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

/** Ten scans of a sensor that stands still (or moves `ego` m per scan along x), rows 0.4
 *  degrees apart from -20 to +4 degrees, columns 0.2 degrees apart over the 120 degrees ahead;
 *  the person crosses at 0.15 m per scan. */
std::vector<Scan> makeScans(double ego = 0.0)
{
    std::vector<Scan> scans(10);
    for (int i = 0; i < 10; ++i)
    {
        Scan& s = scans[i];
        s.pose.translation() = Eigen::Vector3d(ego * i, 0.0, 0.0);
        const Eigen::Vector3d o = s.pose.translation();
        for (double el = -20.0; el <= 4.0; el += 0.4)
            for (double az = -60.0; az <= 60.0; az += 0.2)
            {
                const double e = el * M_PI / 180.0, a = az * M_PI / 180.0;
                const Eigen::Vector3d d(std::cos(e) * std::cos(a), std::cos(e) * std::sin(a),
                                        std::sin(e));
                double r = 0;
                const What w = cast(o, d, i, r);
                if (w == kNothing) continue;
                const Eigen::Vector3d p = d * r;  // sensor frame (no rotation)
                s.x.push_back(float(p.x()));
                s.y.push_back(float(p.y()));
                s.z.push_back(float(p.z()));
                s.what.push_back(w);
            }
    }
    return scans;
}

Params freeSpaceParams()
{
    Params p;
    p.p_empty_init = 0.42;
    p.free_space_window = 10;
    p.free_space_fraction = 0.6;
    return p;
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

/** Offline: the map of all scans; each scan classified with the window of all of them. */
Removed offline(const std::vector<Scan>& scans, const Params& prm, bool with_window)
{
    PillarGrid grid(GridGeometry(), prm);
    ScanWindow window;
    for (std::size_t i = 0; i < scans.size(); ++i)
    {
        grid.insertScan(scans[i].view(), scans[i].pose);
        window.add(i, scans[i].view(), scans[i].pose, kLayout);
    }
    Removed r;
    for (std::size_t i = 0; i < scans.size(); ++i)
    {
        std::vector<uint8_t> dyn;
        if (with_window)
            grid.classify(scans[i].view(), dyn, scans[i].pose, window, i);
        else
            grid.classify(scans[i].view(), dyn, scans[i].pose);
        r.add(scans[i], dyn);
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
        const Removed without = offline(scans, freeSpaceParams(), false);
        const Removed with = offline(scans, freeSpaceParams(), true);
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

// The bicycle's low part reaches 0.6 m beyond its rider on both sides, into pillars where it
// is all there is above the ground: 0.3 m above the clearance, too little to make an object
// there (free_space_min_extent 0.5). Next to a pillar of a mover (here the map already removes
// the rider, which runs into its own shadow), it is tested as part of it.
TEST(FreeSpaceTest, TheLowPartsOfAMoverGoWithItIntoTheNextPillars)
{
    for (const double ego : {0.0, 0.3})
    {
        SCOPED_TRACE("sensor moving " + std::to_string(ego) + " m per scan");
        const std::vector<Scan> scans = makeScans(ego);
        const Removed without = offline(scans, freeSpaceParams(), false);
        const Removed with = offline(scans, freeSpaceParams(), true);
        // Measured: the map alone removes 16 % (standing) and 36 % (moving) of the wheels, with
        // the test 56 % and 79 % (the same as the map alone when only the pillars the test
        // itself shows gone count as a mover's); the rider 98-100 % either way.
        EXPECT_GT(with.n[kWheels], 300u);
        EXPECT_GE(with.pct(kRider), 95.0);
        EXPECT_GE(with.pct(kWheels), without.pct(kWheels) + 30.0);
        for (const What w : {kGround, kWall, kPole, kHedge, kLow})
            EXPECT_EQ(with.removed[w], without.removed[w]) << "kind " << int(w);
    }
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
    ScanWindow window;
    for (std::size_t i = 0; i < scans.size(); ++i)
    {
        grid.insertScan(scans[i].view(), scans[i].pose);
        grid1.insertScan(scans[i].view(), scans[i].pose);
        window.add(i, scans[i].view(), scans[i].pose, kLayout);
    }
    std::vector<uint8_t> dyn;
    Removed all, one;
    grid.classify(scans[0].view(), dyn, scans[0].pose, window, 0);
    all.add(scans[0], dyn);
    grid1.classify(scans[0].view(), dyn, scans[0].pose, window, 0);
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

    // A window holding the scan alone says nothing about it.
    ScanWindow alone;
    alone.add(4, scans[4].view(), scans[4].pose, kLayout);
    const ClassifyStats st = grid.classify(scans[4].view(), dyn, scans[4].pose, alone, 4);
    EXPECT_EQ(st.seen_through_points, 0u);

    // Online: the map and the window of the scans up to scan 6, which is classified as a
    // newer scan than the whole window (no id).
    PillarGrid online_grid(GridGeometry(), freeSpaceParams());
    ScanWindow past;
    for (std::size_t i = 0; i < 6; ++i)
    {
        online_grid.insertScan(scans[i].view(), scans[i].pose);
        past.add(i, scans[i].view(), scans[i].pose, kLayout);
    }
    const Scan& now = scans[6];
    online_grid.insertScan(now.view(), now.pose);
    std::vector<uint8_t> map_only;
    online_grid.classify(now.view(), map_only, now.pose);
    const ClassifyStats online =
        online_grid.classify(now.view(), dyn, now.pose, past, std::nullopt);
    Removed before, after;
    before.add(now, map_only);
    after.add(now, dyn);
    EXPECT_GT(online.seen_through_points, 0u);
    EXPECT_GE(after.pct(kPerson), 90.0);
    EXPECT_LT(before.pct(kPerson), after.pct(kPerson) - 20.0);
    // The first scan has no past: nothing shows its walker gone.
    ScanWindow none;
    EXPECT_EQ(
        grid.classify(scans[0].view(), dyn, scans[0].pose, none, std::nullopt).seen_through_points,
        0u);
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
        ScanWindow past;
        grid.insertScan(scans[0].view(), scans[0].pose);
        past.add(0, scans[0].view(), scans[0].pose, kLayout);
        grid.insertScan(scans[1].view(), scans[1].pose);
        std::vector<uint8_t> dyn;
        grid.classify(scans[1].view(), dyn, scans[1].pose, past, std::nullopt);
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

TEST(ScanWindow, IdsIncreaseAndOldScansAreDropped)
{
    const std::vector<Scan> scans = makeScans();
    ScanWindow w;
    w.add(3, scans[0].view(), scans[0].pose, kLayout);
    w.add(5, scans[1].view(), scans[1].pose, kLayout);
    EXPECT_THROW(w.add(5, scans[2].view(), scans[2].pose, kLayout), std::invalid_argument);
    w.add(8, scans[2].view(), scans[2].pose, kLayout);
    EXPECT_EQ(w.size(), 3u);
    w.dropBefore(5);
    ASSERT_EQ(w.size(), 2u);
    EXPECT_EQ(w.scans().front().id, 5u);
    EXPECT_EQ(w.lastId(), 8u);
    EXPECT_GT(w.memoryBytes(), 2 * 400000u);  // two images of 2 bytes a cell

    // Entries built apart (makeScan, as hif-clean's reader thread does) are the same as those
    // add() builds, and a window sliding over many scans stays the same size either way.
    const ScanWindow::Scan made = ScanWindow::makeScan(9, scans[2].view(), scans[2].pose, kLayout);
    EXPECT_EQ(made.image, w.scans().back().image);
    EXPECT_TRUE(made.sensor_to_world.isApprox(w.scans().back().sensor_to_world));
    EXPECT_THROW(w.add(ScanWindow::makeScan(8, scans[2].view(), scans[2].pose, kLayout)),
                 std::invalid_argument);
    for (const bool apart : {false, true})
    {
        ScanWindow slide;
        std::size_t bytes_at_20 = 0;
        for (std::size_t id = 0; id < 60; ++id)
        {
            const Scan& sc = scans[id % scans.size()];
            if (apart)
                slide.add(ScanWindow::makeScan(id, sc.view(), sc.pose, kLayout));
            else
                slide.add(id, sc.view(), sc.pose, kLayout);
            slide.dropBefore(id >= 5 ? id - 5 : 0);
            if (id == 20) bytes_at_20 = slide.memoryBytes();
        }
        EXPECT_EQ(slide.size(), 6u);
        EXPECT_EQ(slide.memoryBytes(), bytes_at_20) << (apart ? "makeScan" : "add(id, ...)");
    }
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
