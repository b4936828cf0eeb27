// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Trajectory.h
 * @brief  The estimated trajectory: KITTI odometry file, and its error against ground truth.
 */
#pragma once

#include <mrpt/poses/CPose3D.h>

#include <optional>
#include <string>
#include <vector>

namespace hif::slam
{
/** Writes one line per pose: the 3x4 row-major matrix of the LiDAR pose in the frame of the
 *  first scan (KITTI odometry format). Throws std::runtime_error naming the file on failure. */
void writeKittiPoses(const std::string& file, const std::vector<mrpt::poses::CPose3D>& poses);

/** Root mean square of the translation error between `estimated` and `truth`, both expressed
 *  in the frame of their first pose (no alignment beyond that), over the first n poses of
 *  both. Nothing when there are no two poses to compare. */
[[nodiscard]] std::optional<double> trajectoryRmse(
    const std::vector<mrpt::poses::CPose3D>& estimated,
    const std::vector<mrpt::poses::CPose3D>& truth);

}  // namespace hif::slam
