// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   VoxelMerger.h
 * @brief  A point cloud merged per cubic voxel (centroid, mean intensity, number of points),
 *         streamed with bounded memory: a long sequence gives a map of its area's size.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace hif::io
{
/** One voxel's merged point. */
struct MergedPoint
{
    double x = 0, y = 0, z = 0;  ///< the centroid of its points
    float intensity = 0;         ///< their mean intensity
    uint32_t points = 0;         ///< how many were merged
};

/** Merges points into the cubic voxels of side `voxel` of a grid with a corner at the origin
 *  (voxel (i, j, k) holds floor(x / voxel) = i, ...). At most `max_voxels` voxels are held in
 *  memory; when they are full, the half least recently added to (the area the sensor left)
 *  goes to a sorted run file next to `spill_prefix`, and finish() merges the runs, adding up
 *  a voxel's sums across them (a voxel left and seen again, as on a loop, is still one point).
 *  The sums are kept relative to each voxel's corner, in double: world coordinates in the
 *  millions of metres keep their precision. The result does not depend on `max_voxels` beyond
 *  the rounding of the sums' order. Throws std::runtime_error naming a run file that cannot be
 *  written or read back, and for a point whose voxel index does not fit 32 bits. */
class VoxelMerger
{
public:
    VoxelMerger(double voxel, std::string spill_prefix, std::size_t max_voxels);
    ~VoxelMerger();
    VoxelMerger(const VoxelMerger&) = delete;
    VoxelMerger& operator=(const VoxelMerger&) = delete;

    /** Adds a point (one that is not finite is ignored). */
    void add(double x, double y, double z, float intensity);
    /** Starts the next scan: voxels not added to since are the first to go to disk. */
    void nextScan();
    /** Every voxel's merged point, in the order of their indices (i, then j, then k), to
     *  `sink`; the run files are removed. Once only. Returns the number of voxels. */
    std::size_t finish(const std::function<void(const MergedPoint&)>& sink);

    /** The most voxels to hold so that the table holding them stays within `bytes` (its
     *  slots double when 7/8 full: the answer is 7/8 of the largest power of two of slots that
     *  fits); at least 2. Writing a run file takes up to half as much again, for a moment. */
    [[nodiscard]] static std::size_t voxelsWithin(std::size_t bytes);

    [[nodiscard]] double voxel() const { return voxel_; }
    [[nodiscard]] std::size_t pointsAdded() const { return points_; }
    /** Run files written so far. */
    [[nodiscard]] std::size_t spills() const { return spills_; }
    /** The most voxels held in memory at once. */
    [[nodiscard]] std::size_t peakVoxels() const { return peak_; }

    struct Impl;

private:
    /** Adds the points waiting in the batch. */
    void addPending();
    void spill();

    double voxel_;
    std::string prefix_;
    std::size_t max_voxels_;
    std::unique_ptr<Impl> impl_;
    std::vector<std::string> runs_;
    uint32_t scan_ = 0;
    std::size_t points_ = 0, peak_ = 0, spills_ = 0;
    bool finished_ = false;
};

}  // namespace hif::io
