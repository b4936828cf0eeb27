// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScansWithPosesSource.cpp
 * @brief  Scans as LiDAR SLAM systems write them: a folder of per-scan clouds in the sensor
 *         frame (NNNNNN.pcd or NNNNNN.ply) and a trajectory file (KITTI or TUM format) with the
 *         sensor's pose in the world for each.
 */
#include <algorithm>
#include <filesystem>
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
class ScansWithPosesSource : public ScanSource
{
public:
    ScansWithPosesSource(const std::string& folder, const std::string& poses_file)
        : poses_file_(poses_file), trajectory_(io::readTrajectory(poses_file))
    {
        NumberedFiles found = numberedFiles(folder, {".pcd", ".ply"});
        // The trajectory file may be in the folder: it is not a stray file.
        std::error_code ec;
        found.other.erase(
            std::remove_if(found.other.begin(), found.other.end(),
                           [&](const std::string& name)
                           { return fs::equivalent(fs::path(folder) / name, poses_file, ec); }),
            found.other.end());
        if (found.files.empty())
            throw std::runtime_error(
                "'" + folder +
                "' has no scan (clouds named by their number: NNNNNN.pcd or NNNNNN.ply)" +
                (found.other.empty() ? "" : "; it holds " + listNames(found.other)));
        files_ = std::move(found.files);
        for (const auto& [number, file] : files_)
            if (fs::path(file).extension() != fs::path(files_.front().second).extension())
                throw std::runtime_error("'" + folder + "' holds both .pcd and .ply scans (" +
                                         fs::path(files_.front().second).filename().string() +
                                         ", " + fs::path(file).filename().string() +
                                         "): which are the scans?");
        // One pose a scan, in order; a trajectory longer than the folder (scans left out, as
        // KITTI's poses.txt for a part of a sequence) is read by the scans' numbers.
        by_number_ = trajectory_.size() != files_.size();
        const std::size_t n = trajectory_.size();
        if (by_number_)
        {
            if (n < files_.size())
                throw std::runtime_error("'" + poses_file + "' has " + std::to_string(n) +
                                         " poses for the " + std::to_string(files_.size()) +
                                         " scans of '" + folder +
                                         "' (one pose a scan, in the order of their numbers)");
            for (const auto& [number, file] : files_)
                if (number >= n)
                    throw std::runtime_error("'" + poses_file + "' has " + std::to_string(n) +
                                             " poses for the " + std::to_string(files_.size()) +
                                             " scans of '" + folder + "', and none for " +
                                             fs::path(file).filename().string() +
                                             " (pose lines are read by the scan's "
                                             "number when there are more poses than scans)");
            warnings_.push_back("'" + poses_file + "' has " + std::to_string(n) + " poses for " +
                                std::to_string(files_.size()) +
                                " scans: scan NNNNNN takes pose line NNNNNN+1");
        }
        if (!found.other.empty())
            warnings_.push_back(
                "'" + folder + "' holds " + std::to_string(found.other.size()) +
                " file(s) not named as scans (NNNNNN.pcd or NNNNNN.ply), left out: " +
                listNames(found.other));
    }

    bool next(Scan& out) override
    {
        if (pos_ >= files_.size()) return false;
        const std::size_t k = pos_++;
        const auto& [number, file] = files_[k];
        io::PcdCloud cloud =
            fs::path(file).extension() == ".pcd" ? io::readPcd(file) : io::readPly(file);
        if (cloud.has_viewpoint && !cloud.viewpoint.isApprox(Eigen::Isometry3d::Identity()))
            throw std::runtime_error(
                "'" + file +
                "' has a VIEWPOINT other than the identity: its points may be in the world "
                "frame (a DynamicMap scan, read from a folder with pcd/), but a folder with "
                "poses holds clouds in the sensor frame");
        if (!cloud.origin.isZero(0.0))
            for (std::size_t i = 0; i < cloud.size(); ++i)
            {
                const Eigen::Vector3d p = cloud.point(i);
                cloud.x[i] = static_cast<float>(p.x());
                cloud.y[i] = static_cast<float>(p.y());
                cloud.z[i] = static_cast<float>(p.z());
            }
        const std::size_t row = by_number_ ? number : k;
        out.obs = pointCloudObservation(cloud);
        if (!trajectory_.times.empty())
            out.obs->timestamp = mrpt::Clock::fromDouble(trajectory_.times[row]);
        out.robot_pose =
            mrpt::poses::CPose3D::FromHomogeneousMatrix(trajectory_.poses[row].matrix());
        out.frame = number;
        out.has_pose = true;
        return true;
    }

    void rewind() override { pos_ = 0; }
    [[nodiscard]] std::size_t knownSize() const override { return files_.size(); }
    [[nodiscard]] std::vector<std::string> warnings() const override { return warnings_; }

private:
    std::string poses_file_;
    io::Trajectory trajectory_;
    std::vector<std::pair<std::size_t, std::string>> files_;
    bool by_number_ = false;  ///< scan NNNNNN takes pose line NNNNNN (else the k-th scan the k-th)
    std::vector<std::string> warnings_;
    std::size_t pos_ = 0;  ///< next file
};
}  // namespace

std::unique_ptr<ScanSource> openScansWithPoses(const std::string& folder,
                                               const std::string& poses_file)
{
    return std::make_unique<ScansWithPosesSource>(folder, poses_file);
}

}  // namespace hif::apps
