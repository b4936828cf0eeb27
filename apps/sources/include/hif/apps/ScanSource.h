// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanSource.h
 * @brief  hif-clean's inputs, read one scan at a time behind one interface: an MRPT rawlog
 *         (a CObservationRobotPose before each scan, as kitti2rawlog writes; observations or
 *         sensory frames), a .simplemap, a KITTI sequence folder (velodyne/, poses.txt,
 *         calib.txt), a DynamicMap benchmark folder (pcd/NNNNNN.pcd in the world frame,
 *         sensor pose in VIEWPOINT), or a folder of clouds in the sensor frame (NNNNNN.pcd or
 *         .ply) with their poses (poses.txt, KITTI or TUM format), as LiDAR SLAM systems
 *         write them; a rawlog without poses (MRPT's rosbag2rawlog) with such a trajectory.
 */
#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Geometry>

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hif/apps/RunFiles.h"
#include "hif/io/Cloud.h"

namespace hif::apps
{
/** One scan: the observation, the robot pose it was taken at, and its number in its
 *  sequence when the input says (kitti2rawlog's comments, a DynamicMap file's name). */
struct Scan
{
    mrpt::obs::CObservation::Ptr obs;
    mrpt::poses::CPose3D robot_pose;
    std::optional<std::size_t> frame;
    /** False for a scan of a rawlog opened with poses optional that had none before it
     *  (robot_pose is then the identity). */
    bool has_pose = true;
    /** The name of its outputs (predictions/<name>.label) where the input names its scans by
     *  something else than their number (clouds named by their time); else the frame's. */
    std::optional<std::string> name;
};

/** Work done on each scan on the reader thread, right after reading it. */
using PrepareScan = std::function<void(Scan&)>;

class ScanSource
{
public:
    virtual ~ScanSource() = default;
    /** Next scan; false at the end. Throws std::runtime_error naming the file on a scan
     *  without a pose or a corrupt file. */
    virtual bool next(Scan& out) = 0;
    /** Starts again from the first scan. */
    virtual void rewind() = 0;
    /** Number of scans when known before reading, else 0. */
    [[nodiscard]] virtual std::size_t knownSize() const { return 0; }
    /** Objects of the input that were neither poses nor scans (skipped). */
    [[nodiscard]] virtual std::size_t skippedObjects() const { return 0; }
    /** Scans of the input left out in the pass read last, for want of a pose (a rawlog's scans
     *  whose times its trajectory does not cover): how many, and a sentence that says which
     *  and why (empty when none was). */
    struct LeftOut
    {
        std::size_t scans = 0;
        std::string why;
    };
    [[nodiscard]] virtual LeftOut leftOutScans() const { return {}; }
    /** True for a DynamicMap benchmark folder (whose result goes to <folder>/hif_output.pcd). */
    [[nodiscard]] virtual bool isDynamicMapFolder() const { return false; }
    /** What the source found odd but could read past (files it ignored), one line each. */
    [[nodiscard]] virtual std::vector<std::string> warnings() const { return {}; }
};

/** The trajectory file `path` is read with: `poses` when given (a folder of clouds or a
 *  rawlog), else a folder of clouds' poses.txt; empty for any other input. */
[[nodiscard]] std::string inputTrajectory(const std::string& path, const std::string& poses);

/** Adds to `files` what reading `path` (with `poses`, see openScanSource()) reads: a rawlog or
 *  simple map file, a KITTI folder's files, a DynamicMap folder's scans, or a folder's clouds and
 *  its poses. */
void describeInputs(const std::string& path, RunFiles& files, const std::string& poses = "");

/** Throws std::runtime_error naming `where` and the file if `obs` keeps its points in an
 *  external file (MRPT lazy load) that is missing, not a file, or (a KITTI .bin) empty or not a
 *  whole number of points: MRPT would stop with an assertion, or read half a scan. */
void checkExternalPoints(const mrpt::obs::CObservation& obs, const std::string& where);

/** Where a folder of clouds takes its poses. */
struct FolderPoses
{
    /** Its trajectory file (KITTI or TUM format); empty: the folder's poses.txt. */
    std::string trajectory;
    /** The LiDAR's pose in the frame of the trajectory's poses, when they are another
     *  sensor's (the IMU of most LiDAR-inertial SLAM systems): each scan is then at pose x
     *  extrinsic. None: they are the LiDAR's own. */
    std::optional<Eigen::Isometry3d> extrinsic;
    /** The clouds are in the world frame (registered by the SLAM system, as FAST-LIO's
     *  /cloud_registered), not the sensor's: each is brought into the sensor's frame by its
     *  pose's inverse. */
    bool world_frame = false;
};

/** Opens `path`: a folder with velodyne/ is a KITTI sequence, a folder with pcd/ a DynamicMap
 *  folder, a folder with poses.txt (or any folder, with `poses` naming its trajectory file)
 *  clouds with poses (`poses`: their trajectory and extrinsic, for no other input), a *.simplemap
 * file a simple map, a single cloud (.pcd, .ply, .bin, .las) an error that says what is read,
 * anything else a rawlog (plain or gzip). The source reads one scan ahead on a second thread, and
 * there calls `prepare` (if set) on it. Throws std::runtime_error naming it. */
std::unique_ptr<ScanSource> openScanSource(const std::string& path, PrepareScan prepare = {},
                                           bool poses_required = true,
                                           const FolderPoses& poses = {});

/** With `poses_required` false, a scan without a CObservationRobotPose before it is handed out
 *  with has_pose false instead of being an error (SLAM estimates its own poses). */
std::unique_ptr<ScanSource> openRawlog(const std::string& file, bool poses_required = true);
/** A rawlog without poses (as MRPT's rosbag2rawlog writes one from a ROS bag), each scan at the
 *  pose `poses.trajectory` gives it (hif::io::readTrajectory()): in the TUM format the pose of
 *  the scan's time (hif::io::poseAt(), within twice the trajectory's median spacing; a scan
 *  whose time has none is left out, leftOutScans()), in the KITTI format the k-th scan's the
 *  k-th pose; times `poses.extrinsic` when given. Each scan's outputs take its place in the
 *  rawlog for a number. Throws std::runtime_error naming the files when the rawlog holds poses
 *  of its own, a scan has no time (TUM) or the trajectory too few poses (KITTI). */
std::unique_ptr<ScanSource> openRawlogWithPoses(const std::string& file, const FolderPoses& poses);
std::unique_ptr<ScanSource> openSimpleMap(const std::string& file);
std::unique_ptr<ScanSource> openDynamicMapFolder(const std::string& folder);
std::unique_ptr<ScanSource> openKittiFolder(const std::string& folder);
/** Clouds in the sensor frame, NNNNNN.pcd, .ply or .bin (KITTI's) in `folder`, at the poses of
 *  `poses_file` (hif::io::readTrajectory()): the k-th scan (by number) takes the k-th pose when
 *  the counts agree, else scan NNNNNN takes pose NNNNNN (a trajectory longer than the folder);
 *  or clouds named by their time, at the poses of those times (hif::io::poseAt()). With an
 *  extrinsic (`poses`), each at pose x extrinsic; `poses.trajectory` is not read (poses_file
 *  is). */
std::unique_ptr<ScanSource> openScansWithPoses(const std::string& folder,
                                               const std::string& poses_file,
                                               const FolderPoses& poses = {});
/** hdl_graph_slam's saved keyframes (interactive_slam reads them too): a subfolder per keyframe,
 *  NNNNNN/cloud.pcd in the keyframe's frame and NNNNNN/data with its time and its optimized
 *  pose (`estimate`, a 4x4 matrix). */
std::unique_ptr<ScanSource> openKeyframesFolder(const std::string& folder);
/** Whether `folder` holds such keyframes (a numbered subfolder with a `data` file). */
[[nodiscard]] bool isKeyframesFolder(const std::string& folder);
/** `source`, its next scan read (and given to `prepare`, if set) on a second thread while the
 *  caller works on the current one. */
std::unique_ptr<ScanSource> readingAhead(std::unique_ptr<ScanSource> source,
                                         PrepareScan prepare = {});

/** A CObservationPointCloud (sensor label LIDAR) holding `cloud` as a CPointsMapXYZI, without a
 *  time (INVALID_TIMESTAMP: the source sets the scan's time where it knows it). */
[[nodiscard]] mrpt::obs::CObservation::Ptr pointCloudObservation(const io::Cloud& cloud);

/** Whether hif-clean can insert and classify this observation type. */
[[nodiscard]] bool isScan(const mrpt::obs::CObservation& obs);

/** The scans of one sensory frame, handed out one at a time. A CObservationRobotPose in the
 *  frame sets the pose of the scans after it. */
class FrameScans
{
public:
    /** The frame's observations, with the robot pose of the scans before any pose in it. */
    void assign(const mrpt::obs::CSensoryFrame& frame, const mrpt::poses::CPose3D& pose,
                bool has_pose = true);
    /** The next scan of the frame; false when none is left. */
    bool next(Scan& out);
    void clear() { pending_.clear(); }

private:
    std::vector<mrpt::obs::CObservation::Ptr> pending_;  // in reverse order
    mrpt::poses::CPose3D pose_;
    bool has_pose_ = true;
};

}  // namespace hif::apps
