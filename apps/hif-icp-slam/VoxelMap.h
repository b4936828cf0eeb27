// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelMap.h
 * @brief  Voxel thinning of a scan (one centroid per voxel) and the local map that ICP aligns
 *         against (one point per voxel, kept within a radius of the sensor).
 */
#pragma once

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <unordered_set>
#include <vector>

namespace hif::slam
{
/** The centroid of the points of `x`, `y`, `z` in each cubic voxel of side `voxel`, in order of
 *  first appearance; points that are not finite or whose range from the origin is outside
 *  [min_range, max_range] are left out. */
[[nodiscard]] mrpt::maps::CSimplePointsMap thinToVoxels(const std::vector<float>& x,
                                                        const std::vector<float>& y,
                                                        const std::vector<float>& z, double voxel,
                                                        double min_range, double max_range);

/** Points in the world frame, at most one per voxel (the first to arrive), for ICP to align
 *  scans against. */
class VoxelMap
{
public:
    explicit VoxelMap(double voxel) : voxel_(voxel) {}

    /** Adds the points of `scan` (sensor frame) placed at `pose`, each unless its voxel has a
     *  point already. */
    void add(const mrpt::maps::CSimplePointsMap& scan, const mrpt::poses::CPose3D& pose);
    /** Drops the points farther than `radius` (in x, y) from `centre`. */
    void keepWithin(const mrpt::math::TPoint3D& centre, double radius);

    [[nodiscard]] const mrpt::maps::CSimplePointsMap& points() const { return points_; }
    [[nodiscard]] std::size_t size() const { return points_.size(); }

private:
    [[nodiscard]] uint64_t key(float x, float y, float z) const;

    double voxel_;
    mrpt::maps::CSimplePointsMap points_;
    std::unordered_set<uint64_t> occupied_;
};

}  // namespace hif::slam
