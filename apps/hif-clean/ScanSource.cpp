// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanSource.cpp
 * @brief  Which source reads a path, and the scans of a sensory frame.
 */
#include "ScanSource.h"

#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace hif::apps
{
bool isScan(const mrpt::obs::CObservation& obs)
{
    using namespace mrpt::obs;
    return IS_CLASS(obs, CObservationPointCloud) || IS_CLASS(obs, CObservation3DRangeScan) ||
           IS_CLASS(obs, CObservation2DRangeScan) || IS_CLASS(obs, CObservationVelodyneScan);
}

namespace
{
std::unique_ptr<ScanSource> openSource(const std::string& path, bool poses_required)
{
    if (fs::is_directory(path))
    {
        if (fs::is_directory(fs::path(path) / "velodyne")) return openKittiFolder(path);
        if (fs::is_directory(fs::path(path) / "pcd")) return openDynamicMapFolder(path);
        throw std::runtime_error("'" + path +
                                 "' is a folder with neither velodyne/ (a KITTI sequence) nor "
                                 "pcd/ (a DynamicMap benchmark folder); hif-clean reads those, "
                                 "a rawlog or a .simplemap");
    }
    if (!fs::exists(path)) throw std::runtime_error("input '" + path + "' does not exist");
    if (fs::path(path).extension() == ".simplemap") return openSimpleMap(path);
    return openRawlog(path, poses_required);
}
}  // namespace

std::unique_ptr<ScanSource> openScanSource(const std::string& path, PrepareScan prepare,
                                           bool poses_required)
{
    return readingAhead(openSource(path, poses_required), std::move(prepare));
}

mrpt::obs::CObservation::Ptr pointCloudObservation(const io::Cloud& cloud)
{
    auto points = mrpt::maps::CPointsMapXYZI::Create();
    points->resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
    {
        points->setPointFast(i, cloud.x[i], cloud.y[i], cloud.z[i]);
        points->setPointIntensity(i, cloud.intensity[i]);
    }
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    obs->sensorLabel = "LIDAR";
    obs->pointcloud = points;
    return obs;
}

void FrameScans::assign(const mrpt::obs::CSensoryFrame& frame, const mrpt::poses::CPose3D& pose,
                        bool has_pose)
{
    has_pose_ = has_pose;
    pending_.assign(frame.begin(), frame.end());
    std::reverse(pending_.begin(), pending_.end());
    pose_ = pose;
}

bool FrameScans::next(Scan& out)
{
    while (!pending_.empty())
    {
        auto obs = pending_.back();
        pending_.pop_back();
        if (!obs) continue;
        if (isScan(*obs))
        {
            out = {obs, pose_, std::nullopt, std::nullopt, has_pose_};
            return true;
        }
        if (IS_CLASS(*obs, mrpt::obs::CObservationRobotPose))
        {
            pose_ = dynamic_cast<const mrpt::obs::CObservationRobotPose&>(*obs).pose.mean;
            has_pose_ = true;
        }
    }
    return false;
}

}  // namespace hif::apps
