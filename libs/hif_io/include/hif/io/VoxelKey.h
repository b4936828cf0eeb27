// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelKey.h
 * @brief  The exact key of a cubic voxel: its three indices, 32 bits each (no packing that lets
 *         far-apart voxels collide), hashable by Abseil's containers and ordered.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>

namespace hif::io
{
/** A voxel's indices along x, y and z: voxel (i, j, k) of side s holds floor(x / s) = i, ... */
struct VoxelKey
{
    int32_t i = 0, j = 0, k = 0;

    friend bool operator==(const VoxelKey& a, const VoxelKey& b)
    {
        return a.i == b.i && a.j == b.j && a.k == b.k;
    }
    friend bool operator!=(const VoxelKey& a, const VoxelKey& b) { return !(a == b); }
    /** i, then j, then k. */
    friend bool operator<(const VoxelKey& a, const VoxelKey& b)
    {
        return a.i != b.i ? a.i < b.i : (a.j != b.j ? a.j < b.j : a.k < b.k);
    }
    template <typename H>
    friend H AbslHashValue(H h, const VoxelKey& key)
    {
        return H::combine(std::move(h), key.i, key.j, key.k);
    }
};

/** The voxel of side `voxel` that holds (x, y, z); none when a coordinate is not finite or an
 *  index does not fit 32 bits (more than 2^31 voxels from the origin). */
[[nodiscard]] inline std::optional<VoxelKey> voxelKeyOf(double x, double y, double z, double voxel)
{
    int32_t index[3];
    const double p[3] = {x, y, z};
    for (int a = 0; a < 3; ++a)
    {
        const double i = std::floor(p[a] / voxel);
        // NaN fails both comparisons.
        if (!(i >= double(std::numeric_limits<int32_t>::min()) &&
              i <= double(std::numeric_limits<int32_t>::max())))
            return std::nullopt;
        index[a] = static_cast<int32_t>(i);
    }
    return VoxelKey{index[0], index[1], index[2]};
}

}  // namespace hif::io
