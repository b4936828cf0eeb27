// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_slam_files.cpp
 * @brief  The files LiDAR SLAM systems write: PLY clouds (binary and ASCII, any scalar types,
 *         extra properties) read back as written, the extra fields hif writes (class, scan,
 *         time) in PLY and PCD, and KITTI- and TUM-format trajectories.
 */
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "hif/io/CloudFiles.h"
#include "hif/io/Trajectory.h"

namespace
{
std::string tempDir(const std::string& name)
{
    const std::string d = std::filesystem::temp_directory_path().string() + "/hif_" + name + "_" +
                          std::to_string(getpid());
    std::filesystem::create_directories(d);
    return d;
}

std::string write(const std::string& file, const std::string& text)
{
    std::ofstream(file, std::ios::binary) << text;
    return file;
}

/** Throws, and the message holds `what`. */
template <typename F>
void expectThrowWith(F f, const std::string& what)
{
    try
    {
        f();
        ADD_FAILURE() << "no error; expected '" << what << "'";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
}
}  // namespace

TEST(ReadPly, ReadsBackWhatCloudWriterWritesWithEveryFieldAndWideCoordinates)
{
    const std::string d = tempDir("ply");
    hif::io::PointFields all;
    all.colour = all.label = all.scan = all.time = true;
    for (const double offset : {0.0, 5.0e6})  // float32, then UTM-like float64 coordinates
    {
        SCOPED_TRACE(offset);
        hif::io::CloudWriter w({d + "/a.ply"}, all);
        for (int k = 0; k < 50; ++k)
        {
            hif::io::CloudPoint p;
            p.x = offset + 0.125 * k;
            p.y = -3.5 + k;
            p.z = 1.25;
            p.intensity = 0.5f * float(k);
            p.red = 200;
            p.label = static_cast<uint8_t>(k % 2);
            p.scan = 7;
            p.time = 1.5;
            w.add(p);
        }
        w.close();
        const hif::io::PcdCloud c = hif::io::readPly(d + "/a.ply");
        ASSERT_EQ(c.size(), 50u);
        EXPECT_FALSE(c.has_viewpoint);
        for (std::size_t k = 0; k < 50; ++k)
        {
            EXPECT_EQ(c.point(k).x(), offset + 0.125 * double(k));
            EXPECT_EQ(c.point(k).y(), -3.5 + double(k));
            EXPECT_EQ(c.intensity[k], 0.5f * float(k));
        }
    }
    // The PCD gets the same fields after x y z intensity, and readPcd reads past them.
    hif::io::PointFields pcd_fields;
    pcd_fields.label = pcd_fields.scan = pcd_fields.time = true;
    hif::io::CloudWriter w({d + "/b.pcd"}, pcd_fields);
    w.add(1.0, 2.0, 3.0, 4.0f);
    w.close();
    std::ifstream f(d + "/b.pcd");
    std::string header((std::istreambuf_iterator<char>(f)), {});
    EXPECT_NE(header.find("FIELDS x y z intensity class scan time\nSIZE 4 4 4 4 1 4 8\n"
                          "TYPE F F F F U U F\n"),
              std::string::npos)
        << header;
    const hif::io::PcdCloud b = hif::io::readPcd(d + "/b.pcd");
    ASSERT_EQ(b.size(), 1u);
    EXPECT_EQ(b.z[0], 3.0f);
    EXPECT_EQ(b.intensity[0], 4.0f);
    std::filesystem::remove_all(d);
}

TEST(ReadPly, ReadsAsciiAndOtherTypesAndNamesWhatItCannotRead)
{
    const std::string d = tempDir("ply_ascii");
    // CloudCompare-style: double coordinates, a uchar colour first, intensity as a ushort.
    const std::string ascii = write(d + "/a.ply",
                                    "ply\nformat ascii 1.0\ncomment x\nelement vertex 2\n"
                                    "property uchar red\nproperty double x\nproperty double y\n"
                                    "property double z\nproperty ushort intensity\n"
                                    "element face 0\nproperty list uchar int vertex_indices\n"
                                    "end_header\n10 1.5 2 3 100\n20 -1 nan 4 7\n");
    const hif::io::PcdCloud c = hif::io::readPly(ascii);
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c.point(0), Eigen::Vector3d(1.5, 2, 3));
    EXPECT_EQ(c.intensity[0], 100.0f);
    EXPECT_TRUE(std::isnan(c.y[1]));
    EXPECT_EQ(c.intensity[1], 7.0f);

    // A binary body shorter than the header says.
    std::string bin =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
        "property float y\nproperty float z\nend_header\n";
    bin += std::string(24, '\0');  // two vertices of three
    expectThrowWith([&] { (void)hif::io::readPly(write(d + "/short.ply", bin)); },
                    "short.ply' is truncated: it says 3 vertices");
    expectThrowWith(
        [&]
        {
            (void)hif::io::readPly(write(d + "/be.ply",
                                         "ply\nformat binary_big_endian 1.0\nelement vertex 0\n"
                                         "property float x\nend_header\n"));
        },
        "has format 'binary_big_endian', which is not read");
    expectThrowWith(
        [&]
        {
            (void)hif::io::readPly(write(d + "/noz.ply",
                                         "ply\nformat ascii 1.0\nelement vertex 1\nproperty "
                                         "float x\nproperty float y\nend_header\n1 2\n"));
        },
        "has no x, y and z vertex properties");
    expectThrowWith([&] { (void)hif::io::readPly(write(d + "/no.ply", "solid stl\n")); },
                    "does not start with 'ply'");
    expectThrowWith(
        [&]
        {
            (void)hif::io::readPly(write(d + "/word.ply",
                                         "ply\nformat ascii 1.0\nelement vertex 1\nproperty "
                                         "float x\nproperty float y\nproperty float z\n"
                                         "end_header\n1 2 z\n"));
        },
        "vertex line 1: 'z' is not a number");
    std::filesystem::remove_all(d);
}

TEST(Trajectory, KittiAndTumFilesGiveTheSamePoses)
{
    const std::string d = tempDir("trajectory");
    // A quarter turn about z, at (1, 2, 3), then the identity at (4, 5, 6).
    const auto kitti = hif::io::readTrajectory(
        write(d + "/k.txt", "0 -1 0 1 1 0 0 2 0 0 1 3\n\n1 0 0 4 0 1 0 5 0 0 1 6\n"));
    EXPECT_EQ(kitti.format, hif::io::Trajectory::Format::Kitti);
    EXPECT_TRUE(kitti.times.empty());
    const double h = std::sqrt(0.5);
    std::ostringstream tum_text;
    tum_text.precision(17);
    tum_text << "# timestamp tx ty tz qx qy qz qw\n10.5 1 2 3 0 0 " << h << " " << h
             << "\n10.6 4 5 6 0 0 0 1\n";
    const auto tum = hif::io::readTrajectory(write(d + "/t.txt", tum_text.str()));
    EXPECT_EQ(tum.format, hif::io::Trajectory::Format::Tum);
    ASSERT_EQ(tum.size(), 2u);
    ASSERT_EQ(kitti.size(), 2u);
    EXPECT_EQ(tum.times, (std::vector<double>{10.5, 10.6}));
    for (std::size_t i = 0; i < 2; ++i)
        EXPECT_TRUE(tum.poses[i].isApprox(kitti.poses[i], 1e-12)) << i;
    expectThrowWith([&] { (void)hif::io::readTrajectory(write(d + "/e.txt", "# nothing\n")); },
                    "holds no pose");
    expectThrowWith(
        [&] { (void)hif::io::readTrajectory(write(d + "/r.txt", "2 0 0 0 0 1 0 0 0 0 1 0\n")); },
        "line 1: not a rigid motion");
    expectThrowWith([&]
                    { (void)hif::io::readTrajectory(write(d + "/n.txt", "0 1 2 inf 0 0 0 1\n")); },
                    "line 1: number 4 of 8, 'inf', is not finite");
    expectThrowWith([&] { (void)hif::io::readTrajectory(d + "/missing.txt"); },
                    "missing.txt' cannot be opened");
    std::filesystem::remove_all(d);
}

// A scan's pose by its time: the pose of that time (to kSameTime), else the two around it
// interpolated (position linearly, rotation by slerp: a quarter turn half-way is an eighth),
// never across a gap wider than asked, nor before the first pose or after the last.
TEST(Trajectory, AnExtrinsicsSevenNumbersReadBackAsThePose)
{
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    pose.translation() = Eigen::Vector3d(0.1, -0.25, 1.5);
    const auto n = hif::io::xyzQxyzw(pose);
    EXPECT_EQ(n[0], 0.1);
    EXPECT_EQ(n[1], -0.25);
    EXPECT_EQ(n[2], 1.5);
    std::ostringstream text;
    text.precision(17);
    for (const double v : n) text << v << ' ';
    EXPECT_TRUE(hif::io::parseExtrinsic(text.str()).isApprox(pose, 1e-12)) << text.str();
}

TEST(Trajectory, APoseAtATimeIsThePoseThenOrTheTwoAroundItInterpolated)
{
    hif::io::Trajectory tr;
    tr.format = hif::io::Trajectory::Format::Tum;
    Eigen::Isometry3d a = Eigen::Isometry3d::Identity(), b = a, c = a;
    b.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    b.translation() = Eigen::Vector3d(2, 0, 0);
    c.translation() = Eigen::Vector3d(2, 4, 0);
    tr.poses = {a, b, c};
    tr.times = {100.0, 100.1, 100.6};  // a gap of 0.5 s after the second
    EXPECT_DOUBLE_EQ(hif::io::medianSpacing(tr), 0.5);

    const auto exact = hif::io::poseAt(tr, 100.1 + 0.5 * hif::io::kSameTime, 0.2);
    ASSERT_TRUE(exact);
    EXPECT_TRUE(exact->isApprox(b, 1e-15));
    const auto mid = hif::io::poseAt(tr, 100.05, 0.2);
    ASSERT_TRUE(mid);
    EXPECT_TRUE(mid->translation().isApprox(Eigen::Vector3d(1, 0, 0), 1e-9));
    const Eigen::AngleAxisd turn(mid->linear());
    EXPECT_NEAR(turn.angle(), M_PI / 4, 1e-9);
    EXPECT_NEAR(turn.axis().z(), 1.0, 1e-9);
    // The gap: bridged only when wide enough is allowed.
    EXPECT_FALSE(hif::io::poseAt(tr, 100.3, 0.2));
    const auto bridged = hif::io::poseAt(tr, 100.35, 0.5);
    ASSERT_TRUE(bridged);
    EXPECT_TRUE(bridged->translation().isApprox(Eigen::Vector3d(2, 2, 0), 1e-9));
    // Outside the trajectory, and a trajectory without times.
    EXPECT_FALSE(hif::io::poseAt(tr, 99.9, 10.0));
    EXPECT_FALSE(hif::io::poseAt(tr, 100.7, 10.0));
    EXPECT_TRUE(hif::io::poseAt(tr, 100.6, 0.0));  // the last pose itself
    tr.times.clear();
    EXPECT_FALSE(hif::io::poseAt(tr, 100.0, 10.0));
    EXPECT_EQ(hif::io::medianSpacing(tr), 0.0);
}
