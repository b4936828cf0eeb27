// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   QuantizePass.h
 * @brief  Pass 1 of bucketPoints(): every point of a chunk transformed to the world frame and
 *         quantized (Eq. 1), invalid points and repeats dropped.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "hif/GridGeometry.h"
#include "hif/PillarGrid.h"

namespace hif::detail
{
/** What pass 1 of bucketPoints() found in one chunk of input points. */
struct ChunkSummary
{
    std::size_t valid = 0;  ///< valid points, repeats included
    std::size_t kept = 0;   ///< valid points that are not repeats
    std::size_t near = 0;   ///< finite points nearer the sensor than the minimum range
    int32_t m_min = std::numeric_limits<int32_t>::max();
    int32_t m_max = std::numeric_limits<int32_t>::min();
    int32_t n_min = std::numeric_limits<int32_t>::max();
    int32_t n_max = std::numeric_limits<int32_t>::min();
    double top_slope_sq = -std::numeric_limits<double>::infinity();  ///< see ScanBuckets
};

/** Where pass 1 writes a chunk's kept points: their pillar (m, n) and height cell z from the
 *  chunk's first index on; with `src` (classification), their input index, and in `repeats`,
 *  1 for each input point that repeats the one before it. */
struct ChunkOutput
{
    int32_t* m = nullptr;
    int32_t* n = nullptr;
    int32_t* z = nullptr;
    uint32_t* src = nullptr;  ///< null: no index wanted (then repeats is not written)
    uint8_t* repeats = nullptr;
};

/** Pass 1 over input points [i0, i1): transform by `sensor_to_world`, quantize (Eq. 1, as
 *  quantize() without std::optional) and write the valid points that are not repeats to
 *  out.m/n/z[i0...] (and their input index to out.src), with their bounding box and the top
 *  beam's elevation. Points nearer the sensor than `min_range` are dropped (counted in
 *  `near`). Four points at a time with AVX when useAvx() (the same operations in the
 *  same order, without fused multiply-add, so the same bits), one at a time otherwise and for
 *  the last 1-3 points of a chunk. */
ChunkSummary quantizeChunk(const Eigen::Isometry3d& sensor_to_world, const GridGeometry& geometry,
                           double min_range, const PointsView& pts, std::size_t i0, std::size_t i1,
                           const ChunkOutput& out);

}  // namespace hif::detail
