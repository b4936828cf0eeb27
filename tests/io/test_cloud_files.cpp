// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_cloud_files.cpp
 * @brief  CloudWriter: every way of writing the body (straight into the first file when the
 *         expected count has the right number of digits, moved when it has not, through a
 *         .part file without an expectation) gives the same files, header and body, as a
 *         reference written in one go; readPcd reads them back.
 */
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "hif/io/CloudFiles.h"
#include "work_dir.h"

namespace fs = std::filesystem;

namespace
{
std::string bytesOf(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

/** The reference: the header as the formats define it, then the points, float32 each. */
std::string reference(const std::string& ext, const std::vector<float>& xyzi,
                      const std::string& viewpoint)
{
    const std::string n = std::to_string(xyzi.size() / 4);
    std::string h =
        ext == ".ply"
            ? "ply\nformat binary_little_endian 1.0\ncomment written by hif\nelement vertex " + n +
                  "\nproperty float x\nproperty float y\nproperty float z\nproperty float "
                  "intensity\nend_header\n"
            : "# .PCD v0.7 - Point Cloud Data file format (written by hif)\nVERSION 0.7\nFIELDS "
              "x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " +
                  n + "\nHEIGHT 1\nVIEWPOINT " + viewpoint + "\nPOINTS " + n + "\nDATA binary\n";
    return h + std::string(reinterpret_cast<const char*>(xyzi.data()), xyzi.size() * 4);
}

std::string freshDir(const hif::test::WorkDir& work, const std::string& name)
{
    const fs::path d = fs::path(work.path()) / name;
    fs::remove_all(d);
    fs::create_directories(d);
    return d.string();
}
}  // namespace

TEST(CloudWriter, EveryWayOfWritingTheBodyGivesTheReferenceFiles)
{
    const Eigen::Isometry3d pose =
        Eigen::Translation3d(1.5, -2.25, 0.5) * Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ());
    const auto work = hif::test::tempWorkDir("cloud");
    // Counts, and the expectation given before the first point: none; exact; same number of
    // digits; fewer and more digits than the count (the body moved behind the right header).
    const std::vector<std::pair<std::size_t, std::optional<std::size_t>>> cases = {
        {0, std::nullopt}, {0, 0},    {7, std::nullopt}, {7, 7},     {57, 99},
        {57, 5},           {57, 570}, {1234, 1000},      {1234, 99}, {1234, 123456}};
    for (const auto& [count, expected] : cases)
        for (const bool viewpoint : {false, true})
        {
            SCOPED_TRACE("count " + std::to_string(count) + ", expected " +
                         (expected ? std::to_string(*expected) : "none") +
                         (viewpoint ? ", viewpoint" : ""));
            const std::string d = freshDir(work, "c" + std::to_string(count));
            const std::vector<std::string> files{d + "/a.pcd", d + "/b.ply", d + "/c.pcd"};
            std::vector<float> xyzi;
            {
                hif::io::CloudWriter w(files);
                if (viewpoint) w.setViewpoint(pose);
                if (expected) w.expectCount(*expected);
                for (std::size_t i = 0; i < count; ++i)
                {
                    const float v[4] = {0.5f * float(i), -1.25f * float(i), 3.0f + float(i % 7),
                                        float(i % 256)};
                    w.add(v[0], v[1], v[2], v[3]);
                    xyzi.insert(xyzi.end(), v, v + 4);
                }
                w.close();
                EXPECT_EQ(w.count(), count);
            }
            std::ostringstream vp;
            if (viewpoint)
            {
                const Eigen::Quaterniond q(pose.linear());
                vp << std::setprecision(17) << pose.translation().x() << ' '
                   << pose.translation().y() << ' ' << pose.translation().z() << ' ' << q.w() << ' '
                   << q.x() << ' ' << q.y() << ' ' << q.z();
            }
            else
                vp << "0 0 0 1 0 0 0";
            for (const std::string& f : files)
                EXPECT_EQ(bytesOf(f), reference(fs::path(f).extension().string(), xyzi, vp.str()))
                    << f;
            // Nothing else is left in the folder.
            EXPECT_EQ(std::distance(fs::directory_iterator(d), fs::directory_iterator{}), 3);
            const hif::io::PcdCloud back = hif::io::readPcd(files[0]);
            ASSERT_EQ(back.size(), count);
            if (count > 5)
            {
                EXPECT_EQ(back.y[5], xyzi[5 * 4 + 1]);
            }
            EXPECT_TRUE(
                back.viewpoint.isApprox(viewpoint ? pose : Eigen::Isometry3d::Identity(), 1e-12));
        }
}

TEST(CloudWriter, AnUnfinishedWriterLeavesNoFileAndExpectsOnlyBeforeThePoints)
{
    const auto work = hif::test::tempWorkDir("cloud");
    const std::string d = freshDir(work, "unfinished");
    for (const bool expect : {false, true})
    {
        {
            hif::io::CloudWriter w({d + "/a.ply", d + "/b.pcd"});
            if (expect) w.expectCount(10);
            w.add(1, 2, 3, 4);
            EXPECT_THROW(w.expectCount(10), std::logic_error);
        }  // destroyed without close(): an error elsewhere stopped the run
        EXPECT_TRUE(fs::is_empty(d)) << (expect ? "with" : "without") << " an expectation";
    }
    EXPECT_THROW(hif::io::CloudWriter({d + "/a.las"}), std::runtime_error);
}

TEST(CloudWriter, ColouredPointsMakeAColouredPly)
{
    const auto work = hif::test::tempWorkDir("cloud");
    const std::string d = freshDir(work, "coloured");
    for (const std::optional<std::size_t> expected : {std::optional<std::size_t>{}, {3}, {40}})
    {
        const std::vector<std::string> files{d + "/a.ply", d + "/b.ply"};
        {
            hif::io::CloudWriter w(files, hif::io::PointFields::colourOnly());
            if (expected) w.expectCount(*expected);
            w.add(1.5f, -2.0f, 0.25f, 255, 0, 7);
            w.add(0.0f, 3.0f, -1.0f, 1, 2, 3);
            w.add(9.0f, 9.0f, 9.0f, 200, 200, 200);
            w.close();
        }
        std::string body;
        const auto point = [&body](float x, float y, float z, unsigned r, unsigned g, unsigned b)
        {
            const float xyz[3] = {x, y, z};
            body.append(reinterpret_cast<const char*>(xyz), 12);
            body += {char(r), char(g), char(b)};
        };
        point(1.5f, -2.0f, 0.25f, 255, 0, 7);
        point(0.0f, 3.0f, -1.0f, 1, 2, 3);
        point(9.0f, 9.0f, 9.0f, 200, 200, 200);
        const std::string ref =
            "ply\nformat binary_little_endian 1.0\ncomment written by hif\nelement vertex 3\n"
            "property float x\nproperty float y\nproperty float z\nproperty uchar red\nproperty "
            "uchar green\nproperty uchar blue\nend_header\n" +
            body;
        for (const std::string& f : files) EXPECT_EQ(bytesOf(f), ref) << f;
    }
    EXPECT_THROW(hif::io::CloudWriter({d + "/c.pcd"}, hif::io::PointFields::colourOnly()),
                 std::runtime_error);
}
