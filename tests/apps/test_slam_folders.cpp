// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_slam_folders.cpp
 * @brief  The inputs LiDAR SLAM systems write: a folder of per-scan clouds in the sensor frame
 *         (.pcd, PCL's compressed .pcd too, or .ply) with a KITTI- or TUM-format trajectory
 *         give the KITTI folder's classes, and so do clouds named by their time with a TUM
 *         trajectory, and clouds with an IMU's trajectory and the LiDAR's extrinsic;
 *         poses that do not belong to the scans are warned about; a single cloud is named;
 *         a rawlog without poses, as MRPT's rosbag2rawlog writes one from a ROS bag, takes a
 *         trajectory's poses.
 */
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CObservationIMU.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>

#include "app_checks.h"
#include "app_runner.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "job_runner.h"
#include "kitti_fixture.h"
#include "pcl_compressed.h"
#include "ros_bag.h"

namespace fs = std::filesystem;
using hif::test::expectError;
using hif::test::readJson;
using hif::test::Result;
using hif::test::WorkDir;
using hif::test::workDir;

namespace
{
/** The real clip the folders are made from, and how many of its scans they hold: comparing
 *  each folder's classes with the KITTI folder's needs a few scans, not the whole clip. */
std::string kittiClip() { return hif::test::kittiRoot() + "/sequences/04"; }
constexpr std::size_t kClipScans = 6;  // the pose check reads the first 5 pairs of scans
/** Points whose class may differ where the poses are the same to their printed digits: a point
 *  on a cell's border may change sides, and the pillar it leaves or joins with it (6 of the
 *  clip's 742,587 did with 6 scans, the same 6 with all 10); a pose that is wrong moves
 *  thousands. */
constexpr std::size_t kBorderPoints = 10;

/** Writes each scan of `seq` in its sensor frame to `dir`/NNNNNN`ext`. */
void writeScans(const hif::io::KittiSequence& seq, const std::string& dir, const std::string& ext)
{
    fs::create_directories(dir);
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const hif::io::Cloud c = seq.readScan(i);
        hif::io::CloudWriter w({dir + "/" + hif::io::frameName(i) + ext});
        for (std::size_t k = 0; k < c.size(); ++k) w.add(c.x[k], c.y[k], c.z[k], c.intensity[k]);
        w.close();
    }
}

/** One pose a line, KITTI format (3x4, 17 digits: read back exactly). */
void writeKittiPoses(const std::vector<Eigen::Isometry3d>& poses, const std::string& file)
{
    std::ofstream f(file);
    f << std::setprecision(17);
    for (const Eigen::Isometry3d& T : poses)
    {
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) f << T(r, c) << (r == 2 && c == 3 ? "\n" : " ");
    }
}

std::vector<Eigen::Isometry3d> lidarPoses(const hif::io::KittiSequence& seq)
{
    std::vector<Eigen::Isometry3d> poses;
    for (std::size_t i = 0; i < seq.size(); ++i) poses.push_back(seq.pose(i));
    return poses;
}

/** Labels of every scan in `dir`/predictions. */
std::vector<uint32_t> predictions(const std::string& dir, std::size_t scans)
{
    std::vector<uint32_t> all;
    for (std::size_t i = 0; i < scans; ++i)
    {
        const auto l =
            hif::io::readLabels(dir + "/predictions/" + hif::io::frameName(i) + ".label");
        all.insert(all.end(), l.begin(), l.end());
    }
    return all;
}

/** The first `n` scans of `seq` as clouds named by their time (`start` plus the sequence's
 *  time, "%.9f": stamp()) in `dir`, without their intensity (as rosbag2rawlog leaves them), and
 *  the LiDAR's poses at those times as the TUM trajectory `tum`. */
struct TimedClouds
{
    double start;
    std::string stamp(const hif::io::KittiSequence& seq, std::size_t i) const
    {
        char name[64];
        std::snprintf(name, sizeof name, "%.9f", start + seq.time(i));
        return name;
    }
    void write(const hif::io::KittiSequence& seq, std::size_t n, const std::string& dir,
               const std::string& tum) const
    {
        fs::create_directories(dir);
        std::ofstream f(tum);
        f << std::setprecision(21);
        for (std::size_t i = 0; i < n; ++i)
        {
            const hif::io::Cloud c = seq.readScan(i);
            hif::io::CloudWriter cw({dir + "/" + stamp(seq, i) + ".pcd"});
            for (std::size_t k = 0; k < c.size(); ++k) cw.add(c.x[k], c.y[k], c.z[k], 0.0f);
            cw.close();
            const Eigen::Isometry3d pose = seq.pose(i);
            const Eigen::Quaterniond q(pose.linear());
            const Eigen::Vector3d& t = pose.translation();
            f << stamp(seq, i) << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x()
              << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
        }
    }
};

/** Copies trajectory `from` to `to` without its first pose: a trajectory that starts late. */
void withoutFirstPose(const std::string& from, const std::string& to)
{
    std::ifstream in(from);
    std::ofstream out(to);
    std::string line;
    std::getline(in, line);
    for (; std::getline(in, line);) out << line << '\n';
}

/** The cleaning of `input` into `out` (in process, no picture), at the poses of `poses` if
 *  given. */
Result clean(const std::string& input, const std::string& out, const std::string& poses = "",
             bool scan_numbers = false)
{
    return hif::test::clean(input, out,
                            [&](hif::jobs::CleanOptions& o)
                            {
                                o.picture = false;
                                o.poses = poses;
                                o.scan_numbers = scan_numbers;
                            });
}
}  // namespace

TEST(SlamFolders, CloudsWithTheirPosesGiveTheKittiFoldersClasses)
{
    HIF_REQUIRE_KITTI_SEQUENCE(kittiClip());
    const WorkDir work = workDir("slam_folders_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const std::string dir = hif::test::firstScans(kittiClip(), kClipScans, w + "/clip");
    const hif::io::KittiSequence seq(dir);
    const auto poses = lidarPoses(seq);
    // LIO-SAM / KISS-ICP style: NNNNNN.pcd beside poses.txt; .ply clouds with the poses
    // elsewhere (--poses); the same clouds with a TUM trajectory.
    writeScans(seq, w + "/pcd_scans", ".pcd");
    writeKittiPoses(poses, w + "/pcd_scans/poses.txt");
    // The same clouds as PCL saves them compressed (savePCDFileBinaryCompressed).
    fs::create_directories(w + "/compressed_scans");
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const hif::io::Cloud c = seq.readScan(i);
        hif::test::writePclCompressedPcd(w + "/compressed_scans/" + hif::io::frameName(i) + ".pcd",
                                         c.x, c.y, c.z, c.intensity);
    }
    writeKittiPoses(poses, w + "/compressed_scans/poses.txt");
    // KITTI's .bin scans themselves, with the LiDAR's poses (as KISS-ICP writes them).
    fs::create_directories(w + "/bin_scans");
    for (std::size_t i = 0; i < seq.size(); ++i)
        fs::copy_file(dir + "/velodyne/" + hif::io::frameName(i) + ".bin",
                      w + "/bin_scans/" + hif::io::frameName(i) + ".bin");
    writeKittiPoses(poses, w + "/bin_scans/poses.txt");
    writeScans(seq, w + "/ply_scans", ".ply");
    writeKittiPoses(poses, w + "/ply_poses_kitti.txt");
    {
        std::ofstream f(w + "/poses_tum.txt");
        f << "# timestamp tx ty tz qx qy qz qw\n" << std::setprecision(17);
        for (std::size_t i = 0; i < seq.size(); ++i)
        {
            const Eigen::Quaterniond q(poses[i].linear());
            const Eigen::Vector3d& t = poses[i].translation();
            f << seq.time(i) << ' ' << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.x() << ' '
              << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
        }
    }

    Result r = clean(dir, w + "/kitti_out");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto reference = predictions(w + "/kitti_out", seq.size());
    const auto ref_summary = readJson(w + "/kitti_out/summary.json");
    EXPECT_FALSE(ref_summary["poses_check"]["doubted"].get<bool>());
    EXPECT_GT(ref_summary["poses_check"]["overlap_above_sensor"].get<double>(),
              ref_summary["poses_check"]["overlap_above_sensor_without_motion"].get<double>());

    r = hif::test::clean(w + "/pcd_scans", w + "/pcd_out",
                         [&](hif::jobs::CleanOptions& o)
                         {
                             o.picture = false;
                             o.scan_numbers = true;
                             o.rawlog_out = w + "/pcd_clean.rawlog";
                         });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(predictions(w + "/pcd_out", seq.size()), reference);
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    // poses.txt has no times: the points get their scan's number and no time (not the time
    // the scan was read).
    {
        std::ifstream ply(w + "/pcd_out/static_map.ply", std::ios::binary);
        std::string header;
        for (std::string line; std::getline(ply, line) && line != "end_header";)
            header += line + "\n";
        EXPECT_NE(header.find("property float intensity\nproperty uint scan\n"), std::string::npos)
            << header;
        EXPECT_EQ(header.find("time"), std::string::npos) << header;
    }
    // A rawlog needs a time for each observation (MRPT's icp-slam refuses one without): each
    // scan's number, in seconds, and the run says so.
    EXPECT_NE(r.output.find("the input gives no times, so " + std::to_string(seq.size()) +
                            " of them have their number for a time"),
              std::string::npos)
        << r.output;
    {
        const auto objects = hif::test::rawlogObjects(w + "/pcd_clean.rawlog");
        EXPECT_EQ(objects.size(), 3 * seq.size());  // comment, pose, scan
        std::set<double> times;
        for (const auto& o : objects)
        {
            const auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation>(o);
            ASSERT_TRUE(obs);
            ASSERT_NE(obs->timestamp, INVALID_TIMESTAMP);
            times.insert(mrpt::Clock::toDouble(obs->timestamp));
        }
        ASSERT_EQ(times.size(), seq.size());
        EXPECT_EQ(*times.begin(), 0.0);
        EXPECT_EQ(*times.rbegin(), double(seq.size() - 1));
    }

    r = clean(w + "/compressed_scans", w + "/compressed_out");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(predictions(w + "/compressed_out", seq.size()), reference);
    r = clean(w + "/bin_scans", w + "/bin_out");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(predictions(w + "/bin_out", seq.size()), reference);

    r = clean(w + "/ply_scans", w + "/ply_out", w + "/ply_poses_kitti.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("at the poses of " + w + "/ply_poses_kitti.txt"), std::string::npos)
        << r.output;
    EXPECT_EQ(predictions(w + "/ply_out", seq.size()), reference);

    // A quaternion printed to 17 digits gives the rotation to about 1e-16: a point on a cell's
    // border may change sides, hardly more.
    r = clean(w + "/pcd_scans", w + "/tum_out", w + "/poses_tum.txt", true);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto tum = predictions(w + "/tum_out", seq.size());
    ASSERT_EQ(tum.size(), reference.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < tum.size(); ++i) differ += tum[i] != reference[i];
    EXPECT_LE(differ, kBorderPoints) << differ << " of " << reference.size();
    // --scan-numbers: each kept point with its scan's number and the trajectory's time.
    std::ifstream ply(w + "/tum_out/static_map.ply", std::ios::binary);
    std::string header;
    for (std::string line; std::getline(ply, line) && line != "end_header";) header += line + "\n";
    EXPECT_NE(header.find("property float intensity\nproperty uint scan\nproperty double time\n"),
              std::string::npos)
        << header;
    std::vector<std::size_t> per_scan(seq.size(), 0);
    for (char rec[28]; ply.read(rec, 28);)
    {
        uint32_t scan = 0;
        double time = 0;
        std::memcpy(&scan, rec + 16, 4);
        std::memcpy(&time, rec + 20, 8);
        ASSERT_LT(scan, seq.size());
        ASSERT_EQ(time, seq.time(scan));
        ++per_scan[scan];
    }
    const auto kept = hif::io::readLabels(w + "/tum_out/predictions/000003.label");
    EXPECT_EQ(per_scan[3],
              std::size_t(std::count(kept.begin(), kept.end(), hif::io::kLabelStatic)));
}

// A bag exported cloud by cloud (pcl_ros's bag_to_pcd: <seconds>.<nanoseconds>.pcd) with the
// SLAM system's TUM trajectory: each cloud takes the pose of its time and its predictions its
// name, and the classes are the KITTI folder's. A cloud the trajectory has no pose for is left
// out and named; a trajectory without times cannot pose clouds named by time.
TEST(SlamFolders, CloudsNamedByTheirTimeTakeTheTrajectorysPoseOfThatTime)
{
    HIF_REQUIRE_KITTI_SEQUENCE(kittiClip());
    const WorkDir work = workDir("slam_timed_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const std::string dir = hif::test::firstScans(kittiClip(), kClipScans, w + "/clip");
    const hif::io::KittiSequence seq(dir);
    const auto poses = lidarPoses(seq);
    constexpr double kStart = 1317022176.0;  // the recording's clock, not the sequence's
    const TimedClouds timed{kStart};
    const auto stamp = [&](std::size_t i) { return timed.stamp(seq, i); };
    timed.write(seq, seq.size(), w + "/bag", w + "/trajectory.txt");

    Result r = clean(w + "/bag", w + "/bag_out", w + "/trajectory.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    r = clean(dir, w + "/kitti_out");
    ASSERT_EQ(r.code, 0) << r.output;
    // Poses through a quaternion: a point on a cell's border may change sides, hardly more.
    std::size_t differ = 0, points = 0;
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const auto ref =
            hif::io::readLabels(w + "/kitti_out/predictions/" + hif::io::frameName(i) + ".label");
        const auto got = hif::io::readLabels(w + "/bag_out/predictions/" + stamp(i) + ".label");
        ASSERT_EQ(got.size(), ref.size()) << i;
        for (std::size_t k = 0; k < ref.size(); ++k) differ += got[k] != ref[k];
        points += ref.size();
    }
    EXPECT_LE(differ, kBorderPoints) << differ << " of " << points;

    // ROS 2's pointcloud_to_pcd names them <sec>.<nanosec> without the nanoseconds' leading
    // zeros: read so (the first cloud here is at a whole second, 1317022176.0), and said.
    fs::create_directories(w + "/bag2");
    std::vector<std::string> ros2_names;
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const double t = kStart + seq.time(i);
        const auto sec = static_cast<long long>(std::floor(t));
        const auto nanosec = static_cast<long long>(std::llround((t - double(sec)) * 1e9));
        ros2_names.push_back(std::to_string(sec) + "." + std::to_string(nanosec));
        fs::copy_file(w + "/bag/" + stamp(i) + ".pcd", w + "/bag2/" + ros2_names.back() + ".pcd");
    }
    r = clean(w + "/bag2", w + "/bag2_out", w + "/trajectory.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("without the nanoseconds' leading zeros (ROS 2's pointcloud_to_pcd), "
                            "and read so: " +
                            ros2_names.front() + ".pcd is at " + stamp(0) + " s"),
              std::string::npos)
        << r.output;
    for (std::size_t i = 0; i < seq.size(); ++i)
        EXPECT_EQ(hif::io::readLabels(w + "/bag2_out/predictions/" + ros2_names[i] + ".label"),
                  hif::io::readLabels(w + "/bag_out/predictions/" + stamp(i) + ".label"))
            << i;

    // The trajectory starts after the first cloud: that cloud is left out, by name.
    withoutFirstPose(w + "/trajectory.txt", w + "/late.txt");
    r = clean(w + "/bag", w + "/late_out", w + "/late.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("1 of the " + std::to_string(seq.size()) + " clouds of '" + w +
                            "/bag' have no pose in '" + w + "/late.txt'"),
              std::string::npos)
        << r.output;
    EXPECT_NE(r.output.find("left out: " + stamp(0) + ".pcd"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(w + "/late_out/predictions/" + stamp(0) + ".label"));
    EXPECT_TRUE(fs::exists(w + "/late_out/predictions/" + stamp(1) + ".label"));

    writeKittiPoses(poses, w + "/kitti_format.txt");
    expectError(clean(w + "/bag", w + "/kitti_format_out", w + "/kitti_format.txt"),
                "holds clouds named by their time (" + stamp(0) +
                    ".pcd), which need a trajectory with times");
}

// A LiDAR-inertial SLAM system (FAST-LIO, LIO-SAM) writes the IMU's trajectory: with the
// LiDAR's pose in the IMU's frame (--extrinsic), the clouds get the KITTI folder's classes, and
// so do its registered clouds (--world-frame); both flags are refused where the input holds its
// own poses, and a wrong extrinsic is named.
TEST(SlamFolders, AnExtrinsicPutsTheLidarWhereAnImusTrajectorySays)
{
    HIF_REQUIRE_KITTI_SEQUENCE(kittiClip());
    const WorkDir work = workDir("slam_extrinsic_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const std::string dir = hif::test::firstScans(kittiClip(), kClipScans, w + "/clip");
    const hif::io::KittiSequence seq(dir);
    writeScans(seq, w + "/scans", ".pcd");
    // The LiDAR a quarter turn about z from the IMU, 0.3 m ahead, 0.1 m right, 0.2 m up.
    Eigen::Isometry3d extrinsic = Eigen::Isometry3d::Identity();
    extrinsic.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    extrinsic.translation() = Eigen::Vector3d(0.3, -0.1, 0.2);
    const std::string text = "0.3 -0.1 0.2 0 0 0.70710678118654752 0.70710678118654752";
    std::vector<Eigen::Isometry3d> imu;
    for (const Eigen::Isometry3d& lidar : lidarPoses(seq))
        imu.push_back(lidar * extrinsic.inverse());
    writeKittiPoses(imu, w + "/imu_poses.txt");

    Result r = clean(dir, w + "/kitti_out");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto reference = predictions(w + "/kitti_out", seq.size());
    const auto withExtrinsic = [&](const std::string& input, const std::string& out,
                                   const std::string& poses, const std::string& e)
    {
        return hif::test::clean(input, out,
                                [&](hif::jobs::CleanOptions& o)
                                {
                                    o.picture = false;
                                    o.poses = poses;
                                    o.extrinsic = e;
                                });
    };
    r = withExtrinsic(w + "/scans", w + "/imu_out", w + "/imu_poses.txt", text);
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(", the LiDAR at (0.3 -0.1 0.2 0 0 0.707107 0.707107) in their frame"),
              std::string::npos)
        << r.output;
    const auto got = predictions(w + "/imu_out", seq.size());
    ASSERT_EQ(got.size(), reference.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < got.size(); ++i) differ += got[i] != reference[i];
    // The quaternion's 17 digits: a point on a cell's border may change sides, hardly more.
    EXPECT_LE(differ, kBorderPoints) << differ << " of " << reference.size();
    // Without it, the IMU's poses put the clouds elsewhere: not the same classes.
    r = clean(w + "/scans", w + "/no_extrinsic_out", w + "/imu_poses.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(predictions(w + "/no_extrinsic_out", seq.size()), reference);

    // FAST-LIO's registered clouds (/cloud_registered, in the world frame; saved as
    // scans_N.pcd) with its IMU's trajectory: --world-frame brings each into the LiDAR's frame
    // at pose x extrinsic.
    fs::create_directories(w + "/registered");
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const hif::io::Cloud c = seq.readScan(i);
        // Named as FAST-LIO names them.
        hif::io::CloudWriter cw({w + "/registered/scans_" + std::to_string(i) + ".pcd"});
        for (std::size_t k = 0; k < c.size(); ++k)
        {
            const Eigen::Vector3d p = seq.pose(i) * Eigen::Vector3d(c.x[k], c.y[k], c.z[k]);
            cw.add(p.x(), p.y(), p.z(), c.intensity[k]);
        }
        cw.close();
    }
    r = hif::test::clean(w + "/registered", w + "/registered_out",
                         [&](hif::jobs::CleanOptions& o)
                         {
                             o.picture = false;
                             o.poses = w + "/imu_poses.txt";
                             o.extrinsic = text;
                             o.world_frame = true;
                         });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("in their frame, the clouds in the world frame"), std::string::npos)
        << r.output;
    // summary.json says where the poses came from.
    {
        const auto poses = readJson(w + "/registered_out/summary.json")["poses"];
        EXPECT_EQ(poses["trajectory"].get<std::string>(), w + "/imu_poses.txt");
        EXPECT_TRUE(poses["world_frame"].get<bool>());
        const auto e = poses["extrinsic_xyz_qxyzw"].get<std::vector<double>>();
        const std::vector<double> expected{0.3, -0.1,           0.2,           0.0,
                                           0.0, std::sqrt(0.5), std::sqrt(0.5)};
        ASSERT_EQ(e.size(), expected.size());
        for (std::size_t k = 0; k < e.size(); ++k) EXPECT_NEAR(e[k], expected[k], 1e-12) << k;
        EXPECT_TRUE(readJson(w + "/kitti_out/summary.json")["poses"].is_null());
    }
    const auto registered = predictions(w + "/registered_out", seq.size());
    ASSERT_EQ(registered.size(), reference.size());
    differ = 0;
    for (std::size_t i = 0; i < registered.size(); ++i) differ += registered[i] != reference[i];
    // The world coordinates through float32 and back: a point on a cell's border may change
    // sides (8 of 1,234,476 did).
    EXPECT_LE(differ, reference.size() / 20000) << differ << " of " << reference.size();

    expectError(withExtrinsic(dir, w + "/o1", "", text),
                "--extrinsic is for a folder of clouds; '" + dir + "' is a KITTI sequence folder");
    expectError(withExtrinsic(w + "/scans", w + "/o2", w + "/imu_poses.txt", "0.3 -0.1 0.2"),
                "'--extrinsic' '0.3 -0.1 0.2': expected 7 numbers (x y z qx qy qz qw) or 12");
    expectError(withExtrinsic(w + "/scans", w + "/o3", w + "/imu_poses.txt", "0 0 0 0 0 0 2"),
                "'--extrinsic' '0 0 0 0 0 0 2': the quaternion (qx qy qz qw) has norm 2");
    expectError(withExtrinsic(w + "/scans", w + "/o4", w + "/imu_poses.txt", "0 0 x 0 0 0 1"),
                "number 3 of 7, 'x', is not a number");
    expectError(
        hif::test::clean(dir, w + "/o5", [&](hif::jobs::CleanOptions& o) { o.world_frame = true; }),
        "--world-frame is for a folder of clouds; '" + dir + "' is a KITTI sequence");
}

// hdl_graph_slam saves its keyframes (interactive_slam reads them) as NNNNNN/cloud.pcd and
// NNNNNN/data, the optimized pose printed by Eigen to 6 significant digits: read as they are,
// they give the KITTI folder's classes but for the points those digits move; a flag of a
// folder of clouds is refused, and a keyframe without its cloud is named.
TEST(SlamFolders, HdlGraphSlamKeyframesAreScansAtTheirEstimates)
{
    HIF_REQUIRE_KITTI_SEQUENCE(kittiClip());
    const WorkDir work = workDir("slam_keyframes_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const std::string dir = hif::test::firstScans(kittiClip(), kClipScans, w + "/clip");
    const hif::io::KittiSequence seq(dir);
    for (std::size_t i = 0; i < seq.size(); ++i)
    {
        const std::string k = w + "/keyframes/" + hif::io::frameName(i);
        fs::create_directories(k);
        const hif::io::Cloud c = seq.readScan(i);
        hif::io::CloudWriter cw({k + "/cloud.pcd"});
        for (std::size_t j = 0; j < c.size(); ++j) cw.add(c.x[j], c.y[j], c.z[j], c.intensity[j]);
        cw.close();
        std::ofstream data(k + "/data");
        const double t = 1317022176.0 + seq.time(i);
        data << "stamp " << static_cast<long long>(t) << " "
             << std::llround((t - std::floor(t)) * 1e9) << "\n"
             << "estimate\n"
             << seq.pose(i).matrix() << "\n"
             << "odom\n"
             << seq.pose(i).matrix() << "\n"
             << "accum_distance 0\nid " << i << "\n";
    }
    Result r = clean(dir, w + "/kitti_out");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto reference = predictions(w + "/kitti_out", seq.size());
    r = clean(w + "/keyframes", w + "/keyframes_out");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto got = predictions(w + "/keyframes_out", seq.size());
    ASSERT_EQ(got.size(), reference.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < got.size(); ++i) differ += got[i] != reference[i];
    // The poses' 6 digits: a point on a cell's border may change sides (1 did).
    EXPECT_LE(differ, kBorderPoints) << differ << " of " << reference.size();

    expectError(hif::test::clean(w + "/keyframes", w + "/o1",
                                 [&](hif::jobs::CleanOptions& o) { o.world_frame = true; }),
                "--world-frame is for a folder of clouds; '" + w +
                    "/keyframes' is a keyframe (hdl_graph_slam) folder");
    fs::remove(w + "/keyframes/000003/cloud.pcd");
    expectError(
        clean(w + "/keyframes", w + "/o2"),
        "keyframes/000003/cloud.pcd' does not exist (a keyframe's points, beside its data)");
    fs::copy_file(w + "/keyframes/000002/cloud.pcd", w + "/keyframes/000003/cloud.pcd");
    std::ofstream(w + "/keyframes/000004/data") << "stamp 1 2\nodom\n";
    expectError(clean(w + "/keyframes", w + "/o3"), "has no estimate");
}

TEST(SlamFolders, PosesThatDoNotBelongToTheScansAreWarnedAboutAtTheStart)
{
    HIF_REQUIRE_KITTI_SEQUENCE(kittiClip());
    const WorkDir work = workDir("slam_poses_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const std::string dir = hif::test::firstScans(kittiClip(), kClipScans, w + "/clip");
    const hif::io::KittiSequence seq(dir);
    writeScans(seq, w + "/scans", ".pcd");
    const auto right = lidarPoses(seq);
    // The two mistakes the peers' trackers see most: KITTI's camera poses used as the LiDAR's
    // (another frame), and the world-to-sensor transform instead of sensor-to-world.
    std::vector<Eigen::Isometry3d> camera, inverted;
    for (const Eigen::Isometry3d& T : right)
    {
        camera.push_back(seq.Tr() * T * seq.Tr().inverse());
        inverted.push_back(T.inverse());
    }
    for (const auto& [name, poses] :
         {std::make_pair("camera", camera), std::make_pair("inverted", inverted)})
    {
        SCOPED_TRACE(name);
        const std::string file = w + "/" + name + "_poses.txt";
        writeKittiPoses(poses, file);
        const Result r = clean(w + "/scans", w + "/" + name + "_out", file);
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("warning: the poses may not belong to the scans"),
                  std::string::npos)
            << r.output;
        // Said before the run was spent: ahead of the classifying pass's report.
        EXPECT_LT(r.output.find("may not belong"), r.output.find("kept")) << r.output;
        EXPECT_TRUE(
            readJson(w + "/" + name + "_out/summary.json")["poses_check"]["doubted"].get<bool>());
    }
    // A run shorter than the check's pairs is checked on the pairs it has, online too; the
    // right poses are not doubted.
    fs::create_directories(w + "/three");
    for (std::size_t i = 0; i < 3; ++i)
        fs::copy_file(w + "/scans/" + hif::io::frameName(i) + ".pcd",
                      w + "/three/" + hif::io::frameName(i) + ".pcd");
    for (const bool online : {false, true})
    {
        SCOPED_TRACE(online ? "online" : "offline");
        const std::string tag = online ? "_online" : "";
        const Result r = hif::test::clean(w + "/three", w + "/three_camera" + tag,
                                          [&](hif::jobs::CleanOptions& o)
                                          {
                                              o.picture = false;
                                              o.poses = w + "/camera_poses.txt";
                                              o.online = online;
                                          });
        ASSERT_EQ(r.code, 0) << r.output;
        EXPECT_NE(r.output.find("warning: the poses may not belong to the scans: at their poses, "
                                "consecutive scans share"),
                  std::string::npos)
            << r.output;
        EXPECT_NE(r.output.find("median of the first 2 pairs"), std::string::npos) << r.output;
    }
    writeKittiPoses(right, w + "/right_poses.txt");
    const Result r = clean(w + "/three", w + "/three_right", w + "/right_poses.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("may not belong"), std::string::npos) << r.output;
    EXPECT_EQ(readJson(w + "/three_right/summary.json")["poses_check"]["pairs"].get<std::size_t>(),
              2u);
    // A scan of a few points (cut short) is passed over, not taken for a misplaced one: its
    // two pairs would outvote the one good pair of so short a run.
    {
        hif::io::CloudWriter c({w + "/three/000001.pcd"});
        for (int k = 0; k < 10; ++k) c.add(5.0 + k, 1.0, -1.0, 1.0f);
        c.close();
    }
    const Result cut = clean(w + "/three", w + "/three_cut", w + "/right_poses.txt");
    ASSERT_EQ(cut.code, 0) << cut.output;
    EXPECT_EQ(cut.output.find("may not belong"), std::string::npos) << cut.output;
    EXPECT_EQ(readJson(w + "/three_cut/summary.json")["poses_check"]["pairs"].get<std::size_t>(),
              1u);
}

TEST(SlamFolders, WrongFoldersAndTrajectoriesAreNamed)
{
    const WorkDir work = workDir("slam_errors_" + std::to_string(getpid()));
    const std::string& w = work.path();
    // Three small clouds in the sensor frame.
    fs::create_directories(w + "/scans");
    for (int i = 0; i < 3; ++i)
    {
        hif::io::CloudWriter c({w + "/scans/" + hif::io::frameName(i) + ".pcd"});
        for (int k = 0; k < 100; ++k) c.add(5.0 + 0.01 * k, 1.0, -1.0, 1.0f);
        c.close();
    }
    const auto write = [&](const std::string& name, const std::string& text)
    {
        std::ofstream(w + "/" + name) << text;
        return w + "/" + name;
    };
    const std::string id = "1 0 0 0 0 1 0 0 0 0 1 0\n";
    // Clouds of two prefixes: neither is the scans.
    fs::create_directories(w + "/prefixes");
    for (const char* name : {"a_1.pcd", "b_2.pcd"})
        fs::copy_file(w + "/scans/000000.pcd", w + "/prefixes/" + name);
    std::ofstream(w + "/prefixes/poses.txt") << id;
    expectError(clean(w + "/prefixes", w + "/o0"),
                "has no scan (clouds named by their number, NNNNNN.pcd, .ply or .bin, or by their "
                "time, 1317022176.580342102.pcd); it holds a_1.pcd, b_2.pcd");
    // A single cloud: what was given and what is read.
    expectError(clean(w + "/scans/000000.pcd", w + "/o1"),
                "is one point cloud (pcd), without a pose");
    // A folder of clouds without poses.
    expectError(clean(w + "/scans", w + "/o2"), "neither velodyne/, pcd/, poses.txt nor keyframes");
    // Fewer poses than clouds.
    expectError(clean(w + "/scans", w + "/o3", write("two.txt", id + id)),
                "has 2 poses for the 3 scans");
    // Neither format.
    expectError(clean(w + "/scans", w + "/o4", write("seven.txt", "1 2 3 4 5 6 7\n")),
                "line 1 has 7 numbers: neither a KITTI pose (12: a 3x4 matrix) nor a TUM pose");
    // A TUM quaternion that is not a rotation, and times going back.
    expectError(clean(w + "/scans", w + "/o5",
                      write("q.txt", "0 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 2\n0.2 0 0 0 0 0 0 1\n")),
                "line 2: the quaternion (qx qy qz qw) has norm 2");
    expectError(clean(w + "/scans", w + "/o6",
                      write("t.txt", "0 0 0 0 0 0 0 1\n0.2 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 1\n")),
                "line 3: time 0.1 does not come after");
    // A line of another length in the middle.
    expectError(clean(w + "/scans", w + "/o7", write("mixed.txt", id + "0 0 0 0 0 0 0 1\n" + id)),
                "line 2 has 8 numbers where the lines before have 12");
    // --poses with a KITTI folder, and .pcd beside .ply.
    fs::create_directories(w + "/kitti/velodyne");
    expectError(clean(w + "/kitti", w + "/o8", write("three.txt", id + id + id)),
                "--poses is for a folder of clouds");
    fs::copy_file(w + "/scans/000000.pcd", w + "/scans/000003.ply");
    expectError(clean(w + "/scans", w + "/o9", w + "/three.txt"),
                "holds scans of two kinds (000000.pcd, 000003.ply)");
    fs::remove(w + "/scans/000003.ply");
    // A cloud that says it is in the world frame.
    {
        hif::io::CloudWriter c({w + "/scans/000002.pcd"});
        Eigen::Isometry3d vp = Eigen::Isometry3d::Identity();
        vp.translation() = Eigen::Vector3d(10, 0, 0);
        c.setViewpoint(vp);
        c.add(5.0, 1.0, -1.0, 1.0f);
        c.close();
    }
    expectError(clean(w + "/scans", w + "/o10", w + "/three.txt"),
                "000002.pcd' has a VIEWPOINT other than the identity");
    // Nothing was written for any of them.
    for (int k = 1; k <= 10; ++k) EXPECT_FALSE(fs::exists(w + "/o" + std::to_string(k))) << k;
}

// MRPT's rosbag2rawlog turns a ROS bag's sensor_msgs/PointCloud2 messages into a rawlog of
// CObservationPointCloud, each in the sensor's frame with the message's time and no pose (in
// MRPT 2.5.8, points without their intensity, and beside them the bag's other sensors, an IMU
// here). With the SLAM system's trajectory (--poses) its scans get the classes of the same
// clouds as a folder: in the TUM format each at the pose of its time, in the KITTI format the
// k-th at the k-th pose; scans outside the trajectory are left out and counted; a rawlog with
// poses of its own, a scan without a time and too short a trajectory are named.
TEST(SlamFolders, ARawlogWithoutPosesTakesATrajectorysPoses)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const WorkDir work = workDir("slam_rawlog_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const hif::io::KittiSequence seq(dir);
    constexpr std::size_t kScans = 6;
    constexpr double kStart = 1317022176.0;  // the recording's clock
    const TimedClouds timed{kStart};
    const auto stamp = [&](std::size_t i) { return timed.stamp(seq, i); };
    // The rawlog (gzip, observations only) and, for reference, the same clouds as a folder of
    // clouds named by their time and one named by their number.
    const auto writeRawlog =
        [&](const std::string& file, bool own_poses, bool times, bool two_lidars = false)
    {
        mrpt::io::CFileGZOutputStream f(file);
        auto arch = mrpt::serialization::archiveFrom(f);
        for (std::size_t i = 0; i < kScans; ++i)
        {
            const hif::io::Cloud c = seq.readScan(i);
            auto points = mrpt::maps::CSimplePointsMap::Create();
            for (std::size_t k = 0; k < c.size(); ++k) points->insertPoint(c.x[k], c.y[k], c.z[k]);
            if (own_poses)
            {
                auto rp = mrpt::obs::CObservationRobotPose::Create();
                rp->pose.mean = mrpt::poses::CPose3D::FromHomogeneousMatrix(seq.pose(i).matrix());
                arch << *rp;
            }
            auto obs = mrpt::obs::CObservationPointCloud::Create();
            obs->sensorLabel = two_lidars && i % 2 == 1 ? "ouster" : "velodyne";
            obs->pointcloud = points;
            obs->timestamp =
                times ? mrpt::Clock::fromDouble(kStart + seq.time(i)) : INVALID_TIMESTAMP;
            arch << *obs;
            auto imu = mrpt::obs::CObservationIMU::Create();
            imu->timestamp = obs->timestamp;
            arch << *imu;
        }
    };
    writeRawlog(w + "/bag.rawlog", false, true);
    timed.write(seq, kScans, w + "/timed", w + "/trajectory.txt");
    std::vector<Eigen::Isometry3d> poses;
    fs::create_directories(w + "/numbered");
    for (std::size_t i = 0; i < kScans; ++i)
    {
        fs::copy_file(w + "/timed/" + stamp(i) + ".pcd",
                      w + "/numbered/" + hif::io::frameName(i) + ".pcd");
        poses.push_back(seq.pose(i));
    }
    writeKittiPoses(poses, w + "/kitti_format.txt");

    // TUM: the poses of the scans' times.
    Result r = clean(w + "/bag.rawlog", w + "/rawlog_out", w + "/trajectory.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    r = clean(w + "/timed", w + "/timed_out", w + "/trajectory.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    for (std::size_t i = 0; i < kScans; ++i)
        EXPECT_EQ(
            hif::io::readLabels(w + "/rawlog_out/predictions/" + hif::io::frameName(i) + ".label"),
            hif::io::readLabels(w + "/timed_out/predictions/" + stamp(i) + ".label"))
            << i;
    {
        const auto summary = readJson(w + "/rawlog_out/summary.json");
        EXPECT_EQ(summary["poses"]["trajectory"].get<std::string>(), w + "/trajectory.txt");
        EXPECT_EQ(summary["scans_left_out"].get<std::size_t>(), 0u);
        EXPECT_EQ(summary["skipped_objects"].get<std::size_t>(), kScans);  // the IMU's
    }
    // KITTI format: one pose a scan, in order.
    r = clean(w + "/bag.rawlog", w + "/rawlog_kitti_out", w + "/kitti_format.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(w + "/numbered", w + "/numbered_out", w + "/kitti_format.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(predictions(w + "/rawlog_kitti_out", kScans),
              predictions(w + "/numbered_out", kScans));

    // The trajectory starts after the first scan: that scan is left out, counted and said.
    withoutFirstPose(w + "/trajectory.txt", w + "/late.txt");
    r = clean(w + "/bag.rawlog", w + "/late_out", w + "/late.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("warning: 1 of the " + std::to_string(kScans) + " scans of rawlog '" +
                            w + "/bag.rawlog' have no pose in '" + w + "/late.txt'"),
              std::string::npos)
        << r.output;
    EXPECT_FALSE(fs::exists(w + "/late_out/predictions/000000.label"));
    EXPECT_EQ(hif::io::readLabels(w + "/late_out/predictions/000001.label").size(),
              seq.readScan(1).size());
    EXPECT_EQ(readJson(w + "/late_out/summary.json")["scans_left_out"].get<std::size_t>(), 1u);

    // What does not go together.
    {
        std::ofstream(w + "/before.txt") << "1000 0 0 0 0 0 0 1\n1001 0 0 0 0 0 0 1\n";
        std::ofstream(w + "/two.txt") << "1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 0 0 1 0 0 0 0 1 0\n";
    }
    expectError(clean(w + "/bag.rawlog", w + "/o1", w + "/before.txt"),
                "none of the scans has a pose: " + std::to_string(kScans) + " of the " +
                    std::to_string(kScans) + " scans of rawlog");
    expectError(clean(w + "/bag.rawlog", w + "/o2", w + "/two.txt"),
                "has 2 poses, and rawlog '" + w + "/bag.rawlog' more scans: scan 2 has none");
    writeRawlog(w + "/posed.rawlog", true, true);
    expectError(clean(w + "/posed.rawlog", w + "/o3", w + "/trajectory.txt"),
                "rawlog '" + w +
                    "/posed.rawlog' holds its own poses (a CObservationRobotPose "
                    "before scan 0)");
    writeRawlog(w + "/untimed.rawlog", false, false);
    expectError(clean(w + "/untimed.rawlog", w + "/o4", w + "/trajectory.txt"),
                "rawlog '" + w + "/untimed.rawlog': scan 0 has no time, which the poses of '" + w +
                    "/trajectory.txt' (TUM format: time x y z qx qy qz qw) are found by");
    expectError(hif::test::clean(w + "/bag.rawlog", w + "/o5",
                                 [&](hif::jobs::CleanOptions& o)
                                 {
                                     o.poses = w + "/trajectory.txt";
                                     o.world_frame = true;
                                 }),
                "--world-frame goes with a folder of clouds, and '" + w + "/bag.rawlog' is a file");
    expectError(
        hif::test::clean(w + "/bag.rawlog", w + "/o6",
                         [&](hif::jobs::CleanOptions& o) { o.extrinsic = "0 0 0 0 0 0 1"; }),
        "for a rawlog (" + w + "/bag.rawlog) it goes with --poses");
    writeRawlog(w + "/two.rawlog", false, true, true);
    expectError(clean(w + "/two.rawlog", w + "/o8", w + "/trajectory.txt"),
                "rawlog '" + w +
                    "/two.rawlog' holds scans of two sensors, 'velodyne' and "
                    "'ouster' (scan 1), and the trajectory of --poses places one");
    // Without --poses it is what it was: a rawlog whose scans have no pose.
    expectError(clean(w + "/bag.rawlog", w + "/o7"), "scan 0 has no pose before it");
    for (int k = 1; k <= 8; ++k) EXPECT_FALSE(fs::exists(w + "/o" + std::to_string(k))) << k;
}

// The same through a real ROS 1 bag: the clouds recorded as a driver publishes them
// (sensor_msgs/PointCloud2, x y z intensity), turned into a rawlog by MRPT's rosbag2rawlog
// (Debian's mrpt-apps) and cleaned at the poses of the SLAM system's TUM trajectory: the
// classes of the same clouds in a folder named by their time. Without a trajectory,
// hif-icp-slam's poses place them.
TEST(SlamFolders, ARosBagThroughRosbag2rawlogGetsTheClassesOfItsClouds)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    if (std::system("command -v rosbag2rawlog > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "rosbag2rawlog not installed (Debian package mrpt-apps; "
                        "scripts/install-deps.sh)";
    const WorkDir work = workDir("slam_rosbag_" + std::to_string(getpid()));
    const std::string& w = work.path();
    const hif::io::KittiSequence seq(dir);
    constexpr std::size_t kScans = 6;
    const TimedClouds timed{1317022176.0};
    std::vector<hif::test::BagCloud> clouds;
    for (std::size_t i = 0; i < kScans; ++i)
    {
        const hif::io::Cloud c = seq.readScan(i);
        hif::test::BagCloud m{timed.start + seq.time(i), {}};
        for (std::size_t k = 0; k < c.size(); ++k)
            m.xyzi.insert(m.xyzi.end(), {c.x[k], c.y[k], c.z[k], c.intensity[k]});
        clouds.push_back(std::move(m));
    }
    hif::test::writeRosBag(w + "/run.bag", "/velodyne_points", "velodyne", clouds);
    std::ofstream(w + "/bag.yml") << "sensors:\n  lidar:\n    type: 'CObservationPointCloud'\n"
                                     "    topic: '/velodyne_points'\n";
    const std::string cmd = "rosbag2rawlog -c " + w + "/bag.yml -f map -o " + w + "/run.rawlog " +
                            w + "/run.bag > " + w + "/rosbag2rawlog.log 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << hif::test::bytesOf(w + "/rosbag2rawlog.log");
    timed.write(seq, kScans, w + "/timed", w + "/trajectory.txt");

    Result r = clean(w + "/run.rawlog", w + "/rawlog_out", w + "/trajectory.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("scans " + std::to_string(kScans) + ","), std::string::npos)
        << r.output;
    r = clean(w + "/timed", w + "/timed_out", w + "/trajectory.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    for (std::size_t i = 0; i < kScans; ++i)
        EXPECT_EQ(
            hif::io::readLabels(w + "/rawlog_out/predictions/" + hif::io::frameName(i) + ".label"),
            hif::io::readLabels(w + "/timed_out/predictions/" + timed.stamp(seq, i) + ".label"))
            << i;
    // Without a trajectory: hif-icp-slam tracks the rawlog, and its poses place the scans.
    r = hif::test::icpSlam(w + "/run.rawlog", w + "/slam");
    ASSERT_EQ(r.code, 0) << r.output;
    r = clean(w + "/run.rawlog", w + "/tracked_out", w + "/slam/poses_kitti.txt");
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output.find("warning"), std::string::npos) << r.output;  // the poses check passed
    EXPECT_EQ(readJson(w + "/tracked_out/summary.json")["scans"].get<std::size_t>(), kScans);
    // Online too (a SLAM system's use): a class for every point of every scan.
    r = hif::test::clean(w + "/run.rawlog", w + "/online_out",
                         [&](hif::jobs::CleanOptions& o)
                         {
                             o.picture = false;
                             o.poses = w + "/trajectory.txt";
                             o.online = true;
                         });
    ASSERT_EQ(r.code, 0) << r.output;
    for (std::size_t i = 0; i < kScans; ++i)
        EXPECT_EQ(
            hif::io::readLabels(w + "/online_out/predictions/" + hif::io::frameName(i) + ".label")
                .size(),
            seq.readScan(i).size())
            << i;
}

// An organized cloud (Ouster's, Hesai's) holds 0 0 0 where a beam returned nothing: such a
// point is no measurement. It is read as an invalid point: labelled moving, counted as invalid
// (not as a return nearer than min_range), and written to no cloud.
TEST(SlamFolders, AnOrganizedCloudsNoReturnsAreInvalidPoints)
{
    const WorkDir work = workDir("slam_no_return_" + std::to_string(getpid()));
    const std::string& w = work.path();
    fs::create_directories(w + "/scans");
    for (int i = 0; i < 3; ++i)
    {
        hif::io::CloudWriter c({w + "/scans/" + hif::io::frameName(i) + ".pcd"});
        for (int k = 0; k < 150; ++k)
            k % 3 == 2 ? c.add(0.0, 0.0, 0.0, 0.0f) : c.add(5.0 + 0.01 * k, 1.0, -1.0, 1.0f);
        c.close();
    }
    std::ofstream(w + "/scans/poses.txt") << "1 0 0 0 0 1 0 0 0 0 1 0\n"
                                             "1 0 0 0.1 0 1 0 0 0 0 1 0\n"
                                             "1 0 0 0.2 0 1 0 0 0 0 1 0\n";
    const Result r = clean(w + "/scans", w + "/out");
    ASSERT_EQ(r.code, 0) << r.output;
    const auto summary = readJson(w + "/out/summary.json");
    EXPECT_EQ(summary["points_invalid"].get<std::size_t>(), 150u);
    EXPECT_EQ(summary["points_near"].get<std::size_t>(), 0u);
    const auto labels = hif::io::readLabels(w + "/out/predictions/000001.label");
    ASSERT_EQ(labels.size(), 150u);
    for (std::size_t k = 2; k < labels.size(); k += 3) EXPECT_EQ(labels[k], hif::io::kLabelMoving);
    // No cloud holds a point at a sensor's place.
    for (const char* cloud : {"/out/static_map.ply", "/out/removed.ply"})
    {
        const hif::io::PcdCloud c = hif::io::readPly(w + cloud);
        std::size_t at_sensor = 0;
        for (std::size_t k = 0; k < c.size(); ++k) at_sensor += std::abs(c.point(k).z()) < 1e-9;
        EXPECT_EQ(at_sensor, 0u) << cloud;
    }
}
