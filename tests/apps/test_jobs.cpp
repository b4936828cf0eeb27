// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_jobs.cpp
 * @brief  The apps' jobs run in process (no program started): kitti2rawlog's conversion of
 *         real KITTI scans, what it writes and what it refuses.
 */
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/serialization/CArchive.h>

#include <filesystem>
#include <sstream>

#include "hif/io/KittiSequence.h"
#include "hif/jobs/KittiToRawlog.h"
#include "kitti_fixture.h"
#include "work_dir.h"

namespace
{
/** The message of what `f` throws ("" if nothing). */
template <typename F>
std::string thrown(F&& f)
{
    try
    {
        f();
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return "";
}
}  // namespace

TEST(Jobs, KittiToRawlogConvertsAPartOfASequenceInProcess)
{
    const std::string seq_dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(seq_dir);
    const hif::test::WorkDir dir("jobs_kitti2rawlog");
    const hif::io::KittiSequence seq(seq_dir);

    hif::jobs::KittiToRawlogOptions o;
    o.input = seq_dir;
    o.output = dir.path() + "/part.rawlog";
    o.first = 2;
    o.last = 4;
    o.odometry = true;
    o.show_progress = false;
    std::ostringstream log;
    const hif::jobs::KittiToRawlogResult r = hif::jobs::KittiToRawlog(o).run(log);
    EXPECT_EQ(r.scans, 3u);
    EXPECT_EQ(r.points, seq.pointCount(2) + seq.pointCount(3) + seq.pointCount(4));
    EXPECT_EQ(r.labelled, 3u);
    EXPECT_NE(log.str().find("done: 3 scans"), std::string::npos) << log.str();

    // Per scan: its frame comment, its pose as odometry, its pose, its points.
    mrpt::io::CFileGZInputStream in(o.output);
    auto arch = mrpt::serialization::archiveFrom(in);
    for (std::size_t i = 2; i <= 4; ++i)
    {
        const auto comment =
            std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(arch.ReadObject());
        ASSERT_TRUE(comment);
        EXPECT_EQ(comment->text, "kitti frame " + std::to_string(i));
        EXPECT_TRUE(std::dynamic_pointer_cast<mrpt::obs::CObservationOdometry>(arch.ReadObject()));
        const auto pose =
            std::dynamic_pointer_cast<mrpt::obs::CObservationRobotPose>(arch.ReadObject());
        ASSERT_TRUE(pose);
        EXPECT_NEAR(pose->pose.mean.x(), seq.pose(i).translation().x(), 1e-9);
        const auto scan =
            std::dynamic_pointer_cast<mrpt::obs::CObservationPointCloud>(arch.ReadObject());
        ASSERT_TRUE(scan && scan->pointcloud);
        EXPECT_EQ(scan->pointcloud->size(), seq.pointCount(i));
    }

    // What it refuses, before writing anything, with the flag named.
    const auto refused = [&](hif::jobs::KittiToRawlogOptions bad)
    {
        bad.output = dir.path() + "/refused.rawlog";
        const std::string m = thrown([&] { (void)hif::jobs::KittiToRawlog(bad).run(log); });
        EXPECT_FALSE(std::filesystem::exists(bad.output)) << m;
        return m;
    };
    auto bad = o;
    bad.first = 5;
    EXPECT_EQ(refused(bad), "--first 5 is after --last 4");
    bad = o;
    bad.compress_level = 12;
    EXPECT_EQ(refused(bad), "--compress-level 12 is not in 0-9");
    bad = o;
    bad.dynamicmap = true;
    EXPECT_NE(refused(bad).find("apply to rawlogs, not to --dynamicmap"), std::string::npos);
    // The rawlog written is not replaced unless asked.
    EXPECT_NE(thrown([&] { (void)hif::jobs::KittiToRawlog(o).run(log); }).find("already exists"),
              std::string::npos);
    o.overwrite = true;
    EXPECT_EQ(hif::jobs::KittiToRawlog(o).run(log).scans, 3u);
}
