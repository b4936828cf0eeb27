// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Trajectory.h
 * @brief  A sensor trajectory as LiDAR SLAM systems write it: the KITTI format (a 3x4
 *         row-major matrix per line) or the TUM format (timestamp x y z qx qy qz qw).
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
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

/** Reads `file`, its format told by its first pose line (12 or 8 numbers); empty lines and
 *  lines starting with '#' are skipped. Every pose is checked as KittiSequence checks poses.txt
 *  (a rigid motion; a TUM quaternion of norm 1 within kRotationTolerance, and its times
 *  increasing). Throws std::runtime_error naming the file, the line and the problem. */
[[nodiscard]] Trajectory readTrajectory(const std::string& file);

}  // namespace hif::io
