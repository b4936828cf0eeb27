// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_map.cpp
 * @brief  hif::CHeightIntervalMap as an MRPT map: construction, observation types, poses,
 *         queries, copy, rendering and file output.
 */
#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationGPS.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/system/filesystem.h>

#include <fstream>
#include <random>
#include <type_traits>

#include "hif/CHeightIntervalMap.h"
#include "work_dir.h"

using hif::CHeightIntervalMap;
using mrpt::math::TPoint3D;
using mrpt::poses::CPose3D;

static_assert(std::is_copy_constructible_v<CHeightIntervalMap>);
static_assert(std::is_copy_assignable_v<CHeightIntervalMap>);
static_assert(std::is_move_constructible_v<CHeightIntervalMap>);
static_assert(std::is_move_assignable_v<CHeightIntervalMap>);

namespace
{
mrpt::obs::CObservationPointCloud::Ptr cloud(const std::vector<TPoint3D>& pts,
                                             const CPose3D& sensorPose = CPose3D())
{
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    auto map = mrpt::maps::CSimplePointsMap::Create();
    for (const auto& p : pts) map->insertPoint(p);
    obs->pointcloud = map;
    obs->sensorPose = sensorPose;
    return obs;
}
}  // namespace

TEST(CHeightIntervalMap, EmptyOnConstruction)
{
    CHeightIntervalMap map;
    EXPECT_TRUE(map.isEmpty());
    EXPECT_EQ(map.pillarCount(), 0u);
    EXPECT_NE(map.asString().find("0 pillars"), std::string::npos);
}

TEST(CHeightIntervalMap, Clear)
{
    CHeightIntervalMap map;
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}})));
    EXPECT_FALSE(map.isEmpty());
    map.clear();
    EXPECT_TRUE(map.isEmpty());
}

TEST(CHeightIntervalMap, InsertUnhandledObservationTypeReturnsFalse)
{
    CHeightIntervalMap map;
    mrpt::obs::CObservationGPS gps;
    EXPECT_FALSE(map.insertObservation(gps));
    EXPECT_FALSE(map.canComputeObservationLikelihood(gps));
    EXPECT_TRUE(map.isEmpty());
}

TEST(CHeightIntervalMap, InsertObservationPointCloudEmptyReturnsFalse)
{
    CHeightIntervalMap map;
    EXPECT_FALSE(map.insertObservation(*cloud({})));
    mrpt::obs::CObservationPointCloud no_cloud;  // pointcloud == nullptr
    EXPECT_FALSE(map.insertObservation(no_cloud));
    EXPECT_TRUE(map.isEmpty());
}

TEST(CHeightIntervalMap, PointCloudLandsAtRobotPoseComposedWithSensorPose)
{
    CHeightIntervalMap map;
    const CPose3D robot(10.0, -20.0, 0.0, mrpt::DEG2RAD(90.0), 0.0, 0.0);
    const CPose3D sensor(1.0, 0.0, 2.0, 0.0, 0.0, 0.0);
    ASSERT_TRUE(map.insertObservation(*cloud({{3.2, 0.4, -2.0}}, sensor), robot));
    // Sensor frame (3.2, 0.4, -2) -> robot frame (4.2, 0.4, 0) -> yaw 90: (-0.4, 4.2, 0)
    // -> world (9.6, -15.8, 0).
    const TPoint3D expected(9.6, -15.8, 0.0);
    EXPECT_EQ(map.pillarCount(), 1u);
    ASSERT_NE(map.grid().findPillar({9, -16}), nullptr);
    EXPECT_TRUE(map.isStatic(expected));
    EXPECT_NEAR(map.staticProbability(expected), 0.571428571, 1e-6);
    // Where MRPT's CPointsMap would have put it (robot pose ignored): nothing.
    EXPECT_NEAR(map.staticProbability({4.2, 0.4, 0.0}), 0.5, 1e-9);
    EXPECT_EQ(map.grid().findPillar({4, 0}), nullptr);
}

TEST(CHeightIntervalMap, Inserts2DAnd3DRangeScansAtTheirPoses)
{
    CHeightIntervalMap map;
    mrpt::obs::CObservation2DRangeScan scan;
    scan.aperture = static_cast<float>(M_PI);
    scan.rightToLeft = true;
    scan.resizeScan(3);  // beams at -90, 0, +90 degrees
    for (size_t i = 0; i < 3; ++i)
    {
        scan.setScanRange(i, 5.0f);
        scan.setScanRangeValidity(i, i != 2);  // the +90 beam is invalid
    }
    scan.sensorPose = CPose3D(0, 0, 0.5, 0, 0, 0);
    ASSERT_TRUE(map.insertObservation(scan, CPose3D(100, 0, 0, 0, 0, 0)));
    EXPECT_EQ(map.lastInsertStats().points_used, 2u);
    EXPECT_TRUE(map.isStatic({100.5, -4.5, 0.5}));        // -90 deg beam: (100, -5, 0.5)
    EXPECT_TRUE(map.isStatic({105.0, 0.5, 0.5}));         // 0 deg beam
    EXPECT_EQ(map.grid().findPillar({100, 5}), nullptr);  // invalid beam not inserted
    // Scanning left to right, the first beam is at +90 degrees (MRPT's convention).
    scan.rightToLeft = false;
    ASSERT_TRUE(map.insertObservation(scan, CPose3D(200, 0, 0, 0, 0, 0)));
    EXPECT_TRUE(map.isStatic({200.5, 4.5, 0.5}));
    EXPECT_EQ(map.grid().findPillar({200, -5}), nullptr);

    mrpt::obs::CObservation3DRangeScan o3d;
    o3d.hasPoints3D = true;
    o3d.resizePoints3DVectors(1);
    o3d.points3D_x[0] = 1.0f;
    o3d.points3D_y[0] = 2.0f;
    o3d.points3D_z[0] = 0.0f;
    o3d.sensorPose = CPose3D(0, 0, 1.0, 0, 0, 0);
    ASSERT_TRUE(map.insertObservation(o3d, CPose3D(-50, 0, 0, 0, 0, 0)));
    EXPECT_TRUE(map.isStatic({-49.0, 2.0, 1.0}));
}

TEST(CHeightIntervalMap, ClassifyAndLikelihoodFollowTheIntervals)
{
    CHeightIntervalMap map;
    // Every miss counts (Eq. 13 as the paper has it): a scan of one point passes no beam
    // through the box, so with miss_needs_beam the box would stay.
    map.insertionOptions.miss_needs_beam = false;
    // Scan 1: ground and a box at 1 m in pillar (0,0); scan 2 onward: ground only.
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}, {0.5, 0.5, 1.0}})));
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}})));
    mrpt::maps::CSimplePointsMap query;
    query.insertPoint(0.5f, 0.5f, 0.0f);
    query.insertPoint(0.5f, 0.5f, 1.0f);
    std::vector<uint8_t> dyn;
    const hif::ClassifyStats st = map.classify(query, dyn);
    EXPECT_EQ(dyn, (std::vector<uint8_t>{0, 1}));
    EXPECT_EQ(st.static_points, 1u);
    EXPECT_EQ(st.dynamic_points, 1u);

    // Likelihood: a cloud on the ground scores higher than one in the vacated box.
    ASSERT_TRUE(map.canComputeObservationLikelihood(*cloud({{0.5, 0.5, 0.0}})));
    const double on_ground = map.computeObservationLikelihood(*cloud({{0.5, 0.5, 0.0}}), CPose3D());
    const double in_box = map.computeObservationLikelihood(*cloud({{0.5, 0.5, 1.0}}), CPose3D());
    EXPECT_NEAR(on_ground, std::log(map.staticProbability({0.5, 0.5, 0.0})), 1e-6);
    EXPECT_LT(in_box, on_ground);

    // Matching ratio: half the points of `query` lie in a static interval.
    EXPECT_FLOAT_EQ(map.compute3DMatchingRatio(&query, CPose3D(), {}), 0.5f);
    // Shifted up by 1 m: the ground point moves into the box interval (dynamic).
    EXPECT_FLOAT_EQ(map.compute3DMatchingRatio(&query, CPose3D(0, 0, 1.0, 0, 0, 0), {}), 0.0f);
}

// Classifying an observation goes through the insertion's own conversion (sensor points and
// robot (+) sensor pose), so every point of a scan inserted once is static, however close to a
// cell border it lies. Far from the origin, world coordinates in float are 1 mm apart, and
// classifying those instead puts some points in the neighbouring cell.
TEST(CHeightIntervalMap, ClassifyingAnObservationPlacesItsPointsAsInsertionDid)
{
    std::mt19937 rng(8);
    std::uniform_real_distribution<double> u(-15.0, 15.0);
    std::vector<TPoint3D> pts;
    for (int i = 0; i < 20000; ++i) pts.emplace_back(u(rng), u(rng), 0.1 * u(rng));
    const CPose3D sensor(0.4, 0.1, 1.7, mrpt::DEG2RAD(10.0), 0.02, 0.0);
    const CPose3D robot(12345.6, -6789.1, 3.0, mrpt::DEG2RAD(33.0), 0.0, 0.01);
    const auto obs = cloud(pts, sensor);
    CHeightIntervalMap map;
    ASSERT_TRUE(map.insertObservation(*obs, robot));

    std::vector<uint8_t> dyn;
    const hif::ClassifyStats st = map.classify(*obs, robot, dyn);
    ASSERT_EQ(dyn.size(), pts.size());
    EXPECT_EQ(st.dynamic_points, 0u);

    std::vector<float> xs, ys, zs;
    ASSERT_TRUE(CHeightIntervalMap::observationToWorldPoints(*obs, robot, xs, ys, zs));
    mrpt::maps::CSimplePointsMap world;
    for (std::size_t i = 0; i < xs.size(); ++i) world.insertPoint(xs[i], ys[i], zs[i]);
    const hif::ClassifyStats from_world = map.classify(world, dyn);
    EXPECT_GT(from_world.dynamic_points, 0u) << "float world points did not move: the test "
                                                "no longer shows why the conversion matters";

    mrpt::obs::CObservationGPS gps;
    EXPECT_THROW(map.classify(gps, robot, dyn), std::invalid_argument);
}

// The world points a chunk at a time are the world points of the whole scan, in order, to the
// bit, whatever the chunk; a type without points gives none.
TEST(CHeightIntervalMap, WorldPointsByChunksAreTheWholeScansPoints)
{
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-40.0, 40.0);
    std::vector<TPoint3D> pts;
    for (int i = 0; i < 10000; ++i) pts.emplace_back(u(rng), u(rng), 0.05 * u(rng));
    const CPose3D sensor(0.3, -0.1, 1.8, mrpt::DEG2RAD(-5.0), 0.01, 0.02);
    const CPose3D robot(630123.4, 5800321.7, 251.0, mrpt::DEG2RAD(71.0), 0.01, 0.0);  // UTM
    const auto obs = cloud(pts, sensor);
    std::vector<double> xs, ys, zs;
    ASSERT_TRUE(CHeightIntervalMap::observationToWorldPoints(*obs, robot, xs, ys, zs));
    for (const std::size_t chunk :
         {std::size_t{1}, std::size_t{7}, std::size_t{4096}, std::size_t{100000}})
    {
        SCOPED_TRACE(chunk);
        std::size_t next = 0, calls = 0, wrong = 0;
        ASSERT_TRUE(CHeightIntervalMap::forEachWorldPointsChunk(
            *obs, robot, chunk,
            [&](const CHeightIntervalMap::WorldPointsChunk& c)
            {
                ++calls;
                EXPECT_EQ(c.first, next);
                EXPECT_EQ(c.total, pts.size());
                EXPECT_LE(c.size, chunk);
                for (std::size_t j = 0; j < c.size; ++j)
                    wrong += c.xs[j] != xs[c.first + j] || c.ys[j] != ys[c.first + j] ||
                             c.zs[j] != zs[c.first + j];
                next += c.size;
            }));
        EXPECT_EQ(next, pts.size());
        EXPECT_EQ(calls, (pts.size() + chunk - 1) / chunk);
        EXPECT_EQ(wrong, 0u);
    }
    mrpt::obs::CObservationGPS gps;
    bool called = false;
    EXPECT_FALSE(CHeightIntervalMap::forEachWorldPointsChunk(
        gps, robot, 16, [&](const CHeightIntervalMap::WorldPointsChunk&) { called = true; }));
    EXPECT_FALSE(called);
    EXPECT_THROW(CHeightIntervalMap::forEachWorldPointsChunk(
                     *obs, robot, 0, [](const CHeightIntervalMap::WorldPointsChunk&) {}),
                 std::invalid_argument);
}

// Queries never change the map: an option takes effect at the next insertion (or
// applyOptions()), and an invalid one is reported there, not by a query.
TEST(CHeightIntervalMap, OptionChangesApplyAtTheNextInsertion)
{
    CHeightIntervalMap map;
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}})));
    EXPECT_TRUE(map.isStatic({0.5, 0.5, 0.0}));  // 0.571
    map.insertionOptions.static_threshold = 0.6;
    EXPECT_TRUE(map.isStatic({0.5, 0.5, 0.0})) << "a query applied the option";
    EXPECT_EQ(map.params().static_threshold, 0.5);
    map.applyOptions();
    EXPECT_FALSE(map.isStatic({0.5, 0.5, 0.0}));
    map.insertionOptions.static_threshold = 0.5;
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}})));
    EXPECT_EQ(map.params().static_threshold, 0.5);

    map.insertionOptions.alpha = 0.4;  // invalid
    EXPECT_NO_THROW((void)map.isStatic({0.5, 0.5, 0.0}));
    EXPECT_THROW(map.insertObservation(*cloud({{0.5, 0.5, 0.0}})), std::invalid_argument);
    EXPECT_THROW(map.applyOptions(), std::invalid_argument);
    EXPECT_EQ(map.params().alpha, 0.6) << "a rejected option was kept";
    map.insertionOptions.alpha = 0.6;
    map.insertionOptions.threads = 0;
    EXPECT_THROW(map.applyOptions(), std::invalid_argument);
}

TEST(CHeightIntervalMap, CopyIsDeepAndEqual)
{
    CHeightIntervalMap a;
    ASSERT_TRUE(a.insertObservation(*cloud({{0.5, 0.5, 0.0}, {3.5, 0.5, 2.0}})));
    CHeightIntervalMap b = a;
    EXPECT_TRUE(b.grid() == a.grid());
    ASSERT_TRUE(b.insertObservation(*cloud({{0.5, 0.5, 0.0}})));
    EXPECT_FALSE(b.grid() == a.grid());
    EXPECT_NEAR(a.staticProbability({0.5, 0.5, 0.0}), 0.571428571, 1e-6);
}

TEST(CHeightIntervalMap, VisualizationDrawsWhatTheMapKeeps)
{
    CHeightIntervalMap map;
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}, {0.5, 0.5, 2.0}, {7.5, 0.5, 0.0}})));
    ASSERT_EQ(map.intervalCount(), 3u);
    mrpt::opengl::CSetOfObjects objs;
    map.getVisualizationInto(objs);
    auto tris = objs.getByClass<mrpt::opengl::CSetOfTriangles>();
    ASSERT_TRUE(tris);
    // Each static interval: a box of its top and four sides (10 triangles).
    EXPECT_EQ(tris->getTrianglesCount(), 3u * 10u);

    // The box at 1 m that later scans see through (as in ClassifyAndLikelihoodFollowTheIntervals)
    // is below the threshold: its points are classified dynamic, and it is not drawn.
    CHeightIntervalMap seen;
    seen.insertionOptions.miss_needs_beam = false;
    ASSERT_TRUE(seen.insertObservation(*cloud({{0.5, 0.5, 0.0}, {0.5, 0.5, 1.0}})));
    for (int k = 0; k < 5; ++k) ASSERT_TRUE(seen.insertObservation(*cloud({{0.5, 0.5, 0.0}})));
    ASSERT_EQ(seen.intervalCount(), 2u);
    ASSERT_FALSE(seen.isStatic({0.5, 0.5, 1.0}));
    mrpt::opengl::CSetOfObjects kept;
    seen.getVisualizationInto(kept);
    tris = kept.getByClass<mrpt::opengl::CSetOfTriangles>();
    ASSERT_TRUE(tris);
    ASSERT_EQ(tris->getTrianglesCount(), 10u);
    // The one box drawn is the ground's: every vertex below the vacated box.
    for (std::size_t i = 0; i < tris->getTrianglesCount(); ++i)
    {
        mrpt::opengl::TTriangle t;
        tris->getTriangle(i, t);
        for (int k = 0; k < 3; ++k) EXPECT_LT(t.z(k), 0.9f);
        // Coloured by height, never red (kept for what is removed).
        EXPECT_LT(t.r(0), 200);
    }
}

TEST(CHeightIntervalMap, AMapInUtmCoordinatesIsDrawnAndListedToTheMillimetre)
{
    // Scans taken at UTM-like poses: the points themselves are small, in the sensor frame.
    CHeightIntervalMap map;
    const CPose3D at(630000.0, 5800000.0, 250.0, 0, 0, 0);
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}, {3.5, 1.5, 2.0}}), at));
    mrpt::opengl::CSetOfObjects objs;
    map.getVisualizationInto(objs);
    auto tris = objs.getByClass<mrpt::opengl::CSetOfTriangles>();
    ASSERT_TRUE(tris);
    // Placed by a double pose at the map's corner, its float vertices small and exact.
    EXPECT_DOUBLE_EQ(tris->getPoseX(), 630000.0);
    EXPECT_DOUBLE_EQ(tris->getPoseY(), 5800000.0);
    mrpt::opengl::TTriangle t0;
    tris->getTriangle(0, t0);
    for (int k = 0; k < 3; ++k)
    {
        EXPECT_LT(std::abs(t0.x(k)), 10.0f);
        EXPECT_LT(std::abs(t0.y(k)), 10.0f);
    }
    const auto work = hif::test::tempWorkDir("map_geo");
    const std::string prefix = work.path() + "/map";
    map.saveMetricMapRepresentationToFile(prefix);
    std::ifstream f(prefix + "_intervals.txt");
    std::string header;
    std::getline(f, header);
    double x0 = 0, y0 = 0, x1 = 0, y1 = 0, zb = 0;
    ASSERT_TRUE(f >> x0 >> y0 >> x1 >> y1 >> zb);
    EXPECT_DOUBLE_EQ(x0, 630000.0);
    EXPECT_DOUBLE_EQ(y0, 5800000.0);
    EXPECT_DOUBLE_EQ(y1, 5800001.0);
    EXPECT_NEAR(zb, 250.0, 0.051);
    // A map near the origin is drawn as before: at the identity, in world coordinates.
    CHeightIntervalMap local;
    ASSERT_TRUE(local.insertObservation(*cloud({{0.5, 0.5, 0.0}, {3.5, 1.5, 2.0}})));
    // The likelihood is the same there as here: y = 5800000.8 is 5800001 in float32, the next
    // pillar.
    const auto probe = cloud({{0.5, 0.8, 0.0}, {3.5, 1.5, 2.0}});
    EXPECT_DOUBLE_EQ(map.computeObservationLikelihood(*probe, at),
                     local.computeObservationLikelihood(*probe, CPose3D()));
    mrpt::opengl::CSetOfObjects near;
    local.getVisualizationInto(near);
    EXPECT_DOUBLE_EQ(near.getByClass<mrpt::opengl::CSetOfTriangles>()->getPoseX(), 0.0);
}

TEST(CHeightIntervalMap, SavesTextAndSceneRepresentation)
{
    CHeightIntervalMap map;
    ASSERT_TRUE(map.insertObservation(*cloud({{0.5, 0.5, 0.0}, {-1.5, 0.5, 2.0}})));
    const auto work = hif::test::tempWorkDir("map_text_scene");
    const std::string prefix = work.path() + "/map";
    map.saveMetricMapRepresentationToFile(prefix);
    std::ifstream f(prefix + "_intervals.txt");
    ASSERT_TRUE(f.good());
    std::string header, line;
    std::getline(f, header);
    int lines = 0;
    double x0, y0, x1, y1, zb, zt, p;
    while (f >> x0 >> y0 >> x1 >> y1 >> zb >> zt >> p) ++lines;
    EXPECT_EQ(lines, 2);
    EXPECT_TRUE(mrpt::system::fileExists(prefix + "_3D.3Dscene"));
    EXPECT_THROW(map.saveMetricMapRepresentationToFile("/nonexistent-dir/x"), std::exception);
}
