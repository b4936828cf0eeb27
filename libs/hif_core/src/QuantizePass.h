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

/** Bits of a point's edge code (quantizeChunk()): the point lies within the edge margin of
 *  its pillar's low-m, high-m, low-n or high-n edge (kEdgeBits: a stored point's are joined
 *  by those of the repeats of its run); and where in its pillar the stored point lies, in
 *  1/256 of the pillar along m (bits kPlaceShift to kPlaceShift + 7) and n (the next 8). */
enum EdgeBits : int32_t
{
    kEdgeLowM = 1,
    kEdgeHighM = 2,
    kEdgeLowN = 4,
    kEdgeHighN = 8,
    kEdgeBits = 15,
    kPlaceShift = 8
};

/** Where pass 1 writes a chunk's kept points: their pillar (m, n) and height cell z from the
 *  chunk's first index on; with `src` (classification), their input index, and in `repeats`,
 *  1 for each input point that repeats the one before it; with `edge` (insertion with
 *  Params::miss_needs_beam), their edge code (EdgeBits; its edge bits only with
 *  Params::pillar_edge_margin, `edge_fraction` > 0). */
struct ChunkOutput
{
    int32_t* m = nullptr;
    int32_t* n = nullptr;
    int32_t* z = nullptr;
    uint32_t* src = nullptr;  ///< null: no index wanted (then repeats is not written)
    uint8_t* repeats = nullptr;
    int32_t* edge = nullptr;  ///< null: no edge codes wanted (classification, with `src`)
    /** With `edge`: the edge margin as a fraction of the pillar's size, in [0, 0.5). */
    double edge_fraction = 0.0;
};

/** Pass 1 over input points [i0, i1): transform by `sensor_to_world`, quantize (Eq. 1, as
 *  quantize() without std::optional) and write the valid points that are not repeats to
 *  out.m/n/z[i0...] (and their input index to out.src, their edge code to out.edge), with
 *  their bounding box and the top beam's elevation. A repeat's edge code joins that of the stored
 *  point of its run. Points nearer the sensor than `min_range` are dropped (counted in
 *  `near`). Four points at a time with AVX when useAvx() (the same operations in the
 *  same order, without fused multiply-add, so the same bits), one at a time otherwise and for
 *  the last 1-3 points of a chunk. */
ChunkSummary quantizeChunk(const Eigen::Isometry3d& sensor_to_world, const GridGeometry& geometry,
                           double min_range, const PointsView& pts, std::size_t i0, std::size_t i1,
                           const ChunkOutput& out);

}  // namespace hif::detail
