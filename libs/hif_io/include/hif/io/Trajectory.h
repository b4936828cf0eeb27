// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Trajectory.h
 * @brief  A sensor trajectory as LiDAR SLAM systems write it: the KITTI format (a 3x4
 *         row-major matrix per line) or the TUM format (timestamp x y z qx qy qz qw).
 */
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hif::io
{
/** The poses of a trajectory file, one per scan, in the file's order. */
struct Trajectory
{
    enum class Format
    {
        Kitti,  ///< 12 numbers a line: the 3x4 matrix [R | t], row by row
        Tum     ///< 8 numbers a line: time, position, unit quaternion (x y z w)
    };
    Format format = Format::Kitti;
    std::vector<Eigen::Isometry3d> poses;
    /** Seconds, one per pose, for the TUM format; empty for the KITTI format. */
    std::vector<double> times;

    [[nodiscard]] std::size_t size() const { return poses.size(); }
    [[nodiscard]] const char* formatName() const
    {
        return format == Format::Kitti ? "KITTI (3x4 matrix a line)"
                                       : "TUM (time x y z qx qy qz qw a line)";
    }
};

/** Times closer than this are one time, seconds: a scan's time and its pose's, each printed by
 *  its own tool (to the microsecond, or the nanosecond through a double). */
constexpr double kSameTime = 1e-4;

/** The pose of a TUM trajectory `tr` (times increasing) at time `t`: the pose at that time
 *  (within kSameTime), else interpolated between the poses around it (position linearly,
 *  rotation by slerp) when they are at most `max_gap` seconds apart; none before the first
 *  pose, after the last, within a wider gap, or without times (the KITTI format). */
[[nodiscard]] std::optional<Eigen::Isometry3d> poseAt(const Trajectory& tr, double t,
                                                      double max_gap);

/** The median time between consecutive poses of `tr` (0 for fewer than two, or no times). */
[[nodiscard]] double medianSpacing(const Trajectory& tr);

/** For messages about scans a TUM trajectory `tr` gives no pose: "its poses run from A to B s,
 *  S s apart (median)" (times to the microsecond); "it has no times" for the KITTI format. */
[[nodiscard]] std::string describeTimes(const Trajectory& tr);

/** The LiDAR's pose in the frame a trajectory gives (another sensor's: the IMU of most
 *  LiDAR-inertial SLAM systems), from `text`: 7 numbers, x y z qx qy qz qw (a unit quaternion,
 *  the TUM order), or 12, the 3x4 matrix [R | t] row by row (a rigid motion). Throws
 *  std::runtime_error naming "--extrinsic", the text and the problem. */
[[nodiscard]] Eigen::Isometry3d parseExtrinsic(const std::string& text);

/** The 7 numbers of `pose` that parseExtrinsic() reads: x y z qx qy qz qw (the TUM order). */
[[nodiscard]] std::array<double, 7> xyzQxyzw(const Eigen::Isometry3d& pose);

/** Reads `file`, its format told by its first pose line (12 or 8 numbers); empty lines and
 *  lines starting with '#' are skipped. Every pose is checked as KittiSequence checks poses.txt
 *  (a rigid motion; a TUM quaternion of norm 1 within kRotationTolerance, and its times
 *  increasing). Throws std::runtime_error naming the file, the line and the problem. */
[[nodiscard]] Trajectory readTrajectory(const std::string& file);

}  // namespace hif::io
