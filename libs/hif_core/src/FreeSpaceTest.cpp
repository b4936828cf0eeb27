// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FreeSpaceTest.cpp
 * @brief  The scans kept for the free-space test.
 */
#include "hif/FreeSpaceTest.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>
#include <utility>

#include "GridAccess.h"
#include "RangeImage.h"
#include "hif/Params.h"
#include "hif/PillarGrid.h"

namespace hif
{
static_assert(FreeSpaceTest::kNoReturn == detail::kNoReturnCm);

std::size_t FreeSpaceTest::capacityFor(const Params& p)
{
    const std::size_t w = p.free_space_window;
    if (w == 0) return 0;
    return p.online ? w + 1 : 2 * w + 1;
}

void FreeSpaceTest::setCapacity(std::size_t capacity)
{
    capacity_ = capacity;
    dropBeyondCapacity();
}

void FreeSpaceTest::dropBeyondCapacity()
{
    while (scans_.size() > capacity_)
    {
        spare_ = std::move(scans_.front().image);
        scans_.pop_front();
    }
}

template <typename Returned, typename Cell>
void FreeSpaceTest::Image::assignFrom(int rows, int cols, bool by_band, Returned returned,
                                      Cell cell)
{
    rows_ = rows;
    cols_ = cols;
    blocks_per_row_ = (static_cast<std::size_t>(cols) + kBlockCols - 1) / kBlockCols;
    blocks_.assign(static_cast<std::size_t>(rows) * blocks_per_row_, kNoBlock);
    // Every block (row r, columns c0 to c0 + n), in the order of the source's storage.
    auto forBlocks = [&](auto&& f)
    {
        const auto bands = static_cast<int>(blocks_per_row_);
        auto visit = [&](int r, int b)
        {
            const int c0 = b * static_cast<int>(kBlockCols);
            f(r, c0, std::min(static_cast<int>(kBlockCols), cols - c0),
              blocks_[static_cast<std::size_t>(r) * blocks_per_row_ + b]);
        };
        if (by_band)
            for (int b = 0; b < bands; ++b)
                for (int r = 0; r < rows; ++r) visit(r, b);
        else
            for (int r = 0; r < rows; ++r)
                for (int b = 0; b < bands; ++b) visit(r, b);
    };
    // The blocks kept, then their cells (allocated once, at their size), after the empty one.
    std::size_t kept = 1;
    forBlocks(
        [&](int r, int c0, int n, uint32_t& at)
        {
            if (!returned(r, c0, n)) return;
            bool any = false;
            for (int c = c0; c < c0 + n && !any; ++c) any = cell(r, c) != kNoReturn;
            if (!any) return;
            at = static_cast<uint32_t>(kept * kBlockCols);
            ++kept;
        });
    cells_.assign(kept * kBlockCols, kNoReturn);
    forBlocks(
        [&](int r, int c0, int n, uint32_t at)
        {
            if (at == kNoBlock) return;
            for (int c = 0; c < n; ++c) cells_[at + static_cast<uint32_t>(c)] = cell(r, c0 + c);
        });
}

void FreeSpaceTest::Image::assign(int rows, int cols, const std::vector<uint16_t>& dense)
{
    if (rows < 0 || cols < 0 ||
        dense.size() != static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols))
        throw std::invalid_argument("hif::FreeSpaceTest::Image: " + std::to_string(dense.size()) +
                                    " cells for " + std::to_string(rows) + " rows of " +
                                    std::to_string(cols));
    const auto width = static_cast<std::size_t>(cols);
    assignFrom(
        rows, cols, false, [](int, int, int) { return true; },
        [&](int r, int c) { return dense[static_cast<std::size_t>(r) * width + c]; });
}

bool operator==(const FreeSpaceTest::Image& a, const FreeSpaceTest::Image& b)
{
    if (a.rows_ != b.rows_ || a.cols_ != b.cols_) return false;
    for (int r = 0; r < a.rows_; ++r)
        for (int c = 0; c < a.cols_; ++c)
            if (a.at(r, c) != b.at(r, c)) return false;
    return true;
}

namespace
{
/** For Image::assignFrom(): whether a point fell in cells [c0, c0 + n) of row r of an image of
 *  `cols` columns, from `blocks` (per detail::kBlockCols cells of the image flattened row by
 *  row, as the range images mark them). */
auto anyPointIn(const uint8_t* blocks, int cols)
{
    return [blocks, cols](int r, int c0, int n)
    {
        const std::size_t first = static_cast<std::size_t>(r) * static_cast<std::size_t>(cols) + c0;
        for (std::size_t b = first / detail::kBlockCols; b <= (first + n - 1) / detail::kBlockCols;
             ++b)
            if (blocks[b]) return true;
        return false;
    };
}
}  // namespace

FreeSpaceTest::Scan FreeSpaceTest::scanHeader(uint64_t points_fingerprint,
                                              const Eigen::Isometry3d& sensor_to_world,
                                              const RangeImageLayout& layout, Image storage)
{
    Scan s;
    s.fingerprint = withPose(points_fingerprint, sensor_to_world);
    s.sensor_to_world = sensor_to_world;
    s.layout = layout;
    s.image = std::move(storage);
    return s;
}

void FreeSpaceTest::keep(Scan scan)
{
    scans_.push_back(std::move(scan));
    dropBeyondCapacity();
}

void FreeSpaceTest::add(const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
                        const RangeImageLayout& layout)
{
    if (capacity_ == 0) return;
    addFromPoints(pointsFingerprint(points), points, sensor_to_world, layout);
}

void FreeSpaceTest::addFromPoints(uint64_t points_fingerprint, const PointsView& points,
                                  const Eigen::Isometry3d& sensor_to_world,
                                  const RangeImageLayout& layout)
{
    keep(maker_.makeWith(points_fingerprint, points, sensor_to_world, layout,
                         std::exchange(spare_, {})));
}

FreeSpaceTest::Scan FreeSpaceTest::ScanMaker::make(const PointsView& points,
                                                   const Eigen::Isometry3d& sensor_to_world,
                                                   const RangeImageLayout& layout)
{
    return makeWith(pointsFingerprint(points), points, sensor_to_world, layout, {});
}

FreeSpaceTest::Scan FreeSpaceTest::ScanMaker::makeWith(uint64_t points_fingerprint,
                                                       const PointsView& points,
                                                       const Eigen::Isometry3d& sensor_to_world,
                                                       const RangeImageLayout& layout,
                                                       Image storage)
{
    Scan s = scanHeader(points_fingerprint, sensor_to_world, layout, std::move(storage));
    detail::buildRangeImageCm(layout, points, dense_, blocks_);
    const auto cols = static_cast<std::size_t>(layout.cols);
    s.image.assignFrom(layout.rows, layout.cols, false, anyPointIn(blocks_.data(), layout.cols),
                       [&](int r, int c)
                       { return dense_[static_cast<std::size_t>(r) * cols + c]; });
    return s;
}

std::size_t FreeSpaceTest::ScanMaker::memoryBytes() const
{
    return dense_.capacity() * sizeof(uint16_t) + blocks_.capacity();
}

void FreeSpaceTest::add(const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
                        const PillarGrid& grid)
{
    if (capacity_ == 0) return;
    const RangeImageLayout& layout = grid.imageLayout();
    const detail::Workspace& ws = detail::GridAccess::workspace(grid);
    const uint64_t f = pointsFingerprint(points);
    if (ws.range_image_points != f || !(ws.range_image_layout == layout) ||
        ws.range_image.size() != layout.cells() ||
        ws.returned_blocks.size() != layout.cells() / detail::kBlockCols + 1)
    {
        addFromPoints(f, points, sensor_to_world, layout);
        return;
    }
    // The insertion's image holds the same cells (the same nearest return, the same
    // centimetres: BeamReturn::of()), column by column, and marks the blocks of cells (along
    // the rows) where a point fell: only those are read.
    const auto rows = static_cast<std::size_t>(layout.rows);
    const detail::BeamReturn* cells = ws.range_image.data();
    Scan s = scanHeader(f, sensor_to_world, layout, std::exchange(spare_, {}));
    s.image.assignFrom(
        layout.rows, layout.cols, true, anyPointIn(ws.returned_blocks.data(), layout.cols),
        [&](int r, int c) { return cells[static_cast<std::size_t>(c) * rows + r].range_cm; });
    keep(std::move(s));
}

void FreeSpaceTest::add(Scan scan)
{
    if (scan.image.rows() != scan.layout.rows || scan.image.cols() != scan.layout.cols)
        throw std::invalid_argument(
            "hif::FreeSpaceTest::add: an image of " + std::to_string(scan.image.rows()) + " x " +
            std::to_string(scan.image.cols()) + " cells for a layout of " +
            std::to_string(scan.layout.rows) + " x " + std::to_string(scan.layout.cols));
    if (capacity_ == 0) return;
    keep(std::move(scan));
}

namespace
{
/** splitmix64's finalizer: every input bit reaches every output bit. */
uint64_t mix(uint64_t x)
{
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

template <typename T>
uint64_t bitsOf(T v)
{
    static_assert(sizeof(T) <= sizeof(uint64_t));
    uint64_t b = 0;
    std::memcpy(&b, &v, sizeof v);
    return b;
}
}  // namespace

uint64_t FreeSpaceTest::withPose(uint64_t points_fingerprint, const Eigen::Isometry3d& T)
{
    uint64_t h = points_fingerprint;
    const Eigen::Matrix4d& m = T.matrix();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) h = mix(h ^ bitsOf(m(r, c)));
    return h;
}

uint64_t FreeSpaceTest::pointsFingerprint(const PointsView& pts)
{
    // The count and about 4,000 points spread over the scan (every point would cost 0.6 ms a
    // scan of 120,000): two scans of a sequence never share all of them.
    uint64_t h = mix(pts.size);
    const std::size_t stride = std::max<std::size_t>(1, pts.size / kFingerprintPoints);
    for (std::size_t i = 0; i < pts.size; i += stride)
        h = mix(h ^ (bitsOf(pts.x[i]) | bitsOf(pts.y[i]) << 32)) ^ bitsOf(pts.z[i]);
    return h;
}

uint64_t FreeSpaceTest::fingerprint(const PointsView& pts, const Eigen::Isometry3d& T)
{
    return withPose(pointsFingerprint(pts), T);
}

std::optional<std::size_t> FreeSpaceTest::find(const PointsView& points,
                                               const Eigen::Isometry3d& sensor_to_world) const
{
    if (scans_.empty()) return std::nullopt;
    const uint64_t f = fingerprint(points, sensor_to_world);
    // Newest first: online, the scan classified is the one just added.
    for (std::size_t k = scans_.size(); k-- > 0;)
        if (scans_[k].fingerprint == f) return k;
    return std::nullopt;
}

std::size_t FreeSpaceTest::memoryBytes() const
{
    std::size_t bytes = spare_.memoryBytes() + maker_.memoryBytes();
    for (const Scan& s : scans_) bytes += sizeof(Scan) + s.image.memoryBytes();
    return bytes;
}

bool operator==(const FreeSpaceTest& a, const FreeSpaceTest& b)
{
    if (a.capacity_ != b.capacity_ || a.scans_.size() != b.scans_.size()) return false;
    for (std::size_t k = 0; k < a.scans_.size(); ++k)
    {
        const FreeSpaceTest::Scan &x = a.scans_[k], &y = b.scans_[k];
        if (x.fingerprint != y.fingerprint ||
            x.sensor_to_world.matrix() != y.sensor_to_world.matrix() || !(x.layout == y.layout) ||
            !(x.image == y.image))
            return false;
    }
    return true;
}

}  // namespace hif
