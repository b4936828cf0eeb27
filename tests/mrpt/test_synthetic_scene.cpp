// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_synthetic_scene.cpp
 * @brief  A moving sensor sees ground, two walls and a box that drives across the scene over 20
 *         scans. Offline (all scans inserted, then every point classified), the box's vacated
 *         positions must come out dynamic, the ground and walls static.
 */
#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <cmath>
#include <random>

#include "hif/CHeightIntervalMap.h"

using hif::CHeightIntervalMap;
using mrpt::poses::CPose3D;

namespace
{
enum class Kind : uint8_t
{
    Ground,
    Wall,
    Box
};

struct Scan
{
    CPose3D robot;
    mrpt::obs::CObservationPointCloud::Ptr obs;
    std::vector<Kind> kind;
    std::vector<mrpt::math::TPoint3D> world;
};

constexpr int kScans = 20;
constexpr double kRange = 25.0;  // horizontal range of the simulated sensor

// Box of 2 x 2 m, from 0.3 to 1.8 m (a car body), centred at (box_x, 0).
bool underBox(double x, double y, double box_x)
{
    return std::abs(x - box_x) <= 1.0 && std::abs(y) <= 1.0;
}

Scan makeScan(int i, std::mt19937& rng)
{
    std::normal_distribution<double> noise(0.0, 0.02);
    Scan s;
    const double box_x = -10.0 + 1.0 * i;
    s.robot = CPose3D(-10.0 + 0.5 * i, -5.0, 0.0, 0.1 * i, 0.0, 0.0);
    const CPose3D sensor_on_robot(0.0, 0.0, 1.7, 0.0, 0.0, 0.0);
    const CPose3D world_to_sensor = -(s.robot + sensor_on_robot);
    auto add = [&](double x, double y, double z, Kind k)
    {
        if (std::hypot(x - s.robot.x(), y - s.robot.y()) > kRange) return;
        s.world.emplace_back(x, y, z);
        s.kind.push_back(k);
    };
    for (double x = -20.0; x <= 20.0; x += 0.25)
        for (double y = -9.9; y <= 9.9; y += 0.25)
            if (!underBox(x, y, box_x)) add(x, y, noise(rng), Kind::Ground);
    for (double x = -20.0; x <= 20.0; x += 0.2)
        for (double z = 0.0; z <= 3.0; z += 0.15)
        {
            add(x, 10.0, z + noise(rng), Kind::Wall);
            add(x, -10.0, z + noise(rng), Kind::Wall);
        }
    for (double a = -1.0; a <= 1.0; a += 0.2)
        for (double z = 0.3; z <= 1.8; z += 0.15)
        {
            add(box_x + a, -1.0, z, Kind::Box);  // side facing the sensor
            add(box_x - 1.0, a, z, Kind::Box);
            add(box_x + 1.0, a, z, Kind::Box);
        }
    for (double a = -1.0; a <= 1.0; a += 0.25)
        for (double b = -1.0; b <= 1.0; b += 0.25) add(box_x + a, b, 1.8, Kind::Box);  // roof

    auto pts = mrpt::maps::CSimplePointsMap::Create();
    for (const auto& w : s.world) pts->insertPoint(world_to_sensor.composePoint(w));
    s.obs = mrpt::obs::CObservationPointCloud::Create();
    s.obs->pointcloud = pts;
    s.obs->sensorPose = sensor_on_robot;
    return s;
}
}  // namespace

TEST(SyntheticScene, VacatedBoxPositionsAreDynamicGroundAndWallsStatic)
{
    std::mt19937 rng(42);
    std::vector<Scan> scans;
    CHeightIntervalMap map;
    for (int i = 0; i < kScans; ++i)
    {
        scans.push_back(makeScan(i, rng));
        ASSERT_TRUE(map.insertObservation(*scans.back().obs, scans.back().robot));
        EXPECT_EQ(map.lastInsertStats().points_invalid, 0u);
    }

    // Offline classification: every point of every scan against the final map, in the world
    // frame computed by the adapter from the observation and the robot pose.
    std::size_t n[3] = {0, 0, 0}, kept[3] = {0, 0, 0};
    std::size_t vacated = 0, vacated_removed = 0;
    for (int i = 0; i < kScans; ++i)
    {
        const Scan& s = scans[i];
        std::vector<float> xs, ys, zs;
        ASSERT_TRUE(CHeightIntervalMap::observationToWorldPoints(*s.obs, s.robot, xs, ys, zs));
        ASSERT_EQ(xs.size(), s.world.size());
        mrpt::maps::CSimplePointsMap world;
        for (std::size_t k = 0; k < xs.size(); ++k)
        {
            ASSERT_NEAR(xs[k], s.world[k].x, 1e-3);
            ASSERT_NEAR(zs[k], s.world[k].z, 1e-3);
            world.insertPoint(xs[k], ys[k], zs[k]);
        }
        std::vector<uint8_t> dyn;
        map.classify(world, dyn);
        for (std::size_t k = 0; k < dyn.size(); ++k)
        {
            const auto c = static_cast<int>(s.kind[k]);
            ++n[c];
            kept[c] += dyn[k] ? 0 : 1;
            // The box leaves its position of scan i for good by scan i + 3 (it is 2 m long
            // and moves 1 m per scan); from then on the sensor sees the ground there.
            if (s.kind[k] == Kind::Box && i + 3 < kScans)
            {
                ++vacated;
                vacated_removed += dyn[k];
            }
        }
    }
    auto pct = [](std::size_t a, std::size_t b) { return 100.0 * double(a) / double(b); };
    const double ground_kept = pct(kept[0], n[0]);
    const double wall_kept = pct(kept[1], n[1]);
    const double vacated_removed_pct = pct(vacated_removed, vacated);
    std::cout << "[ synthetic ] ground kept " << ground_kept << " % of " << n[0] << ", walls kept "
              << wall_kept << " % of " << n[1] << ", vacated box removed " << vacated_removed_pct
              << " % of " << vacated << "; " << map.asString() << "\n";
    EXPECT_GE(ground_kept, 99.0);
    EXPECT_GE(wall_kept, 99.0);
    EXPECT_GE(vacated_removed_pct, 90.0);
}
