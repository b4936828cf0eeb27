// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanSource.cpp
 * @brief  Which source reads a path, and the scans of a sensory frame.
 */
#include "hif/apps/ScanSource.h"

#include <mrpt/io/lazy_load_path.h>
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
/** Which inputs hif-clean reads, for messages about the others. */
const char* const kInputsRead =
    "hif-clean reads a sequence of scans with their poses: a KITTI sequence folder "
    "(velodyne/), a DynamicMap benchmark folder (pcd/), a folder of clouds in the sensor frame "
    "(NNNNNN.pcd, .ply or .bin) with poses.txt (KITTI or TUM format; or --poses FILE), "
    "hdl_graph_slam's keyframes (NNNNNN/data and cloud.pcd), an MRPT rawlog (with --poses if "
    "it holds none) or a .simplemap";

/** The poses of a folder of clouds: `poses` when given, else its poses.txt; empty if neither. */
std::string posesOf(const fs::path& folder, const std::string& poses)
{
    if (!poses.empty()) return poses;
    return fs::is_regular_file(folder / "poses.txt") ? (folder / "poses.txt").string() : "";
}

std::unique_ptr<ScanSource> openSource(const std::string& path, bool poses_required,
                                       const FolderPoses& poses)
{
    const fs::path p(path);
    // The flag that gave a folder of clouds' poses, for inputs that hold their own.
    const char* flag = !poses.trajectory.empty() ? "--poses"
                       : poses.extrinsic         ? "--extrinsic"
                       : poses.world_frame       ? "--world-frame"
                                                 : "";
    if (fs::is_directory(p))
    {
        const bool kitti = fs::is_directory(p / "velodyne"),
                   dynamicmap = fs::is_directory(p / "pcd");
        const std::string trajectory = posesOf(p, poses.trajectory);
        const bool keyframes =
            !kitti && !dynamicmap && trajectory.empty() && isKeyframesFolder(path);
        if (*flag && (kitti || dynamicmap || keyframes))
            throw std::runtime_error(std::string(flag) + " is for a folder of clouds; '" + path +
                                     "' is a " +
                                     (kitti        ? "KITTI sequence"
                                      : dynamicmap ? "DynamicMap benchmark"
                                                   : "keyframe (hdl_graph_slam)") +
                                     " folder, which holds its own poses");
        if (kitti) return openKittiFolder(path);
        if (dynamicmap) return openDynamicMapFolder(path);
        if (keyframes) return openKeyframesFolder(path);
        if (!trajectory.empty()) return openScansWithPoses(path, trajectory, poses);
        throw std::runtime_error("'" + path +
                                 "' is a folder with neither velodyne/, pcd/, poses.txt nor "
                                 "keyframes; " +
                                 kInputsRead);
    }
    if (!fs::exists(p)) throw std::runtime_error("input '" + path + "' does not exist");
    const std::string ext = p.extension().string();
    const bool cloud =
        ext == ".pcd" || ext == ".ply" || ext == ".bin" || ext == ".las" || ext == ".laz";
    // A rawlog without poses takes a trajectory (--poses, and --extrinsic with it); a simple map
    // holds its poses, and --world-frame is for clouds, which the source transforms.
    if (poses.world_frame)
        throw std::runtime_error("--world-frame goes with a folder of clouds, and '" + path +
                                 "' is a file");
    if (*flag && (cloud || ext == ".simplemap"))
        throw std::runtime_error(
            std::string(flag) + " goes with a folder of clouds or a rawlog without poses, and '" +
            path + "' is " + (cloud ? "one point cloud" : "a simple map, which holds its poses"));
    if (*flag && poses.trajectory.empty())
        throw std::runtime_error(
            "--extrinsic places the LiDAR in the frame of a trajectory, and "
            "for a rawlog (" +
            path + ") it goes with --poses");
    if (cloud)
        throw std::runtime_error("'" + path + "' is one point cloud (" + ext.substr(1) +
                                 "), without a pose: moving objects are found by comparing "
                                 "scans taken at known poses. " +
                                 kInputsRead);
    if (ext == ".simplemap") return openSimpleMap(path);
    if (!poses.trajectory.empty()) return openRawlogWithPoses(path, poses);
    return openRawlog(path, poses_required);
}
}  // namespace

std::string inputTrajectory(const std::string& path, const std::string& poses)
{
    const fs::path p(path);
    if (!fs::is_directory(p)) return poses;
    if (fs::is_directory(p / "velodyne") || fs::is_directory(p / "pcd")) return "";
    return posesOf(p, poses);
}

void describeInputs(const std::string& path, RunFiles& files, const std::string& poses)
{
    const fs::path p(path);
    if (fs::is_directory(p / "velodyne"))
        files.inputKittiSequence(path, "-i");
    else if (fs::is_directory(p / "pcd"))
        files.inputFolder((p / "pcd").string(), ".pcd", "the scans of -i");
    else if (fs::is_directory(p) && !posesOf(p, poses).empty())
    {
        files.inputFolder(path, ".pcd", "the scans of -i");
        files.inputFolder(path, ".ply", "the scans of -i");
        files.input(posesOf(p, poses), "the poses of -i");
    }
    else
    {
        files.input(path, "the input (-i)");
        if (!poses.empty()) files.input(poses, "the poses of -i");
    }
}

namespace
{
/** The format of an externally stored point cloud, which MRPT 2.5.8 keeps protected without a
 *  getter (read through a pointer to the member, which a derived class may form). */
struct ExternalFormat : mrpt::obs::CObservationPointCloud
{
    static ExternalStorageFormat of(const mrpt::obs::CObservationPointCloud& pc)
    {
        return pc.*(&ExternalFormat::m_externally_stored);
    }
};
}  // namespace

void checkExternalPoints(const mrpt::obs::CObservation& obs, const std::string& where)
{
    using Format = mrpt::obs::CObservationPointCloud::ExternalStorageFormat;
    const auto* pc = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(&obs);
    if (!pc || !pc->isExternallyStored() || pc->pointcloud) return;
    const std::string file = mrpt::io::lazy_load_absolute_path(pc->getExternalStorageFile());
    const std::string its = where + ": its points are in the external file '" + file + "'";
    std::error_code ec;
    if (!fs::exists(file, ec))
        throw std::runtime_error(its +
                                 ", which does not exist (moved or deleted? a rawlog made "
                                 "with kitti2rawlog --external needs the sequence folder "
                                 "where it was)");
    if (!fs::is_regular_file(file, ec)) throw std::runtime_error(its + ", which is not a file");
    if (ExternalFormat::of(*pc) == Format::KittiBinFile)
    {
        const auto bytes = fs::file_size(file, ec);
        if (ec || bytes == 0 || bytes % 16 != 0)
            throw std::runtime_error(its + ", which is " + std::to_string(ec ? 0 : bytes) +
                                     " bytes: not a whole number of points (16 bytes each: x y "
                                     "z intensity as float32), truncated?");
    }
}

std::unique_ptr<ScanSource> openScanSource(const std::string& path, PrepareScan prepare,
                                           bool poses_required, const FolderPoses& poses)
{
    return readingAhead(openSource(path, poses_required, poses), std::move(prepare));
}

mrpt::obs::CObservation::Ptr pointCloudObservation(const io::Cloud& cloud)
{
    auto points = mrpt::maps::CPointsMapXYZI::Create();
    points->resize(cloud.size());
    for (std::size_t i = 0; i < cloud.size(); ++i)
    {
        points->setPointFast(i, cloud.x[i], cloud.y[i], cloud.z[i]);
        // An XYZI map's "colour" is its intensity (MRPT's inline setter, without the bounds
        // check of setPointIntensity(): the map was just sized to the cloud).
        points->setPointColor_fast(i, cloud.intensity[i], 0.0f, 0.0f);
    }
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    obs->sensorLabel = "LIDAR";
    obs->pointcloud = points;
    // No time until the source gives one (MRPT stamps a new observation with the time it was
    // made, which a cloud's --scan-numbers would take for the scan's).
    obs->timestamp = INVALID_TIMESTAMP;
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
            out = {obs, pose_, std::nullopt, has_pose_, std::nullopt};
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
