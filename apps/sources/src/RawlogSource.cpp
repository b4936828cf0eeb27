// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RawlogSource.cpp
 * @brief  Scans of an MRPT rawlog: observations, each scan after its CObservationRobotPose, or
 *         sensory frames; or, for a rawlog without poses (as MRPT's rosbag2rawlog writes one
 *         from a ROS bag), each scan at the pose a trajectory file gives for it.
 */
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <atomic>
#include <stdexcept>

#include "hif/apps/Cli.h"
#include "hif/apps/FrameComment.h"
#include "hif/apps/ScanSource.h"
#include "hif/io/Trajectory.h"

namespace hif::apps
{
namespace
{
class RawlogSource : public ScanSource
{
public:
    RawlogSource(std::string file, bool poses_required, const FolderPoses& poses = {})
        : file_(std::move(file)), poses_required_(poses_required)
    {
        if (!poses.trajectory.empty())
        {
            trajectory_file_ = poses.trajectory;
            trajectory_ = io::readTrajectory(poses.trajectory);
            extrinsic_ = poses.extrinsic;
            max_gap_ = 2.0 * io::medianSpacing(trajectory_);  // as for clouds named by time
        }
        open();
    }

    bool next(Scan& out) override
    {
        using namespace mrpt::obs;
        while (frame_scans_.next(out))
            if (placed(out)) return counted(true, out);
        auto arch = mrpt::serialization::archiveFrom(*in_);
        for (;;)
        {
            mrpt::serialization::CSerializable::Ptr obj;
            try
            {
                obj = arch.ReadObject();
            }
            catch (const mrpt::serialization::CExceptionEOF&)
            {
                if (scans_read_ == 0 && left_out_ > 0)
                    throw std::runtime_error("none of the scans has a pose: " + leftOutScans().why);
                return false;
            }
            catch (const std::exception& e)
            {
                throw std::runtime_error("rawlog '" + file_ + "' is corrupt or truncated after " +
                                         std::to_string(scans_read_) +
                                         " scans: " + innermostMessage(e.what()));
            }
            if (auto comment = std::dynamic_pointer_cast<CObservationComment>(obj))
            {
                if (const auto f = parseKittiFrameComment(comment->text))
                {
                    frame_ = f;
                    continue;
                }
            }
            // Odometry (as kitti2rawlog --odometry writes the trajectory for MRPT's viewers) is
            // not a pose of the scans here: they are placed at their CObservationRobotPose.
            if (obj && IS_CLASS(*obj, CObservationOdometry)) continue;
            if (auto rp = std::dynamic_pointer_cast<CObservationRobotPose>(obj))
            {
                if (!trajectory_file_.empty()) throwOwnPoses();
                pose_ = rp->pose.mean;
                have_pose_ = true;
                continue;
            }
            if (auto sf = std::dynamic_pointer_cast<CSensoryFrame>(obj))
            {
                // A pose inside the frame places the scans after it.
                const auto first_scan = std::find_if(sf->begin(), sf->end(),
                                                     [](const auto& o) { return o && isScan(*o); });
                const auto first_pose = std::find_if(
                    sf->begin(), sf->end(),
                    [](const auto& o) { return o && IS_CLASS(*o, CObservationRobotPose); });
                if (!trajectory_file_.empty() && first_pose != sf->end()) throwOwnPoses();
                if (first_scan != sf->end() && !have_pose_ && first_pose > first_scan &&
                    poses_required_ && trajectory_file_.empty())
                    throwNoPose();
                frame_scans_.assign(*sf, have_pose_ ? pose_ : mrpt::poses::CPose3D(), have_pose_);
                have_pose_ = false;
                while (frame_scans_.next(out))
                    if (placed(out)) return counted(true, out);
                continue;
            }
            auto obs = std::dynamic_pointer_cast<CObservation>(obj);
            if (!obs || !isScan(*obs))
            {
                ++skipped_;
                continue;
            }
            if (!have_pose_ && poses_required_ && trajectory_file_.empty()) throwNoPose();
            out = {obs, have_pose_ ? pose_ : mrpt::poses::CPose3D(), frame_, have_pose_,
                   std::nullopt};
            have_pose_ = false;  // every scan needs its own pose: never reuse a stale one
            frame_.reset();      // and its own number
            if (placed(out)) return counted(true, out);
        }
    }

    void rewind() override
    {
        frame_scans_.clear();
        frame_.reset();
        have_pose_ = false;
        scans_read_ = 0;
        scans_seen_ = 0;
        skipped_ = 0;
        left_out_ = 0;
        open();
    }

    [[nodiscard]] std::size_t skippedObjects() const override { return skipped_; }

    [[nodiscard]] LeftOut leftOutScans() const override
    {
        const std::size_t n = left_out_.load();
        if (n == 0) return {};
        return {n, std::to_string(n) + " of the " + std::to_string(scans_seen_.load()) +
                       " scans of rawlog '" + file_ + "' have no pose in '" + trajectory_file_ +
                       "' (taken before its first pose, after its last, or in a gap of more "
                       "than twice its spacing; " +
                       io::describeTimes(trajectory_) + "): left out, without predictions"};
    }

private:
    void open()
    {
        in_ = std::make_unique<mrpt::io::CFileGZInputStream>();
        if (!in_->open(file_)) throw std::runtime_error("cannot open rawlog '" + file_ + "'");
    }
    /** A scan handed out: counted, and its external points checked. */
    bool counted(bool got, const Scan& out)
    {
        if (got)
            checkExternalPoints(*out.obs,
                                "rawlog '" + file_ + "', scan " + std::to_string(scans_read_));
        scans_read_ += got ? 1 : 0;
        return got;
    }
    /** With a trajectory, places scan `out` (the scans_seen_-th of the rawlog, from 0) at its
     *  pose: that of its time (TUM format; io::poseAt(), interpolated within twice the
     *  trajectory's median spacing), or the scan's line (KITTI format), times the extrinsic, its
     *  number (for its outputs) its place in the rawlog. False for a scan whose time has no pose:
     *  left out, and counted. Without a trajectory, every scan as the rawlog places it. */
    bool placed(Scan& out)
    {
        const std::size_t k = scans_seen_++;
        if (trajectory_file_.empty()) return true;
        // One trajectory places one sensor: a second LiDAR's scans (another topic of the bag)
        // would be put where the first one was.
        if (k == 0) sensor_label_ = out.obs->sensorLabel;
        if (out.obs->sensorLabel != sensor_label_)
            throw std::runtime_error(
                "rawlog '" + file_ + "' holds scans of two sensors, '" + sensor_label_ + "' and '" +
                out.obs->sensorLabel + "' (scan " + std::to_string(k) +
                "), and the trajectory of --poses places one: convert one LiDAR's topic (for "
                "rosbag2rawlog, one sensor in its .yml)");
        std::optional<Eigen::Isometry3d> pose;
        if (trajectory_.times.empty())
        {
            if (k >= trajectory_.size())
                throw std::runtime_error(
                    "'" + trajectory_file_ + "' has " + std::to_string(trajectory_.size()) +
                    " poses, and rawlog '" + file_ + "' more scans: scan " + std::to_string(k) +
                    " has none (a trajectory in the KITTI format gives one pose a scan, in "
                    "order; with times, the TUM format, each scan takes the pose of its time)");
            pose = trajectory_.poses[k];
        }
        else
        {
            if (out.obs->timestamp == INVALID_TIMESTAMP)
                throw std::runtime_error("rawlog '" + file_ + "': scan " + std::to_string(k) +
                                         " has no time, which the poses of '" + trajectory_file_ +
                                         "' (TUM format: time x y z qx qy qz qw) are found by");
            pose = io::poseAt(trajectory_, mrpt::Clock::toDouble(out.obs->timestamp), max_gap_);
            if (!pose)
            {
                ++left_out_;
                return false;
            }
        }
        const Eigen::Isometry3d lidar = extrinsic_ ? *pose * *extrinsic_ : *pose;
        out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(lidar.matrix());
        out.has_pose = true;
        if (!out.frame) out.frame = k;
        return true;
    }
    [[noreturn]] void throwOwnPoses() const
    {
        throw std::runtime_error(
            "rawlog '" + file_ + "' holds its own poses (a CObservationRobotPose before scan " +
            std::to_string(scans_seen_.load()) + "); --poses places the scans of a rawlog " +
            "without them (as MRPT's rosbag2rawlog writes one): leave --poses out to use the " +
            "rawlog's");
    }
    [[noreturn]] void throwNoPose() const
    {
        throw std::runtime_error("rawlog '" + file_ + "': scan " + std::to_string(scans_read_) +
                                 " has no pose before it (hif-clean needs a "
                                 "CObservationRobotPose before each scan, as kitti2rawlog "
                                 "writes, or a .simplemap)");
    }

    std::string file_;
    bool poses_required_;
    std::unique_ptr<mrpt::io::CFileGZInputStream> in_;
    FrameScans frame_scans_;
    std::optional<std::size_t> frame_;  ///< from a "kitti frame N" comment, for the next scan
    mrpt::poses::CPose3D pose_;
    bool have_pose_ = false;
    std::size_t scans_read_ = 0;
    std::size_t skipped_ = 0;
    /** --poses: the trajectory the scans are placed at, instead of poses in the rawlog. */
    std::string trajectory_file_;
    io::Trajectory trajectory_;
    std::optional<Eigen::Isometry3d> extrinsic_;
    double max_gap_ = 0.0;
    std::string sensor_label_;  ///< of the first scan: every one must be that sensor's
    /** Scans of the rawlog met in this pass, and those left out for want of a pose (read on
     *  the caller's thread while the reader's may write them: atomic). */
    std::atomic<std::size_t> scans_seen_{0};
    std::atomic<std::size_t> left_out_{0};
};
}  // namespace

std::unique_ptr<ScanSource> openRawlog(const std::string& file, bool poses_required)
{
    return std::make_unique<RawlogSource>(file, poses_required);
}

std::unique_ptr<ScanSource> openRawlogWithPoses(const std::string& file, const FolderPoses& poses)
{
    return std::make_unique<RawlogSource>(file, true, poses);
}

}  // namespace hif::apps
