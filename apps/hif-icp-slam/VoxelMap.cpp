// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelMap.cpp
 * @brief  Voxel thinning and the local ICP map.
 */
#include "VoxelMap.h"

#include <cmath>
#include <unordered_map>

namespace hif::slam
{
namespace
{
/** 21 bits per axis, offset so that +-10 km from the origin fits at 1 cm voxels. */
uint64_t packVoxel(double x, double y, double z, double voxel)
{
    const auto c = [voxel](double v)
    {
        return static_cast<uint64_t>(static_cast<int64_t>(std::floor(v / voxel)) + (1 << 20)) &
               0x1FFFFF;
    };
    return (c(x) << 42) | (c(y) << 21) | c(z);
}
}  // namespace

mrpt::maps::CSimplePointsMap thinToVoxels(const std::vector<float>& x, const std::vector<float>& y,
                                          const std::vector<float>& z, double voxel,
                                          double min_range, double max_range)
{
    struct Sum
    {
        double x = 0, y = 0, z = 0, n = 0;
    };
    std::unordered_map<uint64_t, std::size_t> index;
    std::vector<Sum> sums;
    index.reserve(x.size() / 8);
    const double min2 = min_range * min_range, max2 = max_range * max_range;
    for (std::size_t i = 0; i < x.size(); ++i)
    {
        if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !std::isfinite(z[i])) continue;
        const double r2 = double(x[i]) * x[i] + double(y[i]) * y[i] + double(z[i]) * z[i];
        if (r2 < min2 || r2 > max2) continue;
        const auto [it, added] = index.try_emplace(packVoxel(x[i], y[i], z[i], voxel), sums.size());
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

uint64_t VoxelMap::key(float x, float y, float z) const { return packVoxel(x, y, z, voxel_); }

void VoxelMap::add(const mrpt::maps::CSimplePointsMap& scan, const mrpt::poses::CPose3D& pose)
{
    const auto& xs = scan.getPointsBufferRef_x();
    const auto& ys = scan.getPointsBufferRef_y();
    const auto& zs = scan.getPointsBufferRef_z();
    for (std::size_t i = 0; i < xs.size(); ++i)
    {
        double gx, gy, gz;
        pose.composePoint(xs[i], ys[i], zs[i], gx, gy, gz);
        if (occupied_.insert(key(float(gx), float(gy), float(gz))).second)
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
        kept.insertPointFast(xs[i], ys[i], zs[i]);
        occupied_.insert(key(xs[i], ys[i], zs[i]));
    }
    kept.mark_as_modified();
    points_ = std::move(kept);
}

}  // namespace hif::slam
