// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScansWithPosesSource.cpp
 * @brief  Scans as LiDAR SLAM systems write them: a folder of per-scan clouds in the sensor
 *         frame (NNNNNN.pcd, .ply or KITTI's .bin) and a trajectory file (KITTI or TUM format) with
 * the sensor's pose in the world for each; or clouds named by their time (a bag exported cloud by
 * cloud) with a TUM trajectory, posed by time.
 */
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <limits>
#include <optional>
#include <stdexcept>

#include "NumberedFiles.h"
#include "hif/apps/ScanSource.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Trajectory.h"

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
/** The clouds a folder with a trajectory holds: PCD, PLY, or KITTI's .bin (float32 x y z
 *  intensity, as KISS-ICP and other odometry pipelines read them). */
const std::vector<std::string> kCloudExtensions{".pcd", ".ply", ".bin"};

io::PcdCloud readCloud(const std::string& file)
{
    const std::string ext = fs::path(file).extension().string();
    if (ext == ".pcd") return io::readPcd(file);
    if (ext == ".ply") return io::readPly(file);
    io::PcdCloud cloud;
    static_cast<io::Cloud&>(cloud) = io::readKittiBin(file);
    return cloud;
}

class ScansWithPosesSource : public ScanSource
{
public:
    ScansWithPosesSource(const std::string& folder, const std::string& poses_file,
                         const FolderPoses& poses)
        : extrinsic_(poses.extrinsic), world_frame_(poses.world_frame)
    {
        // Read here: the scans keep their poses (entries_), not the trajectory.
        const io::Trajectory trajectory = io::readTrajectory(poses_file);
        NumberedFiles found = numberedFiles(folder, kCloudExtensions);
        // The trajectory file may be in the folder: it is not a stray file.
        std::error_code ec;
        found.other.erase(
            std::remove_if(found.other.begin(), found.other.end(),
                           [&](const std::string& name)
                           { return fs::equivalent(fs::path(folder) / name, poses_file, ec); }),
            found.other.end());
        // One kind of cloud: .pcd, .ply and .bin beside each other leave which are the scans
        // open.
        const auto oneKind = [&](const auto& files)
        {
            const fs::path first = files.front().second;
            for (const auto& f : files)
                if (fs::path(f.second).extension() != first.extension())
                    throw std::runtime_error(
                        "'" + folder + "' holds scans of two kinds (" + first.filename().string() +
                        ", " + fs::path(f.second).filename().string() + "): which are the scans?");
        };
        if (!found.files.empty())
        {
            oneKind(found.files);
            byNumber(folder, poses_file, trajectory, found.files);
        }
        else
        {
            // Clouds named by their time (a bag exported with pcl_ros's bag_to_pcd), posed by
            // the trajectory's times.
            const TimedFiles timed = timedFiles(folder, kCloudExtensions);
            if (timed.files.empty())
                throw std::runtime_error(
                    "'" + folder +
                    "' has no scan (clouds named by their number, NNNNNN.pcd, .ply or .bin, or "
                    "by their time, 1317022176.580342102.pcd)" +
                    (found.other.empty() ? "" : "; it holds " + listNames(found.other)));
            oneKind(timed.files);
            byTime(folder, poses_file, trajectory, timed.files);
            if (timed.nanoseconds_unpadded)
            {
                char at[40];
                std::snprintf(at, sizeof at, "%.9f s", timed.files.front().first);
                warnings_.push_back(
                    "the clouds of '" + folder +
                    "' are named <seconds>.<nanoseconds> without the nanoseconds' leading zeros "
                    "(ROS 2's pointcloud_to_pcd), and read so: " +
                    fs::path(timed.files.front().second).filename().string() + " is at " + at);
            }
            std::vector<std::string> timed_names;
            for (const auto& [time, file] : timed.files)
                timed_names.push_back(fs::path(file).filename().string());
            std::sort(timed_names.begin(), timed_names.end());
            std::vector<std::string> rest;
            std::set_difference(found.other.begin(), found.other.end(), timed_names.begin(),
                                timed_names.end(), std::back_inserter(rest));
            found.other = std::move(rest);
        }
        if (!found.other.empty())
            warnings_.push_back("'" + folder + "' holds " + std::to_string(found.other.size()) +
                                " file(s) not named as scans (NNNNNN.pcd, .ply or .bin, or by "
                                "their time), left out: " +
                                listNames(found.other));
    }

    bool next(Scan& out) override
    {
        if (pos_ >= entries_.size()) return false;
        const Entry& e = entries_[pos_++];
        io::PcdCloud cloud = readCloud(e.file);
        if (cloud.has_viewpoint && !cloud.viewpoint.isApprox(Eigen::Isometry3d::Identity()))
            throw std::runtime_error(
                "'" + e.file +
                "' has a VIEWPOINT other than the identity: its points may be in the world "
                "frame (a DynamicMap scan, read from a folder with pcd/), but a folder with "
                "poses holds clouds in the sensor frame");
        // A point at the sensor's origin exactly is no return (an organized cloud's place
        // holder: Ouster's and Hesai's drivers write 0 0 0 there): read as an invalid point,
        // still labelled, not written to the clouds.
        if (!world_frame_)
            for (std::size_t i = 0; i < cloud.size(); ++i)
                if (cloud.point(i).isZero(0.0))
                    cloud.x[i] = cloud.y[i] = cloud.z[i] = std::numeric_limits<float>::quiet_NaN();
        if (world_frame_)
        {
            // Registered points: into the sensor's frame (in double, a wide file's origin
            // included), where the map takes them from, at this pose.
            cloud.viewpoint = e.pose;
            io::toViewpointFrame(cloud);
        }
        else
            io::absorbOrigin(cloud);
        out.obs = pointCloudObservation(cloud);
        if (e.time) out.obs->timestamp = mrpt::Clock::fromDouble(*e.time);
        out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(e.pose.matrix());
        out.frame = e.frame;
        out.name = e.name;
        out.has_pose = true;
        return true;
    }

    void rewind() override { pos_ = 0; }
    [[nodiscard]] std::size_t knownSize() const override { return entries_.size(); }
    [[nodiscard]] std::vector<std::string> warnings() const override { return warnings_; }

private:
    /** A scan: its cloud, pose and time (when the trajectory has times), its number, and the
     *  name of its outputs when it is not that number's. */
    struct Entry
    {
        std::size_t frame;
        std::string file;
        Eigen::Isometry3d pose;
        std::optional<double> time;
        std::optional<std::string> name;
    };

    /** The LiDAR's pose for the trajectory's `pose`. */
    [[nodiscard]] Eigen::Isometry3d lidarPose(const Eigen::Isometry3d& pose) const
    {
        return extrinsic_ ? pose * *extrinsic_ : pose;
    }

    /** Clouds named by their number: one pose a scan, in order; a trajectory longer than the
     *  folder (scans left out, as KITTI's poses.txt for a part of a sequence) is read by the
     *  scans' numbers. */
    void byNumber(const std::string& folder, const std::string& poses_file,
                  const io::Trajectory& trajectory,
                  const std::vector<std::pair<std::size_t, std::string>>& files)
    {
        const bool by_number = trajectory.size() != files.size();
        const std::size_t n = trajectory.size();
        if (by_number)
        {
            if (n < files.size())
                throw std::runtime_error("'" + poses_file + "' has " + std::to_string(n) +
                                         " poses for the " + std::to_string(files.size()) +
                                         " scans of '" + folder +
                                         "' (one pose a scan, in the order of their numbers)");
            for (const auto& [number, file] : files)
                if (number >= n)
                    throw std::runtime_error("'" + poses_file + "' has " + std::to_string(n) +
                                             " poses for the " + std::to_string(files.size()) +
                                             " scans of '" + folder + "', and none for " +
                                             fs::path(file).filename().string() +
                                             " (pose lines are read by the scan's "
                                             "number when there are more poses than scans)");
            warnings_.push_back("'" + poses_file + "' has " + std::to_string(n) + " poses for " +
                                std::to_string(files.size()) +
                                " scans: scan NNNNNN takes pose line NNNNNN+1");
        }
        for (std::size_t k = 0; k < files.size(); ++k)
        {
            const auto& [number, file] = files[k];
            const std::size_t row = by_number ? number : k;
            std::optional<double> time;
            if (!trajectory.times.empty()) time = trajectory.times[row];
            entries_.push_back(
                {number, file, lidarPose(trajectory.poses[row]), time, std::nullopt});
        }
    }

    /** Clouds named by their time: each takes the trajectory's pose at that time (io::poseAt():
     *  the pose of that time, else interpolated between the two around it when they are at most
     *  twice the trajectory's median spacing apart: a gap in it is not bridged). Its outputs
     *  take its name; those without a pose are left out, and named. */
    void byTime(const std::string& folder, const std::string& poses_file,
                const io::Trajectory& trajectory,
                const std::vector<std::pair<double, std::string>>& files)
    {
        const std::string first = fs::path(files.front().second).filename().string();
        if (trajectory.times.empty())
            throw std::runtime_error("'" + folder + "' holds clouds named by their time (" + first +
                                     "), which need a trajectory with times, the TUM format "
                                     "(time x y z qx qy qz qw), but '" +
                                     poses_file + "' is in the KITTI format");
        const double spacing = io::medianSpacing(trajectory);
        std::vector<std::string> left_out;
        for (const auto& [time, file] : files)
        {
            const auto pose = io::poseAt(trajectory, time, 2.0 * spacing);
            if (!pose)
            {
                left_out.push_back(fs::path(file).filename().string());
                continue;
            }
            entries_.push_back(
                {entries_.size(), file, lidarPose(*pose), time, fs::path(file).stem().string()});
        }
        char clouds[96];
        std::snprintf(clouds, sizeof clouds, ", the clouds' from %.6f to %.6f s",
                      files.front().first, files.back().first);
        const std::string span = io::describeTimes(trajectory) + clouds;
        if (entries_.empty())
            throw std::runtime_error("none of the " + std::to_string(files.size()) +
                                     " clouds of '" + folder + "' has a pose in '" + poses_file +
                                     "': " + span);
        if (!left_out.empty())
            warnings_.push_back(std::to_string(left_out.size()) + " of the " +
                                std::to_string(files.size()) + " clouds of '" + folder +
                                "' have no pose in '" + poses_file +
                                "' (before its first pose, after its last, or in a gap of more "
                                "than twice its spacing; " +
                                span + "), left out: " + listNames(left_out));
    }

    /** FolderPoses::extrinsic: each scan at pose x extrinsic, after any interpolation of the
     *  trajectory's pose (lidarPose()). */
    std::optional<Eigen::Isometry3d> extrinsic_;
    bool world_frame_ = false;  ///< FolderPoses::world_frame
    std::vector<Entry> entries_;
    std::vector<std::string> warnings_;
    std::size_t pos_ = 0;  ///< next entry
};
}  // namespace

std::unique_ptr<ScanSource> openScansWithPoses(const std::string& folder,
                                               const std::string& poses_file,
                                               const FolderPoses& poses)
{
    return std::make_unique<ScansWithPosesSource>(folder, poses_file, poses);
}

}  // namespace hif::apps
