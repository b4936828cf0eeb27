// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PoseCheck.h
 * @brief  Whether the poses belong to the scans: consecutive scans of a moving LiDAR see mostly
 *         the same surfaces, and their true poses put those surfaces in the same place.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "hif/apps/ScanSource.h"

namespace hif::apps
{
/** Checks the first kPairs pairs of consecutive scans, before the run is spent on wrong poses
 *  (the most common cause of bad results: poses of another sensor frame, such as KITTI's
 *  camera, inverted, or of other scans). For a pair (a, b), the overlap is the share of b's
 *  points (a sample) that fall in a kVoxel-metre voxel holding a point of a, both in the world
 *  at their poses. With true poses it is high (0.8-0.95 on KITTI's HDL-64E); camera-frame poses
 *  give 0.05-0.2. Then the relative motion the poses state must explain the scans at least as
 *  well as no motion (b placed at a's pose) does. That comparison is made on the points above
 *  the sensor (walls, trees, poles) only: the rings a LiDAR draws on the ground below it move
 *  with it, so with no motion they fall on themselves, and a sparse sensor's ground would
 *  favour "no motion" whatever the poses. Inverted poses fall 0.1-0.15 below no motion there.
 *  The medians over the pairs decide, so one odd pair does not. */
class PoseCheck
{
public:
    static constexpr std::size_t kPairs = 5;
    static constexpr double kVoxel = 0.5;  ///< metres
    /** Below this median overlap the poses do not align the scans. */
    static constexpr double kMinOverlap = 0.3;
    /** The poses are doubted when no motion aligns the scans better by more than this. */
    static constexpr double kNoMotionMargin = 0.05;
    /** Points above the sensor a pair needs for the comparison with no motion. */
    static constexpr std::size_t kMinAbove = 200;
    /** Points a scan needs to be checked: one of a few points (a scan cut short) would make
     *  its two pairs look misplaced, and a short run has few pairs to outvote them; a 2D
     *  scanner's 181 beams are enough (the share of 50 points is known to about 0.07). */
    static constexpr std::size_t kMinPoints = 50;

    /** Adds the next scan (while the check is not done; scans with fewer than kMinPoints
     *  points or of a type without world points are passed over). Returns, once the last pair
     *  is in and the poses fail, the warning to print. */
    std::optional<std::string> add(const Scan& scan);
    /** Decides on the pairs added so far, for a run of fewer than kPairs + 1 scans: the
     *  warning to print when the poses fail (none without a pair, or once done). */
    std::optional<std::string> finish();
    [[nodiscard]] bool done() const { return finished_; }
    /** Medians of the pairs checked so far: at the poses (all points), and above the sensor
     *  at the poses and with no motion between a pair (NaN when no pair had enough points
     *  above the sensor). */
    [[nodiscard]] double medianOverlap() const;
    [[nodiscard]] double medianAbove() const;
    [[nodiscard]] double medianAboveNoMotion() const;
    [[nodiscard]] std::size_t pairs() const { return overlap_.size(); }

private:
    /** The voxel of a world point, relative to the first scan's position; nullopt far off. */
    [[nodiscard]] std::optional<uint64_t> key(double x, double y, double z) const;
    /** The share of a sample of the points (x, y, z) higher than `min_z` that lie in voxels of
     *  occupied_, and the size of that sample. */
    [[nodiscard]] std::pair<double, std::size_t> overlap(const std::vector<double>& x,
                                                         const std::vector<double>& y,
                                                         const std::vector<double>& z,
                                                         double min_z) const;

    bool finished_ = false;
    bool have_origin_ = false;
    double ox_ = 0, oy_ = 0, oz_ = 0;
    std::unordered_set<uint64_t> occupied_;              ///< voxels of the previous scan
    std::optional<mrpt::poses::CPose3D> previous_pose_;  ///< of the previous scan
    std::vector<double> overlap_, above_, above_no_motion_;
};

}  // namespace hif::apps
