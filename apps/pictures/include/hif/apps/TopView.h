// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   TopView.h
 * @brief  A bird's-eye picture of a cleaned map (OpenCV): kept points in grey by height, removed
 *         points in red and, with ground truth, missed moving points and wrongly removed static
 *         ones in their own colours; a legend and a scale bar. The picture shows the map's main
 *         area, whatever stray points or poses far from it the input has, and its size is
 *         bounded.
 */
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace hif::apps
{
/** A block of a coarse grid over the ground (index bx, by) and how much it holds. */
struct WeightedBlock
{
    int64_t bx = 0, by = 0;
    std::size_t weight = 0;
};

/** Which blocks form the main area: the group, heaviest in total, of blocks linked to one
 *  another through blocks at most `reach` blocks apart (in x and y). The map of a drive is one
 *  such group; a stray point or a pose far off makes a small group of its own, left out.
 *  Returns a flag per block. */
[[nodiscard]] std::vector<bool> mainArea(const std::vector<WeightedBlock>& blocks, int64_t reach);

/** Blocks farther apart than this (metres) of empty ground belong to different areas. */
constexpr double kAreaLinkMetres = 100.0;

class TopView
{
public:
    /** What became of a point. */
    enum Outcome : uint8_t
    {
        kKept = 0,               ///< kept (static, or not known)
        kRemoved = 1,            ///< removed (moving, or not known)
        kMissedMoving = 2,       ///< a moving point that was kept (ground truth given)
        kWronglyRemoved = 3,     ///< a static point that was removed (ground truth given)
        kRemovedUnlabelled = 4,  ///< removed, unlabelled in the ground truth (not scored)
    };

    /** The colour of each outcome (red, green, blue), as the picture's legend shows it (kept
     *  points are drawn in grey by height there, light grey elsewhere). */
    static constexpr uint8_t kRgb[5][3] = {
        {200, 200, 200}, {230, 40, 40}, {255, 215, 0}, {0, 160, 255}, {190, 90, 230}};

    /** The longest side of a picture, pixels: a larger area is drawn coarser. */
    static constexpr int kMaxSide = 8000;

    /** Cells of `resolution` metres, kept in tiles where points fell (memory follows the area
     *  covered, not its bounding box); coarser (twice, as often as needed) when they would
     *  need more than `max_cells`. */
    explicit TopView(double resolution = 0.2, std::size_t max_cells = std::size_t{1} << 23);

    /** Before the first point: the cells' size such that the longer side of [x0, x1) x [y0, y1)
     *  (the main area of a map known beforehand) spans about `pixels` cells (5 cm at the
     *  finest), so that the picture needs no scaling up. Ignored after the first point. */
    void cover(double x0, double y0, double x1, double y1, int pixels = 1300);

    void add(double x, double y, float z, Outcome outcome)
    {
        const double fx = x * inv_res_, fy = y * inv_res_;
        // Most points fall in the tile of the one before (a scan is swept in order).
        const double dx = fx - last_x0_, dy = fy - last_y0_;
        if (dx >= 0 && dx < double(kTileSide) && dy >= 0 && dy < double(kTileSide))
        {
            // The offsets are exact but near the tile's far edge (then the last cell).
            const auto lx = std::min<std::size_t>(static_cast<std::size_t>(dx), kTileSide - 1);
            const auto ly = std::min<std::size_t>(static_cast<std::size_t>(dy), kTileSide - 1);
            mark(*last_, (ly << kTileBits) | lx, z, outcome);
            return;
        }
        addToTile(fx, fy, z, outcome);
    }

    /** The picture as written. */
    struct Picture
    {
        int width = 0, height = 0;
        /** Points left out: apart from the main area (see mainArea()), or too far from the
         *  origin to draw at all. */
        std::size_t points_outside = 0;
        std::size_t points = 0;  ///< every point added (NaN excepted)
        double cell_metres = 0;  ///< what one cell of the picture covers
    };

    /** Writes the picture (PNG) of the main area of what was added, at least `min_width` pixels
     *  wide where kMaxSide allows, with `title` above; `with_truth` puts the two ground-truth
     *  outcomes in the legend. Throws std::runtime_error naming the file when nothing was added
     *  or it cannot be written. */
    Picture write(const std::string& file, const std::string& title, bool with_truth,
                  int min_width = 1200) const;

    [[nodiscard]] double resolution() const { return res_; }
    /** No point to draw was added (none, or only points too far from the origin). */
    [[nodiscard]] bool empty() const { return tiles_.empty(); }

private:
    static constexpr int kTileBits = 7;  ///< tiles of 128 x 128 cells
    static constexpr int64_t kTileSide = int64_t{1} << kTileBits;
    static constexpr int64_t kTileMask = kTileSide - 1;
    static constexpr std::size_t kTileCells = std::size_t{1} << (2 * kTileBits);
    static constexpr double kMaxCell = 137438953472.0;  ///< 2^37 cells: tile indices fit int32

    struct Tile
    {
        int64_t tx = 0, ty = 0;
        std::vector<float> top;      ///< highest kept point of each cell, NaN for none
        std::vector<uint8_t> marks;  ///< bit per outcome other than kept
        std::size_t points = 0;
    };

    static void mark(Tile& t, std::size_t i, float z, Outcome outcome)
    {
        if (outcome == kKept)
        {
            if (!(z <= t.top[i])) t.top[i] = z;  // top starts NaN
        }
        else
            t.marks[i] |= static_cast<uint8_t>(1u << outcome);
        ++t.points;
    }
    /** add() for a point outside the last tile: finds or makes its tile (cell (floor(fx),
     *  floor(fy))), which becomes the last one. */
    void addToTile(double fx, double fy, float z, Outcome outcome);
    /** The tile, made if needed; nullptr if making it coarsened the cells instead. */
    Tile* findOrAdd(int64_t tx, int64_t ty);
    Tile* setLast(Tile* t)
    {
        last_ = t;
        last_x0_ = t ? double(t->tx * kTileSide) : std::numeric_limits<double>::quiet_NaN();
        last_y0_ = t ? double(t->ty * kTileSide) : std::numeric_limits<double>::quiet_NaN();
        return t;
    }
    /** fn(tile, cell index in it, global cell x, y) for each cell that holds something, in
     *  the tiles flagged in `in`. */
    template <typename Fn>
    void forEachCell(const std::vector<bool>& in, Fn&& fn) const;
    /** Twice the cell size: every 2 x 2 cells become one. */
    void coarsen();

    double res_, inv_res_;
    std::size_t max_cells_;
    std::vector<Tile> tiles_;
    std::unordered_map<uint64_t, std::size_t> index_;  ///< packed (tx, ty) -> tiles_ index
    Tile* last_ = nullptr;
    /** The last tile's first cell (in cells, as doubles); NaN while there is none. */
    double last_x0_ = std::numeric_limits<double>::quiet_NaN();
    double last_y0_ = std::numeric_limits<double>::quiet_NaN();
    std::size_t far_ = 0;
};

}  // namespace hif::apps
