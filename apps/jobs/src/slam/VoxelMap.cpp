// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelMap.cpp
 * @brief  Voxel thinning and the local ICP map.
 */
#include "VoxelMap.h"

#include <absl/container/flat_hash_map.h>

#include <cmath>

namespace hif::slam
{
mrpt::maps::CSimplePointsMap thinToVoxels(const std::vector<float>& x, const std::vector<float>& y,
                                          const std::vector<float>& z, double voxel,
                                          double min_range, double max_range)
{
    struct Sum
    {
        double x = 0, y = 0, z = 0, n = 0;
    };
    absl::flat_hash_map<io::VoxelKey, std::size_t> index;
    std::vector<Sum> sums;
    index.reserve(x.size() / 8);
    const double min2 = min_range * min_range, max2 = max_range * max_range;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !std::isfinite(z[i])) continue;
        const double r2 = double(x[i]) * x[i] + double(y[i]) * y[i] + double(z[i]) * z[i];
        if (r2 < min2 || r2 > max2) continue;
        const auto key = io::voxelKeyOf(x[i], y[i], z[i], voxel);
        if (!key) continue;  // more than 2^31 voxels away: not a point of this scan's surroundings
        const auto [it, added] = index.try_emplace(*key, sums.size());
        if (added) sums.emplace_back();
        Sum& s = sums[it->second];
        s.x += x[i];
        s.y += y[i];
        s.z += z[i];
        s.n += 1;
    }
    mrpt::maps::CSimplePointsMap out;
    out.reserve(sums.size());
    for (const Sum& s : sums)
        out.insertPointFast(static_cast<float>(s.x / s.n), static_cast<float>(s.y / s.n),
                            static_cast<float>(s.z / s.n));
    return out;
}

bool VoxelMap::occupy(float x, float y, float z)
{
    const auto key = io::voxelKeyOf(x, y, z, voxel_);
    return key && occupied_.insert(*key).second;
}

void VoxelMap::add(const mrpt::maps::CSimplePointsMap& scan, const mrpt::poses::CPose3D& pose)
{
    const auto& xs = scan.getPointsBufferRef_x();
    const auto& ys = scan.getPointsBufferRef_y();
    const auto& zs = scan.getPointsBufferRef_z();
    for (std::size_t i = 0; i < xs.size(); ++i)
    {
        double gx, gy, gz;
        pose.composePoint(xs[i], ys[i], zs[i], gx, gy, gz);
        if (occupy(float(gx), float(gy), float(gz)))
            points_.insertPointFast(float(gx), float(gy), float(gz));
    }
    points_.mark_as_modified();  // its KD-tree is built again for the next alignment
}

void VoxelMap::keepWithin(const mrpt::math::TPoint3D& centre, double radius)
{
    const auto& xs = points_.getPointsBufferRef_x();
    const auto& ys = points_.getPointsBufferRef_y();
    const auto& zs = points_.getPointsBufferRef_z();
    mrpt::maps::CSimplePointsMap kept;
    kept.reserve(xs.size());
    occupied_.clear();
    const double r2 = radius * radius;
    for (std::size_t i = 0; i < xs.size(); ++i)
    {
        const double dx = xs[i] - centre.x, dy = ys[i] - centre.y;
        if (dx * dx + dy * dy > r2) continue;
        if (occupy(xs[i], ys[i], zs[i])) kept.insertPointFast(xs[i], ys[i], zs[i]);
    }
    kept.mark_as_modified();
    points_ = std::move(kept);
}

}  // namespace hif::slam
