// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PoseCheck.cpp
 * @brief  Overlap of consecutive scans at their poses.
 */
#include "PoseCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "hif/CHeightIntervalMap.h"

namespace hif::apps
{
namespace
{
double median(std::vector<double> v)
{
    if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

/** Voxels of 21 bits an axis: +-2^20 voxels around the first scan. */
constexpr int64_t kHalfRange = int64_t{1} << 20;
}  // namespace

std::optional<uint64_t> PoseCheck::key(double x, double y, double z) const
{
    const double c[3] = {(x - ox_) / kVoxel, (y - oy_) / kVoxel, (z - oz_) / kVoxel};
    uint64_t k = 0;
    for (int a = 0; a < 3; ++a)
    {
        if (!(std::abs(c[a]) < double(kHalfRange))) return std::nullopt;  // NaN too
        k |= static_cast<uint64_t>(static_cast<int64_t>(std::floor(c[a])) + kHalfRange) << (21 * a);
    }
    return k;
}

std::pair<double, std::size_t> PoseCheck::overlap(const std::vector<double>& x,
                                                  const std::vector<double>& y,
                                                  const std::vector<double>& z, double min_z) const
{
    constexpr std::size_t kSample = 4096;
    std::size_t above = 0;
    for (std::size_t i = 0; i < z.size(); ++i) above += z[i] > min_z;
    const std::size_t step = std::max<std::size_t>(1, above / kSample);
    std::size_t hit = 0, n = 0, seen = 0;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        if (!(z[i] > min_z) || seen++ % step != 0) continue;
        if (const auto k = key(x[i], y[i], z[i]))
        {
            ++n;
            hit += occupied_.count(*k);
        }
    }
    return {n ? double(hit) / double(n) : 0.0, n};
}

std::optional<std::string> PoseCheck::add(const Scan& scan)
{
    if (done()) return std::nullopt;
    std::vector<double> x, y, z;
    if (!hif::CHeightIntervalMap::observationToWorldPoints(*scan.obs, scan.robot_pose, x, y, z) ||
        x.size() < kMinPoints)
        return std::nullopt;
    if (!have_origin_)
    {
        ox_ = scan.robot_pose.x();
        oy_ = scan.robot_pose.y();
        oz_ = scan.robot_pose.z();
        have_origin_ = true;
    }
    mrpt::poses::CPose3D on_robot;
    scan.obs->getSensorPose(on_robot);
    if (previous_pose_)
    {
        overlap_.push_back(overlap(x, y, z, -std::numeric_limits<double>::infinity()).first);
        std::vector<double> sx, sy, sz;  // this scan where the sensor was for the previous one
        hif::CHeightIntervalMap::observationToWorldPoints(*scan.obs, *previous_pose_, sx, sy, sz);
        const auto at_poses = overlap(x, y, z, (scan.robot_pose + on_robot).z());
        const auto still = overlap(sx, sy, sz, (*previous_pose_ + on_robot).z());
        if (at_poses.second >= kMinAbove && still.second >= kMinAbove)
        {
            above_.push_back(at_poses.first);
            above_no_motion_.push_back(still.first);
        }
    }
    previous_pose_ = scan.robot_pose;
    occupied_.clear();
    for (std::size_t i = 0; i < x.size(); ++i)
        if (const auto k = key(x[i], y[i], z[i])) occupied_.insert(*k);
    return overlap_.size() >= kPairs ? finish() : std::nullopt;
}

std::optional<std::string> PoseCheck::finish()
{
    if (done() || overlap_.empty()) return std::nullopt;
    finished_ = true;
    occupied_ = {};
    previous_pose_.reset();
    const double at_poses = medianOverlap(), above = medianAbove(), still = medianAboveNoMotion();
    const bool no_motion_better = above < still - kNoMotionMargin;  // false for NaN
    if (at_poses >= kMinOverlap && !no_motion_better) return std::nullopt;
    std::ostringstream msg;
    msg.precision(2);
    msg << std::fixed << "the poses may not belong to the scans: at their poses, consecutive "
        << "scans share " << at_poses * 100 << " % of their points (" << kVoxel
        << " m voxels, median of the first " << pairs() << (pairs() == 1 ? " pair)" : " pairs)");
    if (no_motion_better)
        msg << "; above the sensor, " << above * 100
            << " %, fewer than if it had not moved at all (" << still * 100 << " %)";
    msg << ". Check that each pose is the sensor's (not a camera's or the vehicle's) pose in the "
           "world (not its inverse), one per scan in order";
    return msg.str();
}

double PoseCheck::medianOverlap() const { return median(overlap_); }
double PoseCheck::medianAbove() const { return median(above_); }
double PoseCheck::medianAboveNoMotion() const { return median(above_no_motion_); }

}  // namespace hif::apps
