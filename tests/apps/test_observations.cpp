// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_observations.cpp
 * @brief  hif-clean on every kind of observation MRPT records: points placed at the robot pose
 *         composed with the sensor pose; sensory frames, 2D and 3D range scans and Velodyne scans
 *         read and written back.
 */
#include <gtest/gtest.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>

#include "app_checks.h"
#include "app_runner.h"
#include "hif/io/CloudFiles.h"
#include "job_runner.h"

namespace fs = std::filesystem;
using nlohmann::json;

using hif::test::clean;
using Options = hif::jobs::CleanOptions;
using hif::test::readJson;
using hif::test::runInProcess;
using hif::test::WorkDir;
using hif::test::workDir;

using hif::test::rawlogObjects;

TEST(HifClean, PlacesPointsAtTheRobotPoseComposedWithTheSensorPose)
{
    const WorkDir work = workDir("sensor_pose");
    const std::string& d = work.path();
    const mrpt::poses::CPose3D sensor(0.8, -0.3, 1.7, mrpt::DEG2RAD(30.0), mrpt::DEG2RAD(3.0),
                                      mrpt::DEG2RAD(-2.0));
    std::size_t points = 0;
    {
        mrpt::io::CFileOutputStream f(d + "/scans.rawlog");
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 5; ++s)
        {
            const mrpt::poses::CPose3D robot(0.5 * s, 0.2 * s, 0.0, mrpt::DEG2RAD(5.0 * s), 0, 0);
            auto pose = mrpt::obs::CObservationRobotPose::Create();
            pose->pose.mean = robot;
            arch << *pose;
            // A wall at x = 10 and the ground z = 0 in the world, seen from the sensor.
            const mrpt::poses::CPose3D world_to_sensor = -(robot + sensor);
            auto cloud = mrpt::maps::CSimplePointsMap::Create();
            for (double a = -4.0; a <= 4.0; a += 0.25)
                for (double b = 0.0; b <= 2.5; b += 0.25)
                {
                    cloud->insertPoint(world_to_sensor.composePoint({10.0, a, b}));
                    cloud->insertPoint(world_to_sensor.composePoint({2.0 + b * 2.0, a, 0.0}));
                }
            points = cloud->size();
            auto obs = mrpt::obs::CObservationPointCloud::Create();
            obs->pointcloud = cloud;
            obs->sensorPose = sensor;
            arch << *obs;
        }
    }
    const auto r =
        runInProcess("hif-clean", "-i " + d + "/scans.rawlog -o " + d + "/out -q --format pcd");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_FALSE(fs::exists(d + "/out/static_map.ply"));
    const hif::io::PcdCloud kept = hif::io::readPcd(d + "/out/static_map.pcd");
    ASSERT_GT(kept.size(), points) << "most points of a static scene are kept";
    for (std::size_t i = 0; i < kept.size(); ++i)
        ASSERT_TRUE(std::abs(kept.x[i] - 10.0f) < 1e-3f || std::abs(kept.z[i]) < 1e-3f)
            << "point " << i << " at (" << kept.x[i] << ", " << kept.y[i] << ", " << kept.z[i]
            << ") is on neither the wall nor the ground";
}

TEST(HifClean, ReadsSensoryFramesAnd2DAnd3DAndVelodyneScansAndWritesThemBack)
{
    using namespace mrpt::obs;
    const WorkDir work = workDir("mrpt_kinds");
    const std::string& d = work.path();
    // A wall 6 m ahead and the ground, seen from a robot that moves 0.3 m a scan; a box passes
    // in front of the wall in the first scan only.
    const auto pointsOf = [](int s)
    {
        std::vector<mrpt::math::TPoint3D> p;
        for (double a = -3.0; a <= 3.0; a += 0.1)
            for (double z = 0.0; z <= 2.0; z += 0.1) p.push_back({6.0 - 0.3 * s, a, z - 1.0});
        for (double x = 1.0; x <= 5.0; x += 0.1)
            for (double a = -3.0; a <= 3.0; a += 0.1) p.push_back({x, a, -1.0});
        if (s == 0)
            for (double a = -0.5; a <= 0.5; a += 0.05)
                for (double z = 0.0; z <= 1.0; z += 0.05) p.push_back({3.0, a, z - 0.8});
        return p;
    };
    {
        mrpt::io::CFileOutputStream f(d + "/frames3d.rawlog");
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 5; ++s)
        {
            arch << mrpt::obs::CActionCollection();
            mrpt::obs::CSensoryFrame sf;
            auto pose = CObservationRobotPose::Create();
            pose->pose.mean = mrpt::poses::CPose3D(0.3 * s, 0, 0, 0, 0, 0);
            sf.insert(pose);
            auto o3d = CObservation3DRangeScan::Create();
            o3d->hasPoints3D = true;
            const auto pts = pointsOf(s);
            o3d->resizePoints3DVectors(pts.size());
            for (std::size_t i = 0; i < pts.size(); ++i)
            {
                o3d->points3D_x[i] = float(pts[i].x);
                o3d->points3D_y[i] = float(pts[i].y);
                o3d->points3D_z[i] = float(pts[i].z);
            }
            sf.insert(o3d);
            arch << sf;
        }
    }
    // Observations format: per scan its pose, then the scan `make(s)` builds.
    const auto writeRawlog =
        [&d](const std::string& name, const std::function<CObservation::Ptr(int)>& make)
    {
        mrpt::io::CFileOutputStream f(d + "/" + name);
        auto arch = mrpt::serialization::archiveFrom(f);
        for (int s = 0; s < 5; ++s)
        {
            auto pose = CObservationRobotPose::Create();
            pose->pose.mean = mrpt::poses::CPose3D(0.3 * s, 0, 0, 0, 0, 0);
            arch << *pose << *make(s);
        }
    };
    writeRawlog("scans2d.rawlog",
                [](int s)
                {
                    auto scan = CObservation2DRangeScan::Create();
                    scan->aperture = float(M_PI);
                    scan->resizeScan(181);
                    for (std::size_t i = 0; i < 181; ++i)
                    {
                        // The wall at x = 6 - 0.3 s, and, in the first scan, a box at 3 m
                        // across 20 rays.
                        const double ang = -M_PI / 2 + M_PI * double(i) / 180.0;
                        const double wall = (6.0 - 0.3 * s) / std::max(0.2, std::cos(ang));
                        const bool box = s == 0 && i >= 80 && i < 100;
                        scan->setScanRange(i,
                                           float(box ? 3.0 / std::cos(ang) : std::min(wall, 30.0)));
                        scan->setScanRangeValidity(i, std::cos(ang) > 0.2 || box);
                    }
                    return scan;
                });
    // As the Velodyne driver leaves it after generatePointCloud(): the points (and here no raw
    // packets).
    writeRawlog("velodyne.rawlog",
                [&pointsOf](int s)
                {
                    auto velo = CObservationVelodyneScan::Create();
                    for (const auto& p : pointsOf(s))
                    {
                        velo->point_cloud.x.push_back(float(p.x));
                        velo->point_cloud.y.push_back(float(p.y));
                        velo->point_cloud.z.push_back(float(p.z));
                        velo->point_cloud.intensity.push_back(100);
                    }
                    return velo;
                });
    for (const std::string kind : {"frames3d", "scans2d", "velodyne"})
    {
        SCOPED_TRACE(kind);
        const std::string out = d + "/" + kind;
        auto r = clean(d + "/" + kind + ".rawlog", out,
                       [&](Options& o)
                       {
                           o.picture = false;
                           o.rawlog_out = out + ".clean.rawlog";
                       });
        ASSERT_EQ(r.code, 0) << r.output;
        const json s = readJson(out + "/summary.json");
        EXPECT_EQ(s["scans"], 5);
        EXPECT_GT(s["points_removed"].get<std::size_t>(), 0u) << "the box is removed";
        // The cleaned rawlog: the same kind of scan, only the kept points.
        std::size_t points = 0, scans = 0;
        for (const auto& o : rawlogObjects(out + ".clean.rawlog"))
        {
            if (auto o3d = std::dynamic_pointer_cast<CObservation3DRangeScan>(o))
            {
                ++scans;
                points += o3d->points3D_x.size();
            }
            if (auto velo = std::dynamic_pointer_cast<CObservationVelodyneScan>(o))
            {
                ++scans;
                points += velo->point_cloud.size();
                EXPECT_EQ(velo->point_cloud.intensity.size(), velo->point_cloud.size());
            }
            if (auto o2d = std::dynamic_pointer_cast<CObservation2DRangeScan>(o))
            {
                ++scans;
                for (std::size_t i = 0; i < o2d->getScanSize(); ++i)
                    points += o2d->getScanRangeValidity(i) ? 1 : 0;
            }
        }
        EXPECT_EQ(scans, 5u);
        EXPECT_EQ(points, s["points_kept"].get<std::size_t>());
    }
}
