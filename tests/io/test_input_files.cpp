// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_input_files.cpp
 * @brief  What the readers take and refuse: poses that are not rigid motions, a calibration with
 *         two Tr lines, numbers that are not finite or not numbers (named by line and position);
 *         PCD files with float64 coordinates (UTM) and PCL's "nan" for an invalid point; PCL's
 *         binary_compressed PCD files, and intensity as a driver's uint8; and the writer's
 *         switch to float64 where a coordinate needs it.
 */
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Rings.h"
#include "kitti_fixture.h"
#include "pcl_compressed.h"
#include "work_dir.h"

namespace fs = std::filesystem;

namespace
{
const std::string kIdentity = "1 0 0 0 0 1 0 0 0 0 1 0";

/** A one-scan KITTI folder with these poses.txt and calib.txt lines. */
std::string sequence(const hif::test::WorkDir& work, const std::vector<std::string>& poses,
                     const std::vector<std::string>& calib, const std::string& times = "0")
{
    const fs::path d = work.path();
    fs::create_directories(d / "velodyne");
    const float point[4] = {5, 0, 0, 1};
    std::ofstream(d / "velodyne" / "000000.bin", std::ios::binary)
        .write(reinterpret_cast<const char*>(point), sizeof point);
    std::ofstream p(d / "poses.txt"), c(d / "calib.txt"), t(d / "times.txt");
    for (const auto& l : poses) p << l << "\n";
    for (const auto& l : calib) c << l << "\n";
    t << times << "\n";
    return d.string();
}

std::string errorOf(const std::string& dir)
{
    try
    {
        const hif::io::KittiSequence seq(dir);
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return "no error";
}
}  // namespace

TEST(KittiSequence, APoseMustBeARigidMotion)
{
    const auto work = hif::test::tempWorkDir("input_rigid");
    const std::string tr = "Tr: " + kIdentity;
    // KITTI's own rows (6 digits) pass; a scaled rotation, zeros and a reflection do not.
    EXPECT_EQ(errorOf(sequence(work,
                               {"1 -0.000547252 -0.000750314 -0.00231195 0.000548409 "
                                "0.999999 0.00154008 -0.0396405 0.00074947 -0.00154049 "
                                "0.999999 1.24666"},
                               {tr})),
              "no error");
    const std::string scaled = errorOf(sequence(work, {"2 0 0 0 0 2 0 0 0 0 2 0"}, {tr}));
    EXPECT_NE(scaled.find("poses.txt' line 1: not a rigid motion: the rotation part is not "
                          "orthonormal (R^T R differs from the identity by up to 3"),
              std::string::npos)
        << scaled;
    EXPECT_NE(errorOf(sequence(work, {"0 0 0 0 0 0 0 0 0 0 0 0"}, {tr})).find("not a rigid motion"),
              std::string::npos);
    EXPECT_NE(errorOf(sequence(work, {"-1 0 0 0 0 1 0 0 0 0 1 0"}, {tr})).find("a reflection"),
              std::string::npos);
    // The calibration is a pose too.
    EXPECT_NE(errorOf(sequence(work, {kIdentity}, {"Tr: 1 0 0 0 0 1 0 0 0 0 0.5 0"}))
                  .find("calib.txt' line 1 (Tr): not a rigid motion"),
              std::string::npos);
}

TEST(KittiSequence, NumbersAreNamedByLineAndPosition)
{
    const auto work = hif::test::tempWorkDir("input_numbers");
    const std::string tr = "Tr: " + kIdentity;
    const auto pose = [&](const std::string& row) {
        return errorOf(sequence(work, {kIdentity, row}, {tr}));
    };
    // Only scan 0 exists, so line 2 is not read: a bad line 1 is.
    const auto first = [&](const std::string& row) { return errorOf(sequence(work, {row}, {tr})); };
    EXPECT_EQ(pose("garbage"), "no error");  // beyond the scans: not read
    EXPECT_NE(
        first("1 inf 0 0 0 1 0 0 0 0 1 0").find("line 1: number 2 of 12, 'inf', is not finite"),
        std::string::npos);
    EXPECT_NE(first("1 0 0 0 0 1 0 nan 0 0 1 0").find("number 8 of 12, 'nan', is not finite"),
              std::string::npos);
    EXPECT_NE(first("1 0 0 0 0 1 0 1.5m 0 0 1 0").find("number 8 of 12, '1.5m', is not a number"),
              std::string::npos);
    EXPECT_NE(first("1 0 0 0 0 1 0 0 0 0 1")
                  .find("expected 12 numbers (a 3x4 row-major matrix), "
                        "found 11"),
              std::string::npos);
    EXPECT_NE(first(kIdentity + " abc").find("line 1: 'abc' after the 12 numbers"),
              std::string::npos);
    EXPECT_NE(errorOf(sequence(work, {kIdentity}, {tr}, "inf"))
                  .find("times.txt' line 1: expected one finite number (seconds), found 'inf'"),
              std::string::npos);
}

TEST(KittiSequence, ACalibrationWithTwoTrLinesIsRefused)
{
    const auto work = hif::test::tempWorkDir("input_two_tr");
    const std::string e = errorOf(sequence(
        work, {kIdentity},
        {"P0: 1 0 0 0 0 1 0 0 0 0 1 0", "Tr: " + kIdentity, "Tr: 0 -1 0 0 0 0 -1 0 1 0 0 0"}));
    EXPECT_NE(e.find("calib.txt' has two 'Tr:' lines (2 and 3)"), std::string::npos) << e;
}

TEST(ReadPcd, AsciiNanIsAnInvalidPointAndFloat64KeepsTheMillimetres)
{
    const auto work = hif::test::tempWorkDir("input_pcd");
    const std::string ascii = work.path() + "/ascii.pcd";
    std::ofstream(ascii) << "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\n"
                            "COUNT 1 1 1 1\nWIDTH 3\nHEIGHT 1\nVIEWPOINT 1 2 3 1 0 0 0\nPOINTS 3\n"
                            "DATA ascii\n1 2 3 0.5\nnan nan nan 0\n-1e2 0 7 1\n";
    const hif::io::PcdCloud a = hif::io::readPcd(ascii);
    ASSERT_EQ(a.size(), 3u);
    EXPECT_TRUE(a.has_viewpoint);
    EXPECT_TRUE(std::isnan(a.x[1]) && std::isnan(a.y[1]) && std::isnan(a.z[1]));
    EXPECT_EQ(a.x[2], -100.0f);
    EXPECT_EQ(a.intensity[0], 0.5f);
    std::ofstream(ascii) << "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 x 3\n";
    try
    {
        (void)hif::io::readPcd(ascii);
        FAIL() << "'x' read as a number";
    }
    catch (const std::exception& e)
    {
        EXPECT_NE(std::string(e.what()).find("line 1 of the data: 'x' is not a number"),
                  std::string::npos)
            << e.what();
    }
    std::ofstream(ascii) << "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 1\nDATA ascii\n1 2\n";
    EXPECT_THROW((void)hif::io::readPcd(ascii), std::runtime_error);

    // A PCD with float64 x y z in UTM, as PCL writes it, with another field between.
    const std::string binary = work.path() + "/utm.pcd";
    {
        std::ofstream f(binary, std::ios::binary);
        f << "FIELDS x y z ring intensity\nSIZE 8 8 8 2 4\nTYPE F F F U F\nCOUNT 1 1 1 1 1\n"
             "POINTS 2\nDATA binary\n";
        const double p0[3] = {630123.4567, 5800321.1234, 251.0009};
        const double p1[3] = {630124.0001, 5800322.0002, 250.5};
        for (const double* p : {p0, p1})
        {
            f.write(reinterpret_cast<const char*>(p), 24);
            const uint16_t ring = 7;
            const float intensity = 0.25f;
            f.write(reinterpret_cast<const char*>(&ring), 2);
            f.write(reinterpret_cast<const char*>(&intensity), 4);
        }
    }
    const hif::io::PcdCloud u = hif::io::readPcd(binary);
    ASSERT_EQ(u.size(), 2u);
    EXPECT_FALSE(u.has_viewpoint);
    EXPECT_NEAR(u.point(0).x(), 630123.4567, 1e-6);
    EXPECT_NEAR(u.point(0).y(), 5800321.1234, 1e-6);
    EXPECT_NEAR(u.point(1).x(), 630124.0001, 1e-6);
    EXPECT_NEAR(u.point(1).z(), 250.5, 1e-6);
    EXPECT_EQ(u.intensity[1], 0.25f);
    // As float32 coordinates of their own (a sensor-frame cloud's): the same points, rounded.
    hif::io::PcdCloud f = u;
    hif::io::absorbOrigin(f);
    EXPECT_TRUE(f.origin.isZero(0.0));
    EXPECT_EQ(f.x[0], static_cast<float>(u.point(0).x()));
    EXPECT_EQ(f.y[1], static_cast<float>(u.point(1).y()));
    EXPECT_EQ(f.z[1], 250.5f);
}

// A binary body is read in chunks of records: every point of a cloud of several chunks (and a
// last, partial one) reads back as written, float32 or float64, with a field between.
TEST(ReadPcd, ABinaryBodyOfManyChunksReadsBackPointForPoint)
{
    const auto work = hif::test::tempWorkDir("input_chunks");
    constexpr std::size_t kPoints = 3 * 4096 + 123;
    const auto coordinate = [](std::size_t i, int axis)
    { return 630000.0 * (axis == 0) + 0.001 * double(i) + 10.0 * axis; };
    for (const int size : {4, 8})
    {
        const std::string file = work.path() + "/cloud" + std::to_string(size) + ".pcd";
        {
            std::ofstream f(file, std::ios::binary);
            f << "FIELDS x y z ring intensity\nSIZE " << size << " " << size << " " << size
              << " 2 4\nTYPE F F F U F\nPOINTS " << kPoints << "\nDATA binary\n";
            for (std::size_t i = 0; i < kPoints; ++i)
            {
                for (int axis = 0; axis < 3; ++axis)
                {
                    const double d = coordinate(i, axis);
                    const auto v = static_cast<float>(d);
                    f.write(size == 8 ? reinterpret_cast<const char*>(&d)
                                      : reinterpret_cast<const char*>(&v),
                            size);
                }
                const auto ring = static_cast<uint16_t>(i % 64);
                const auto intensity = static_cast<float>(i);
                f.write(reinterpret_cast<const char*>(&ring), 2);
                f.write(reinterpret_cast<const char*>(&intensity), 4);
            }
        }
        const hif::io::PcdCloud c = hif::io::readPcd(file);
        ASSERT_EQ(c.size(), kPoints);
        std::size_t wrong = 0;
        for (std::size_t i = 0; i < kPoints; ++i)
            for (int axis = 0; axis < 3; ++axis)
            {
                const double expected = size == 8 ? coordinate(i, axis)
                                                  : double(static_cast<float>(coordinate(i, axis)));
                wrong += std::abs(c.point(i)[axis] - expected) > 1e-6 ||
                         c.intensity[i] != static_cast<float>(i);
            }
        EXPECT_EQ(wrong, 0u) << "SIZE " << size;
    }
}

/** The points of a LiDAR driver's cloud (as Hesai's and Robosense's write them: intensity a
 *  uint8, a time and a ring, padding between), written by PCL as binary or binary_compressed. */
struct DriverCloud
{
    static constexpr std::size_t kPoints = 5000;
    static float coordinate(std::size_t i, int axis)
    {
        return static_cast<float>(0.01 * double(i) - 20.0 * axis);
    }
    static uint8_t intensity(std::size_t i) { return static_cast<uint8_t>(i * 7 % 256); }

    static constexpr const char* kHeader =
        "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z _ intensity "
        "timestamp ring\nSIZE 4 4 4 1 1 8 2\nTYPE F F F U U F U\nCOUNT 1 1 1 3 1 1 1\n"
        "WIDTH 5000\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 5000\n";
    static constexpr std::size_t kRecord = 4 * 3 + 3 + 1 + 8 + 2;
    static constexpr std::size_t kPacked = kRecord - 3;  // without the padding

    /** Field by field (x of every point, then y, ...), padding left out, as PCL packs it. */
    static std::vector<char> packed()
    {
        std::vector<char> body(kPoints * kPacked);
        char* at = body.data();
        for (int axis = 0; axis < 3; ++axis)
            for (std::size_t i = 0; i < kPoints; ++i, at += 4)
            {
                const float v = coordinate(i, axis);
                std::memcpy(at, &v, 4);
            }
        for (std::size_t i = 0; i < kPoints; ++i) *at++ = static_cast<char>(intensity(i));
        for (std::size_t i = 0; i < kPoints; ++i, at += 8)
        {
            const double t = 0.1 * double(i) / kPoints;
            std::memcpy(at, &t, 8);
        }
        for (std::size_t i = 0; i < kPoints; ++i, at += 2)
        {
            const auto ring = static_cast<uint16_t>(i % 32);
            std::memcpy(at, &ring, 2);
        }
        return body;
    }

    static void writeBinary(const std::string& file)
    {
        const std::vector<char> body = packed();
        std::ofstream f(file, std::ios::binary);
        f << kHeader << "DATA binary\n";
        const std::size_t widths[] = {4, 4, 4, 1, 8, 2};  // the packed fields
        for (std::size_t i = 0; i < kPoints; ++i)
        {
            std::size_t block = 0;
            for (std::size_t k = 0; k < 6; ++k)
            {
                if (k == 3) f.write("\0\0\0", 3);  // the padding, before intensity
                f.write(body.data() + block * kPoints + i * widths[k],
                        static_cast<std::streamsize>(widths[k]));
                block += widths[k];
            }
        }
    }

    /** PCL's layout: the two sizes (compressed, uncompressed), then the LZF data. */
    static std::vector<char> compressed() { return hif::test::pclCompressedBody(packed()); }

    static void writeCompressed(const std::string& file, const std::vector<char>& data)
    {
        std::ofstream f(file, std::ios::binary);
        f << kHeader << "DATA binary_compressed\n";
        f.write(data.data(), static_cast<std::streamsize>(data.size()));
    }
};

std::string readError(const std::string& file)
{
    try
    {
        (void)hif::io::readPcd(file);
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return "";
}

// PCL saves clouds as binary_compressed too (pcl::io::savePCDFileBinaryCompressed, pcl_convert):
// such a file reads as the same cloud written binary, padding fields and all; intensity stored
// as a uint8 (a driver's) reads as its value.
TEST(ReadPcd, BinaryCompressedReadsAsItsBinaryTwin)
{
    const auto work = hif::test::tempWorkDir("input_compressed");
    const std::string binary = work.path() + "/binary.pcd";
    const std::string compressed = work.path() + "/compressed.pcd";
    DriverCloud::writeBinary(binary);
    const std::vector<char> data = DriverCloud::compressed();
    DriverCloud::writeCompressed(compressed, data);
    ASSERT_LT(fs::file_size(compressed), fs::file_size(binary));

    const hif::io::PcdCloud b = hif::io::readPcd(binary);
    const hif::io::PcdCloud c = hif::io::readPcd(compressed);
    ASSERT_EQ(b.size(), DriverCloud::kPoints);
    ASSERT_EQ(c.size(), DriverCloud::kPoints);
    EXPECT_TRUE(c.has_viewpoint);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < DriverCloud::kPoints; ++i)
    {
        const float expected[3] = {DriverCloud::coordinate(i, 0), DriverCloud::coordinate(i, 1),
                                   DriverCloud::coordinate(i, 2)};
        for (const hif::io::PcdCloud* cloud : {&b, &c})
            wrong += cloud->x[i] != expected[0] || cloud->y[i] != expected[1] ||
                     cloud->z[i] != expected[2] ||
                     cloud->intensity[i] != static_cast<float>(DriverCloud::intensity(i));
    }
    EXPECT_EQ(wrong, 0u);
}

// What goes wrong in a compressed body is named, with the file: data cut short, sizes that do
// not match POINTS and the fields, data that do not uncompress.
TEST(ReadPcd, ABrokenCompressedBodyIsNamed)
{
    const auto work = hif::test::tempWorkDir("input_compressed_bad");
    const std::string file = work.path() + "/bad.pcd";
    const std::vector<char> good = DriverCloud::compressed();

    std::vector<char> cut(good.begin(),
                          good.begin() + static_cast<std::ptrdiff_t>(good.size() / 2));
    DriverCloud::writeCompressed(file, cut);
    std::string e = readError(file);
    EXPECT_NE(e.find(file), std::string::npos) << e;
    EXPECT_NE(e.find("is truncated"), std::string::npos) << e;

    std::vector<char> sizes = good;
    sizes[4] = static_cast<char>(sizes[4] + 1);  // the uncompressed size, one byte more
    DriverCloud::writeCompressed(file, sizes);
    e = readError(file);
    EXPECT_NE(
        e.find("uncompress to " + std::to_string(DriverCloud::kPoints * DriverCloud::kPacked + 1) +
               " bytes, but POINTS and its fields make " +
               std::to_string(DriverCloud::kPoints * DriverCloud::kPacked)),
        std::string::npos)
        << e;

    // A POINTS that no compressed body of this size holds is refused before anything is
    // allocated for it.
    {
        std::ofstream f(file, std::ios::binary);
        f << "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 300000000\nDATA binary_compressed\n";
        f.write(good.data(), static_cast<std::streamsize>(good.size()));
    }
    e = readError(file);
    EXPECT_NE(e.find("is truncated: POINTS says 300000000, more than " +
                     std::to_string(good.size()) + " bytes of compressed data can hold"),
              std::string::npos)
        << e;

    // A back-reference before the start of the output: LZF data that cannot be.
    std::vector<char> corrupt = good;
    corrupt[8] = static_cast<char>(0xE0);
    corrupt[9] = static_cast<char>(0xFF);
    corrupt[10] = static_cast<char>(0xFF);
    DriverCloud::writeCompressed(file, corrupt);
    e = readError(file);
    EXPECT_NE(e.find("corrupt LZF data"), std::string::npos) << e;

    std::ofstream(file) << "FIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F X\nPOINTS 1\n"
                           "DATA ascii\n1 2 3 4\n";
    e = readError(file);
    EXPECT_NE(e.find("has a field intensity of TYPE X and SIZE 4, which is not a number"),
              std::string::npos)
        << e;
}

TEST(CloudWriter, CoordinatesWidenToFloat64WhereFloat32WouldLoseMillimetres)
{
    const auto work = hif::test::tempWorkDir("input_widen");
    const std::string d = work.path();
    for (const bool expect : {false, true})
    {
        const std::vector<std::string> files{d + "/a.ply", d + "/b.pcd"};
        std::vector<Eigen::Vector3d> pts;
        for (int i = 0; i < 20000; ++i)  // enough to fill the writer's buffer before the switch
            pts.emplace_back(0.001 * i, -2.5, 1.25);
        pts.emplace_back(630000.123, 5800000.456, 250.789);  // UTM: float32 steps 0.25-0.5 m
        pts.emplace_back(1.0, 2.0, 3.0);
        {
            hif::io::CloudWriter w(files);
            if (expect) w.expectCount(pts.size());
            for (std::size_t i = 0; i < pts.size(); ++i)
                w.add(pts[i].x(), pts[i].y(), pts[i].z(), float(i % 7));
            EXPECT_TRUE(w.doubleCoordinates());
            w.close();
        }
        // Both files hold the same records behind their headers: x y z float64, intensity.
        for (const std::string& file : files)
        {
            std::ifstream in(file, std::ios::binary);
            const std::string text((std::istreambuf_iterator<char>(in)), {});
            const std::string end = file == files[0] ? "end_header\n" : "DATA binary\n";
            EXPECT_NE(text.find(file == files[0] ? "property double x\nproperty double y\n"
                                                   "property double z\nproperty float intensity\n"
                                                 : "SIZE 8 8 8 4\n"),
                      std::string::npos)
                << file;
            const auto body = text.find(end) + end.size();
            ASSERT_EQ(text.size() - body, pts.size() * 28) << file;
            for (std::size_t i = 0; i < pts.size(); ++i)
            {
                double xyz[3];
                float intensity = 0;
                std::memcpy(xyz, text.data() + body + i * 28, 24);
                std::memcpy(&intensity, text.data() + body + i * 28 + 24, 4);
                // The points before the switch were float32: exactly what float32 held.
                const Eigen::Vector3d want =
                    i + 2 < pts.size() ? pts[i].cast<float>().cast<double>() : pts[i];
                ASSERT_EQ(Eigen::Vector3d(xyz[0], xyz[1], xyz[2]), want) << file << " point " << i;
                ASSERT_EQ(intensity, float(i % 7));
            }
        }
        // Read back, a UTM cloud keeps its millimetres (offsets from its first point).
        const hif::io::PcdCloud back = hif::io::readPcd(files[1]);
        EXPECT_NEAR(back.point(pts.size() - 1).x(), 1.0, 1e-4);
        EXPECT_NEAR(back.point(0).y(), -2.5, 1e-4);
    }
    // Below the limit nothing changes: float32, as before.
    hif::io::CloudWriter w({d + "/small.pcd"});
    w.add(8191.0, -8191.0, 100.0, 1.0f);
    w.close();
    EXPECT_FALSE(w.doubleCoordinates());
    std::ifstream small(d + "/small.pcd");
    const std::string text((std::istreambuf_iterator<char>(small)), {});
    EXPECT_NE(text.find("SIZE 4 4 4 4"), std::string::npos);
}

TEST(Rings, RecoveredFromThePointOrderWithoutJitterAtTheSeam)
{
    // Three turns swept clockwise from +170 degrees, 0.5 degree a point: each crosses the seam
    // at +-180 degrees once (at its 700th point), where a point jitters back across it.
    hif::io::Cloud c;
    const auto add = [&c](double az_deg, float z)
    {
        c.x.push_back(float(10 * std::cos(az_deg * M_PI / 180.0)));
        c.y.push_back(float(10 * std::sin(az_deg * M_PI / 180.0)));
        c.z.push_back(z);
        c.intensity.push_back(0);
    };
    for (int turn = 0; turn < 3; ++turn)
        for (int k = 0; k < 720; ++k)
        {
            if (k == 100 && turn == 1)
            {
                add(0, 0);  // a point at the axis: no azimuth, it stays in its ring
                c.x.back() = c.y.back() = 0.0f;
            }
            if (k == 702)
                add(-179.9, float(turn));  // back across the seam, once
            else
                add(170.0 - 0.5 * k, float(turn));
        }
    const auto got = hif::io::ringOfEachPoint(c);
    ASSERT_EQ(got.size(), c.size());
    std::vector<std::size_t> changes;
    for (std::size_t i = 1; i < got.size(); ++i)
        if (got[i] != got[i - 1]) changes.push_back(i);
    // One new ring per crossing of the seam: after points 700, 720 + 1 + 700 and 1440 + 1 + 700
    // (the axis point is in turn 1), whatever the jitter.
    EXPECT_EQ(changes, (std::vector<std::size_t>{701, 1422, 2142}));
    EXPECT_EQ(got.back(), 3u);
}

TEST(Rings, KittiScansHoldSixtyFourRings)
{
    const std::string seq = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(seq);
    const hif::io::KittiSequence s(seq);
    for (std::size_t i = 0; i < s.size(); i += 3)
    {
        const auto rings = hif::io::ringOfEachPoint(s.readScan(i));
        // 64 lasers; the scan starts mid-ring, which splits one in two.
        EXPECT_EQ(rings.back() + 1, 65u) << "scan " << i;
        EXPECT_TRUE(std::is_sorted(rings.begin(), rings.end()));
    }
}
