// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KittiSequence.h
 * @brief  A KITTI odometry sequence in the SemanticKITTI layout, validated on opening.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hif/io/Cloud.h"

namespace hif::io
{
/** Reads `<dir>/velodyne/NNNNNN.bin`, `calib.txt`, `poses.txt`, `times.txt` and, when
 *  present, `labels/NNNNNN.label`.
 *  The constructor checks everything it can before any scan is read, and throws
 *  std::runtime_error naming the file and the problem: a missing folder or file, a
 *  `calib.txt` without `Tr` or with two, a malformed line or a pose that is not a rigid motion,
 * fewer poses or times than scans, scan files that are not numbered 000000, 000001, ... without
 * gaps, or a .bin whose size is not a multiple of 16 bytes. */
class KittiSequence
{
public:
    explicit KittiSequence(const std::string& dir);

    [[nodiscard]] const std::string& dir() const { return dir_; }
    [[nodiscard]] std::size_t size() const { return scan_count_; }
    [[nodiscard]] bool hasLabels() const { return has_labels_; }

    /** Pose of scan i in the world frame of the LiDAR: T_world_velo(i) = inv(Tr) * P(i) * Tr,
     *  where P(i) is the camera-0 pose of poses.txt and Tr maps LiDAR to camera-0 coordinates. */
    [[nodiscard]] const Eigen::Isometry3d& pose(std::size_t i) const { return poses_.at(i); }
    /** Seconds since the start of the sequence (times.txt). */
    [[nodiscard]] double time(std::size_t i) const { return times_.at(i); }
    [[nodiscard]] const Eigen::Isometry3d& Tr() const { return Tr_; }

    [[nodiscard]] std::string scanFile(std::size_t i) const;
    [[nodiscard]] std::string labelFile(std::size_t i) const;

    /** Number of points of scan i, from its file size; throws if the file is empty or its size
     *  is not a multiple of 16 bytes. */
    [[nodiscard]] std::size_t pointCount(std::size_t i) const;
    /** The points of scan i, in the LiDAR frame, in file order. Throws naming the file if it
     *  cannot be read whole. */
    [[nodiscard]] Cloud readScan(std::size_t i) const;

private:
    std::string dir_;
    std::size_t scan_count_ = 0;
    bool has_labels_ = false;
    Eigen::Isometry3d Tr_ = Eigen::Isometry3d::Identity();
    std::vector<Eigen::Isometry3d> poses_;
    std::vector<double> times_;
};

/** The number of points of a KITTI .bin scan (x y z intensity, float32 each), from its size;
 *  throws naming the file if it is empty, unreadable or not a multiple of 16 bytes. */
[[nodiscard]] std::size_t kittiBinPointCount(const std::string& file);
/** The points of a KITTI .bin scan, in file order. Throws naming the file as
 *  kittiBinPointCount() does, or if it cannot be read whole. */
[[nodiscard]] Cloud readKittiBin(const std::string& file);

/** "%06d" file stem used by KITTI and SemanticKITTI. */
[[nodiscard]] std::string frameName(std::size_t i);

/** How far R^T R of a pose's rotation may differ from the identity (largest element): poses
 *  printed with 4 or more significant digits pass, a scaled or degenerate matrix does not. */
constexpr double kRotationTolerance = 1e-3;

/** Reads a 3x4 row-major matrix (12 numbers) from `line` of `file`, a rigid motion; throws
 *  naming the file, `where` (e.g. "line 3") and the problem: a token that is not a number or
 *  not finite (which one), fewer or more than 12, or a rotation part that is not orthonormal
 *  within kRotationTolerance (or is a reflection). */
[[nodiscard]] Eigen::Isometry3d parseRow34(const std::string& line, const std::string& file,
                                           const std::string& where);

}  // namespace hif::io
