// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FreeSpaceTest.h
 * @brief  The free-space test (Params::free_space_window) as one object: the scans that may
 *         show that a scan's points were not there, and which of them judge it.
 */
#pragma once

#include <Eigen/Geometry>
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "hif/SensorModel.h"

namespace hif
{
class PillarGrid;
struct PointsView;
struct Params;

/** The scans of the free-space test, in the order they were taken, each kept as its pose and
 *  its range image (the nearest return in each cell of directions around its sensor, laid out
 *  for the map's sensor model, in centimetres; about 1 MB for a 64-beam LiDAR).
 *
 *  PillarGrid::classify() with a test judges a scan by the scans the test holds, but itself:
 *  when the test holds the scan classified (the same points at the same pose), by those within
 *  free_space_window scans of it on either side; otherwise by all of them (a scan newer than
 *  every one held).
 *
 *  Online (Params::online: SLAM, each scan judged with the past only), add each scan once it
 *  is inserted (add(points, pose, grid): its image is then the one the insertion built) and
 *  classify it right away: the test keeps it and the free_space_window scans before it.
 *  Offline (all scans inserted before any is classified), add the scans again in their order
 *  and classify scan k once scan k + free_space_window is added (or the last one is): the
 *  test keeps 2 free_space_window + 1. capacityFor() gives those. */
class FreeSpaceTest
{
public:
    /** "No return" in an image. */
    static constexpr uint16_t kNoReturn = 0xFFFF;
    /** Points of a scan that its fingerprint() reads (all of a smaller scan). */
    static constexpr std::size_t kFingerprintPoints = 4096;

    /** A scan's range image: rows x cols cells, centimetres (up to 655.34 m), kNoReturn where
     *  no return. Kept by blocks of kBlockCols cells of a row, only those with a return: a
     *  scan's returns fill 35-45 % of them (its beams every other row, rows of a beam partly
     *  empty), so the image takes about half the memory of all its cells. */
    class Image
    {
    public:
        static constexpr uint32_t kBlockCols = 32;

        /** Takes the cells of `dense` (rows x cols, row-major). Throws std::invalid_argument if
         *  its size is not rows x cols. */
        void assign(int rows, int cols, const std::vector<uint16_t>& dense);
        /** The cell at (row, col), which must lie in the image. */
        [[nodiscard]] uint16_t at(int row, int col) const { return cells_[index(row, col)]; }
        /** Asks the CPU to fetch the cell at (row, col) ahead of at(), which must lie in the
         *  image (a hint: no effect on any result). */
        void prefetch(int row, int col) const
        {
            __builtin_prefetch(&cells_[index(row, col)]);  // GCC and Clang
        }
        [[nodiscard]] int rows() const { return rows_; }
        [[nodiscard]] int cols() const { return cols_; }
        /** rows() x cols(). */
        [[nodiscard]] std::size_t cells() const
        {
            return static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_);
        }
        /** Calls f(cell, value) for every cell with a return, in row-major order (cell = row x
         *  cols() + col). */
        template <typename F>
        void forEachReturn(F&& f) const
        {
            for (int r = 0; r < rows_; ++r)
                for (std::size_t b = 0; b < blocks_per_row_; ++b)
                {
                    const uint32_t at = blocks_[static_cast<std::size_t>(r) * blocks_per_row_ + b];
                    if (at == kNoBlock) continue;  // no return in it
                    const std::size_t c0 = b * kBlockCols;
                    const std::size_t n = std::min<std::size_t>(kBlockCols, cols_ - c0);
                    for (std::size_t c = 0; c < n; ++c)
                        if (cells_[at + c] != kNoReturn)
                            f(static_cast<std::size_t>(r) * cols_ + c0 + c, cells_[at + c]);
                }
        }
        /** Heap memory held. */
        [[nodiscard]] std::size_t memoryBytes() const
        {
            return blocks_.capacity() * sizeof(uint32_t) + cells_.capacity() * sizeof(uint16_t);
        }
        /** The same cells. */
        friend bool operator==(const Image& a, const Image& b);

    private:
        friend class FreeSpaceTest;
        /** assign() from any source: `returned(row, col0, n)` is false only where none of
         *  the cells [col0, col0 + n) of the row holds a return; `cell(row, col)` is a cell.
         *  Blocks are read row by row, or with `by_band` (a source stored column by column)
         *  a band of kBlockCols columns at a time, row after row. */
        template <typename Returned, typename Cell>
        void assignFrom(int rows, int cols, bool by_band, Returned returned, Cell cell);
        /** Where the cell at (row, col) is in cells_. */
        [[nodiscard]] std::size_t index(int row, int col) const
        {
            const auto c = static_cast<uint32_t>(col);
            return blocks_[static_cast<std::size_t>(row) * blocks_per_row_ + c / kBlockCols] +
                   c % kBlockCols;
        }
        /** Where every block without a return starts: cells_ begins with one block of
         *  kNoReturn, so at() needs no branch. */
        static constexpr uint32_t kNoBlock = 0;
        int rows_ = 0, cols_ = 0;
        std::size_t blocks_per_row_ = 0;
        std::vector<uint32_t> blocks_;  ///< per block, where its cells start in cells_
        std::vector<uint16_t> cells_;   ///< kBlockCols per block kept, after the empty one
    };

    /** One scan of the test. */
    struct Scan
    {
        /** fingerprint() of its points and pose: which scan it is. */
        uint64_t fingerprint = 0;
        Eigen::Isometry3d sensor_to_world = Eigen::Isometry3d::Identity();
        /** How `image` is laid out (from the map's sensor model). */
        RangeImageLayout layout;
        /** layout.rows x layout.cols. */
        Image image;
    };

    /** Makes scans for add(Scan) as add(points, sensor_to_world, layout) makes them, away from
     *  the test: on another thread while the test judges (hif-clean's second pass builds the
     *  next scan's image while it classifies). It keeps its buffers from one scan to the
     *  next; one maker per thread. */
    class ScanMaker
    {
    public:
        /** The scan of `points` (sensor frame) at `sensor_to_world`, its range image laid out
         *  as `layout`. */
        [[nodiscard]] Scan make(const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
                                const RangeImageLayout& layout);
        /** Heap memory of its buffers. */
        [[nodiscard]] std::size_t memoryBytes() const;

    private:
        friend class FreeSpaceTest;
        /** make() with the points' fingerprint (pointsFingerprint()) found already, the image
         *  in the memory of `storage`. */
        Scan makeWith(uint64_t points_fingerprint, const PointsView& points,
                      const Eigen::Isometry3d& sensor_to_world, const RangeImageLayout& layout,
                      Image storage);

        std::vector<uint16_t> dense_;  ///< all cells of the image being built
        std::vector<uint8_t> blocks_;  ///< where its points fell (blocks of cells)
    };

    /** A test that keeps the newest `capacity` scans added (0: none; the test is off). */
    explicit FreeSpaceTest(std::size_t capacity = 0) : capacity_(capacity) {}

    /** The capacity for `params`: 0 without the test (free_space_window 0); online, the scan
     *  classified and the free_space_window before it; offline, free_space_window on each
     *  side of it. */
    [[nodiscard]] static std::size_t capacityFor(const Params& params);
    [[nodiscard]] std::size_t capacity() const { return capacity_; }
    /** Changes the capacity, dropping the oldest scans beyond it. */
    void setCapacity(std::size_t capacity);

    /** Adds the scan taken after every one added before: its points (sensor frame), placed in
     *  the world by `sensor_to_world`, and its range image laid out as `layout`. The oldest
     *  scan beyond the capacity is dropped. */
    void add(const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
             const RangeImageLayout& layout);
    /** The same for the scan just inserted into `grid` (online), laid out as
     *  grid.imageLayout(): its range image is taken from the one the insertion built for the
     *  see-through gate (the same cells, converted once), when the grid's last insertion built
     *  one for these points (the same pointsFingerprint()) in that layout; otherwise it is
     *  built from the points, as above. */
    void add(const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
             const PillarGrid& grid);
    /** Adds a scan as it was kept (scans() of another test: deserialization), or as a
     *  ScanMaker made it. Throws std::invalid_argument if its image does not have its layout's
     *  rows and columns. */
    void add(Scan scan);

    /** Position in scans() of the scan with these points at this pose, if the test holds it. */
    [[nodiscard]] std::optional<std::size_t> find(const PointsView& points,
                                                  const Eigen::Isometry3d& sensor_to_world) const;
    /** Identifies a scan: a 64-bit digest of its pose, its point count and the coordinates
     *  (their bits) of kFingerprintPoints of its points spread over it, the same on every run
     *  and machine. */
    [[nodiscard]] static uint64_t fingerprint(const PointsView& points,
                                              const Eigen::Isometry3d& sensor_to_world);
    /** The part of fingerprint() that reads the points (their count and coordinates). */
    [[nodiscard]] static uint64_t pointsFingerprint(const PointsView& points);

    /** Oldest first. */
    [[nodiscard]] const std::deque<Scan>& scans() const { return scans_; }
    [[nodiscard]] bool empty() const { return scans_.empty(); }
    [[nodiscard]] std::size_t size() const { return scans_.size(); }
    void clear() { scans_.clear(); }
    /** Heap memory of the images kept (and of one spare for the next scan). */
    [[nodiscard]] std::size_t memoryBytes() const;

    /** Same capacity and scans. */
    friend bool operator==(const FreeSpaceTest& a, const FreeSpaceTest& b);

private:
    void dropBeyondCapacity();
    /** fingerprint() from pointsFingerprint(). */
    static uint64_t withPose(uint64_t points_fingerprint, const Eigen::Isometry3d& sensor_to_world);
    /** add(points, pose, layout) with the points' fingerprint found already. */
    void addFromPoints(uint64_t points_fingerprint, const PointsView& points,
                       const Eigen::Isometry3d& sensor_to_world, const RangeImageLayout& layout);
    /** A scan with the fingerprint of these points at this pose, and its layout; its image
     *  (to be assigned) in the memory of `storage`. */
    static Scan scanHeader(uint64_t points_fingerprint, const Eigen::Isometry3d& sensor_to_world,
                           const RangeImageLayout& layout, Image storage);
    /** Keeps `scan` as the newest, dropping the oldest beyond the capacity. */
    void keep(Scan scan);

    std::size_t capacity_ = 0;
    std::deque<Scan> scans_;
    Image spare_;      ///< the image of the last scan dropped, reused
    ScanMaker maker_;  ///< for the scans added by their points
};

}  // namespace hif
