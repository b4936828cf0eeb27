// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelMap.h
 * @brief  Voxel thinning of a scan (one centroid per voxel) and the local map that ICP aligns
 *         against (one point per voxel, kept within a radius of the sensor).
 */
#pragma once

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3D.h>

#include <absl/container/flat_hash_set.h>

#include <cstdint>
#include <vector>

#include "hif/io/VoxelKey.h"

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
    /** Marks the voxel of (x, y, z) occupied: false when it was already (or lies more than
     *  2^31 voxels away). */
    bool occupy(float x, float y, float z);

    double voxel_;
    mrpt::maps::CSimplePointsMap points_;
    absl::flat_hash_set<io::VoxelKey> occupied_;  ///< exact keys: far voxels never collide
};

}  // namespace hif::slam
