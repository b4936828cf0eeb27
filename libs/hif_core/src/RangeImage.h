// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RangeImage.h
 * @brief  A scan's range image for the see-through and free-space tests: the nearest return in
 *         every cell of directions around the sensor (RangeImageLayout: from its sensor model).
 */
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "HeightCells.h"
#include "hif/PillarGrid.h"
#include "hif/SensorModel.h"
#include "hif/detail/PillarUpdate.h"

namespace hif::detail
{
/** A monotone stand-in for the azimuth of (x, y), in [0, 4) ("diamond angle"): one division
 *  instead of an atan2. Range-image columns are uniform in it. */
inline double pseudoAzimuth(double x, double y)
{
    const double s = std::abs(x) + std::abs(y);
    if (s == 0.0) return 0.0;
    const double a = y / s;
    return x >= 0.0 ? (y >= 0.0 ? a : 4.0 + a) : 2.0 - a;
}

/** Column of a range image laid out as `l` for a pseudo-azimuth. */
inline int imageCol(const RangeImageLayout& l, double paz)
{
    return std::min(l.cols - 1, static_cast<int>(paz * (l.cols / 4.0)));
}

/** Row of a range image laid out as `l` for tan(elevation), or -1 outside its rows. */
inline int imageRow(const RangeImageLayout& l, double tan_el)
{
    if (!(tan_el >= l.tan_min && tan_el < l.tan_max)) return -1;
    return std::min(l.rows - 1, static_cast<int>((tan_el - l.tan_min) / l.tan_res));
}

/** Cell of a range image laid out as `l` for (pseudo-azimuth, tan(elevation)), row by row
 *  (row * cols + col), or -1 outside its rows. */
inline int imageCell(const RangeImageLayout& l, double paz, double tan_el)
{
    const int r = imageRow(l, tan_el);
    return r < 0 ? -1 : r * l.cols + imageCol(l, paz);
}

/** The range-adaptive interval widths (Params::beam_spacing_deg) of a pillar at horizontal
 *  distance `d` from the sensor, for heights seen at elevation tangent `tan_el`, in height
 *  cells: heights whose gap is at most `gap` share an interval, which is widened by `pad`. */
struct IntervalWidths
{
    int32_t gap = 0;
    int32_t pad = 0;

    static IntervalWidths of(const PillarGrid& grid, double d, double tan_el)
    {
        return ofBeamGap(grid, d * grid.beamGapSlope(tan_el));  // between the beams around it
    }
    /** The widths where the sensor's beams are `beam_gap` metres apart. */
    static IntervalWidths ofBeamGap(const PillarGrid& grid, double beam_gap)
    {
        const Params& prm = grid.params();
        const double inv_res = 1.0 / grid.geometry().height_resolution;
        return {floorCells(std::max(prm.merge_gap, beam_gap) * inv_res + 1e-9),
                ceilCells(std::max(prm.interval_padding, 0.5 * beam_gap) * inv_res - 1e-9)};
    }

    /** The part of interval [lo, hi) within the padding: what was seen of it (its middle cell
     *  when the interval is no wider than twice its padding). */
    [[nodiscard]] Span core(int32_t lo, int32_t hi) const
    {
        const int64_t a = int64_t{lo} + pad, b = int64_t{hi} - pad;
        if (a < b) return {static_cast<int32_t>(a), static_cast<int32_t>(b)};
        const int64_t twice = int64_t{lo} + hi - 1;  // halved rounding down, at any sign
        const auto mid = static_cast<int32_t>(twice >= 0 ? twice / 2 : -((1 - twice) / 2));
        return {mid, mid + 1};
    }
};

/** The farthest range a range image's cell holds, metres: farther returns are kept as none
 *  (its centimetres would reach the "no return" value). */
constexpr float kMaxCellRange = 655.34f;

/** One cell of a scan's range image for insertion: the nearest return in it, with the
 *  tangent of its elevation (sensor frame), which places its beam more finely than the cell's
 *  row does. Four bytes, as a float range was: centimetres (up to 655.34 m) and the tangent
 *  in steps of 1/16384 (6 mm at 100 m; elevations within +-63 degrees). */
struct BeamReturn
{
    static constexpr uint16_t kNone = 0xFFFF;
    static constexpr double kTanStep = 1.0 / 16384.0;

    uint16_t range_cm = kNone;
    int16_t tan_q = -1;  ///< all bits set where no return, as range_cm: an image is a memset

    /** Metres; +inf where no return. */
    [[nodiscard]] float range() const
    {
        return range_cm == kNone ? std::numeric_limits<float>::infinity()
                                 : static_cast<float>(range_cm) * 0.01f;
    }
    [[nodiscard]] double tan() const { return tan_q * kTanStep; }
    /** A return at `range` metres with elevation tangent `tan_el`, rounded (none from
     *  kMaxCellRange on, as in the free-space test's images, nor for a NaN range). */
    static BeamReturn of(float range, float tan_el)
    {
        BeamReturn b;
        if (!(range < kMaxCellRange)) return b;  // also NaN
        b.range_cm = static_cast<uint16_t>(range * 100.0f + 0.5f);
        const float q =
            std::clamp(tan_el * static_cast<float>(1.0 / kTanStep), -32767.0f, 32767.0f);
        b.tan_q = static_cast<int16_t>(q + (q >= 0.0f ? 0.5f : -0.5f));  // rounded
        return b;
    }
    /** Keeps `b` (of()) when it is nearer than the cell's return. Its centimetres are
     *  x + 0.5 truncated (x >= 0), which is below an integer exactly when x + 0.5 is: the
     *  nearer of two returns rounded is the rounding of the nearer. */
    void keepNearer(const BeamReturn& b)
    {
        if (b.range_cm < range_cm) *this = b;
    }
};

/** Squared distance, along the middle of `row` of an image laid out as `l`, to a pillar's axis
 *  at horizontal distance `d`. */
inline double rowDist2(const RangeImageLayout& l, double d, int row)
{
    const double tan_el = l.tan_min + (row + 0.5) * l.tan_res;
    return d * d * (1.0 + tan_el * tan_el);
}

/** Whether a return at range `r` passed a pillar at squared distance `dist2` along its beam
 *  (rowDist2()): it lies farther by more than `margin`. */
inline bool passesBeyond(double r, double dist2, double margin)
{
    const double beyond = r - margin;
    return beyond > 0.0 && beyond * beyond > dist2;
}

/** Bit k of the result: whether the return of row row_lo + k of `column` (one column of an
 *  image laid out as `l`, k < n <= 64) passed a pillar at horizontal distance `d` by more than
 *  `margin` (passesBeyond()); 0 where no return. Four rows at a time with AVX when useAvx()
 *  (the same bits as one at a time). */
uint64_t passedRows(const RangeImageLayout& l, const BeamReturn* column, int row_lo, int n,
                    double d, double margin);

/** Where the sensor's next beam up or down a column of an image laid out as `l` (rows of half
 *  its median beam spacing, RangeImageLayout::forSensor()) lies farther than one and a half
 *  median spacings, how many rows to look along to reach it: for each row, entry 2 * row (down)
 *  and 2 * row + 1 (up), one and a half times the gap from the beam nearest the row to the next
 *  one that way, in rows; 0 where that gap is no wider than one and a half median spacings (or
 *  there is no next beam). `ring_tan`: the tangents of the beams' elevations, ascending (empty
 *  without rings: every entry 0). A sensor whose beams crowd near the horizon (a VLP-32C's a
 *  third of a degree apart there, up to 9 degrees at the bottom of its view) has its next beam
 *  several median spacings away at the ends of its view. */
std::vector<uint16_t> nextBeamRowsTable(const RangeImageLayout& l,
                                        const std::vector<double>& ring_tan);

/** Rows to look along from `row`, up (`dir` 1) or down (-1), for the sensor's next beam: `rows`
 *  (about one and a half median spacings), or more where nextBeamRowsTable()'s `table` (null:
 *  none) for an image of `image_rows` rows says the next beam lies farther. */
inline int nextBeamRows(const uint16_t* table, int image_rows, int rows, int row, int dir)
{
    if (!table || row < 0 || row >= image_rows) return rows;
    return std::max<int>(rows, table[2 * row + (dir > 0)]);
}

/** Column `c` of an image of `cols` columns, wrapped around the azimuth (one wrap without a
 *  division). */
inline int wrapCol(int c, int cols)
{
    if (c >= cols)
        c -= cols;
    else if (c < 0)
        c += cols;
    return c >= 0 && c < cols ? c : (c % cols + cols) % cols;
}

/** The index of the highest set bit of `m` (not 0). */
inline int highestBit(uint64_t m) { return 63 - __builtin_clzll(m); }

/** Cells of a block of buildReturnImage()'s `blocks` (the sky test of BeamGate looks this far
 *  aside). */
constexpr int kBlockCols = 8;

/** The see-through test of one pillar against a scan's range image (nearest return per cell,
 *  with its elevation): where did beams of the scan pass through heights [lo, hi) (height
 *  cells) of the pillar whose axis is base + up * z in the sensor frame? In the direction of
 *  the pillar's centre (and half_cols columns on each side), a return that lies farther than
 *  the pillar by more than `margin` passed through it, at the heights its beam crosses within
 *  the pillar (from `reach` before the pillar's axis to `reach` after); a return within
 *  `margin` of the pillar between those heights vetoes (something is there); a return nearer
 *  than that is occlusion, and a cell without a return is no evidence. */
struct BeamGate
{
    const RangeImageLayout* layout = nullptr;
    const BeamReturn* image = nullptr;
    Eigen::Vector3d base = Eigen::Vector3d::Zero();
    Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    double margin = 0.0;
    double res = 0.0;  ///< height cell, metres
    static constexpr int kMaxHalfCols = 1;
    int half_cols = 0;  ///< columns looked along on each side of the centre's (<= kMaxHalfCols)
    /** Half the pillar's extent along the beam through its centre, metres. */
    double reach = 0.0;
    /** passedCells(): two beams that passed, with no other return between them and elevation
     *  tangents at most this apart (neighbouring beams of the sensor), show the heights
     *  between them empty too; 0: each beam only its own. */
    double bridge_tan = 0.0;
    /** For widthsOf(): the grid (its interval widths). */
    const PillarGrid* grid = nullptr;
    /** The sensor's height in the world frame, metres (-up.base, given exactly). */
    double sensor_z = 0.0;
    /** Log-odds up to which an interval counts as seen once (p_empty_init and one hit), for
     *  skyFor() and floorTop(); -inf: a beam that returned nothing is never evidence (a
     *  sensor without rings, whose cells without a return may have had no beam), and the
     *  floor is the lowest interval alone. */
    float seen_once = -std::numeric_limits<float>::infinity();

    /** Whether beams of the sensor's rings that returned nothing above the horizon count as
     *  passing through an interval of log-odds `l`: only for one seen once. If it were still
     *  there, they would have returned from it, as a beam did before; a surface seen more than
     *  once that returns nothing now (glass, a dark car, foliage) keeps what it has. */
    [[nodiscard]] bool skyFor(float l) const { return l <= seen_once; }
    /** The blocks of buildReturnImage() for `image`: where a beam that returned nothing had
     *  neighbours that did. */
    const uint8_t* returned_blocks = nullptr;
    /** For floorTop(): how many height cells the ground may rise across the pillar (the
     *  steepest ground the map takes for ground, Params::ground_max_slope_deg, over its
     *  diagonal): a sighting of it that much thicker is still one sighting, where nothing
     *  touching goes on above it. */
    int32_t floor_slope_cells = 0;
    /** The axis (as `base`) through where in the pillar what stands above its ground was seen
     *  (Pillar::object_u, object_v), for the intervals above its floor that the map holds
     *  firmly (passedCells() with `object`), when `object_axis_set`. The gate reads the beams
     *  around one axis; through the centre of a 1 m pillar, they pass its free part beside a
     *  pole, a trunk or the corner of a box that stands off the centre, and would show it gone. */
    Eigen::Vector3d object_axis = Eigen::Vector3d::Zero();
    bool object_axis_set = false;

    /** Sets object_axis from pillar `pil` at `idx` of `geo` (unset where nothing above its
     *  ground was seen yet), for a sensor at `sensor` (world frame) whose frame
     *  `world_to_sensor` rotates to. */
    void setObjectAxis(const GridGeometry& geo, PillarIndex idx, const Pillar& pil,
                       const Eigen::Vector3d& sensor, const Eigen::Matrix3d& world_to_sensor)
    {
        object_axis_set = pil.object_weight != 0;
        if (!object_axis_set) return;
        const double x = geo.origin_x + (idx.m + Pillar::placeOf(pil.object_u)) * geo.pillar_size;
        const double y = geo.origin_y + (idx.n + Pillar::placeOf(pil.object_v)) * geo.pillar_size;
        object_axis =
            world_to_sensor * Eigen::Vector3d(x - sensor.x(), y - sensor.y(), -sensor.z());
    }

    /** The widths (IntervalWidths) of interval [lo, hi) of this pillar: those of its middle
     *  height at the pillar's distance. */
    [[nodiscard]] IntervalWidths widthsOf(int32_t lo, int32_t hi) const
    {
        // Horizontal distance to the axis: base without its component along the vertical.
        const double d = (base - up * up.dot(base)).norm();
        if (d == 0.0 || !grid) return {};
        const double mid = 0.5 * (static_cast<double>(lo) + hi) * res - sensor_z;  // above it
        return IntervalWidths::of(*grid, d, mid / d);
    }

    /** The last of the `n` intervals `iv` (the pillar's, ascending) that make its floor, for
     *  floorOrObject(): the lowest, and above it the next while each is a sliver of padding
     *  under the next (seen once, no wider than its padding, touching the next, which lies
     *  below the sensor). A later scan that saw the ground a little lower adds such a sliver
     *  under it, which would otherwise make the ground itself an object. Then on up through
     *  the touching intervals below the sensor that end within one sighting of the ground
     *  from the floor's bottom (twice the padding at the pillar's distance, and a cell; and
     *  floor_slope_cells more when the touching run ends there: sloped ground): the
     *  padding above the ground seen there, and the ground seen a few centimetres higher by
     *  another scan, whose log-odds differ. As objects, a beam skimming the ground across
     *  the pillar would show all of them gone, the ground seen in them with them; what
     *  stands on the ground reaches above a sighting of it. */
    [[nodiscard]] std::size_t floorTop(const Interval* iv, std::size_t n) const
    {
        std::size_t top = 0;
        while (top + 1 < n && iv[top].hi == iv[top + 1].lo && iv[top].logodds <= seen_once &&
               iv[top].hi - iv[top].lo <= widthsOf(iv[top].lo, iv[top].hi).pad &&
               iv[top + 1].hi * res <= sensor_z)
            ++top;
        if (n == 0) return top;
        int64_t sighting_top =
            int64_t{iv[0].lo} + 2 * int64_t{widthsOf(iv[0].lo, iv[0].hi).pad} + 1;
        // Ground rising across the pillar is seen a little thicker, by up to floor_slope_cells;
        // but only where the pillar's content ends there: what stands on the ground (a walker
        // whose feet no ring saw) goes on up through touching pieces.
        if (floor_slope_cells > 0)
        {
            std::size_t run = top;
            while (run + 1 < n && iv[run].hi == iv[run + 1].lo) ++run;
            if (iv[run].hi <= sighting_top + floor_slope_cells) sighting_top += floor_slope_cells;
        }
        while (top + 1 < n && iv[top].hi == iv[top + 1].lo && iv[top + 1].hi <= sighting_top &&
               iv[top + 1].hi * res <= sensor_z)
            ++top;
        return top;
    }

    /** What a beam must cross to show all of the piece [lo, hi) of interval `k` of `iv`
     *  (the pillar's intervals, ascending), for passedCells(). The pillar's floor (the
     *  ground, mostly), its intervals up to `top` (0: the lowest alone; floorTop()): beams
     *  reach it at grazing angles from above and pass through the padding around what was
     *  seen of it, so only a beam through what was seen (the whole floor's core) shows all of
     *  it gone, any other only the heights it crossed. An interval above the floor is an
     *  object: a beam through any part of it shows it gone. */
    [[nodiscard]] Span floorOrObject(const Interval* iv, std::size_t top, std::size_t k, int32_t lo,
                                     int32_t hi) const
    {
        if (k > top) return {lo, hi};
        const Span c = widthsOf(iv[0].lo, iv[top].hi).core(iv[0].lo, iv[top].hi);
        return {std::max(c.lo, lo), std::min(c.hi, hi)};
    }

    /** Whether any beam between those heights returned beyond the pillar (returns near it do
     *  not veto): some of the pillar's free space was seen empty. The heights within the
     *  pillar of the rows of the image where a beam did so (after the first such row, the
     *  beam toward its centre) go to `passed`: a row's band of elevations (half a beam
     *  spacing: a ring's row, or for a sensor without rings the beams near that elevation),
     *  not only the beam's own; but not where the beam met a surface that runs on into the
     *  pillar beside it (intoPillar()): it passed the pillar's free part only. */
    [[nodiscard]] bool seenEmpty(int32_t lo, int32_t hi, PassedCells& passed) const
    {
        Axis a;
        if (!axisOf(lo, hi, a)) return false;
        // From the top row down: beams above what stands in the pillar pass first; until one
        // has, every column's beam counts, then only the centre's is read. Rows are taken a
        // block at a time (passedRows()), the first ones in short blocks: a beam passes after
        // a few rows in most pillars.
        constexpr int kFirstBlock = 16;
        int run_top = -1;  // the top row of the run of rows that passed, walking down
        int row = a.row1;
        bool seen = false;  // a beam passed, whether or not it shows heights to record
        while (row >= a.row0 && run_top < 0)
        {
            const int block_lo = std::max(a.row0, row - kFirstBlock + 1);
            const int n = row - block_lo + 1;
            uint64_t m = 0;
            for (int k = 0; k < a.ncols; ++k)
            {
                const uint64_t b =
                    passedRows(*layout, columnOf(a.cols[k]), block_lo, n, a.d, margin);
                seen = seen || b != 0;
                m |= withoutSurfacesInto(a, lo, a.cols[k], block_lo, b);
            }
            if (m != 0) run_top = block_lo + highestBit(m);
            row = m != 0 ? run_top - 1 : block_lo - 1;
        }
        if (run_top < 0) return seen;
        // The rest of the centre's column, down the image (a column is contiguous): each run
        // of rows that passed goes to `passed` (the heights its rows cross, rowsCells()).
        const BeamReturn* column = columnOf(a.cols[a.ncols / 2]);
        auto endRun = [&](int bottom)
        {
            const Span b = rowsCells(bottom, run_top + 1, a);
            passed.add(b.lo, b.hi);
            run_top = -1;
        };
        while (row >= a.row0)
        {
            const int block_lo = std::max(a.row0, row - 63);
            const uint64_t m = withoutSurfacesInto(
                a, lo, a.cols[a.ncols / 2], block_lo,
                passedRows(*layout, column, block_lo, row - block_lo + 1, a.d, margin));
            // Bits [0, i] of the block are left to walk, from the top: the next row where a
            // run ends (in a run) or starts (between runs).
            for (int i = row - block_lo; i >= 0;)
            {
                const uint64_t below = i == 63 ? ~uint64_t{0} : (uint64_t{1} << (i + 1)) - 1;
                const uint64_t next = (run_top >= 0 ? ~m : m) & below;
                if (next == 0) break;
                const int j = highestBit(next);
                if (run_top >= 0)
                    endRun(block_lo + j + 1);
                else
                    run_top = block_lo + j;
                i = j - 1;
            }
            row = block_lo - 1;
        }
        if (run_top >= 0) endRun(a.row0);
        return true;
    }

    /** Whether seenEmpty() leaves out of `passed` the beams that met a surface running on
     *  into the pillar (intoPillar()): for a sensor without rings, whose beams near a pillar
     *  a facade cuts may miss the facade's strip of it. A ring that passes the pillar's free
     *  part goes on to hit that strip at the same heights in the same sweep, unless something
     *  hides it, so the pillar is seen there as it is seen passed (measured with rings: SA
     *  +0.00 to +0.13, DA -0.07 to +0.15, for 10-20 % more insertion time; doc/sensors.md). */
    bool surfaces_into = false;

    /** Where the scan saw a surface within Params::pillar_edge_margin of the pillar's edge,
     *  in the pillars beside it (ScanBuckets::edge_spans), sorted and disjoint: passedCells()
     *  leaves those heights out. */
    const Span* edge_spans = nullptr;
    std::size_t edge_count = 0;

    /** The height cells of [lo, hi) that beams passed through, as sorted disjoint spans in
     *  `out` (cleared first): the cells each such beam crosses within the pillar, and those
     *  between two neighbouring beams that both passed (bridge_tan); all of [lo, hi) when a
     *  beam passed through `core` (floorOrObject()). Empty when none passed, or when a return
     *  between those heights lies near the pillar (something is there: a veto). Without the
     *  heights of a surface seen at the pillar's edge (edge_spans): it may go on into the
     *  pillar where the beams toward its centre did not go. With `object` (an interval above
     *  the floor, floorOrObject(), that the map holds firmly), the beams are those around
     *  object_axis. */
    void passedCells(int32_t lo, int32_t hi, Span core, std::vector<Span>& out, bool sky = false,
                     bool object = false) const
    {
        beamsThrough(lo, hi, core, out, sky, object);
        if (edge_count != 0 && !out.empty()) withoutEdges(out);
    }

    /** `spans` (sorted and disjoint) without the heights of edge_spans. */
    void withoutEdges(std::vector<Span>& spans) const;

    /** passedCells() before the edges' heights are taken out. */
    void beamsThrough(int32_t lo, int32_t hi, Span core, std::vector<Span>& out, bool sky,
                      bool object = false) const
    {
        out.clear();
        Axis a;
        if (!axisOf(lo, hi, a, object)) return;
        if (sky) a.horizon_tan = up.z() != 0.0 ? -(up.x() * a.hx + up.y() * a.hy) / up.z() : 0.0;
        if (core.lo <= lo && core.hi >= hi)
        {
            // An object: any beam through it shows all of it gone, unless one is vetoed; with
            // none through it, neighbouring beams on both sides may still bridge across it.
            const Crossing c = objectCrossing(a, lo, hi, sky);
            if (c == Crossing::Passed) out.assign(1, Span{lo, hi});
            if (c != Crossing::None || !passesAround(a, sky)) return;
        }
        const RangeImageLayout& l = *layout;
        // From one beam spacing above [lo, hi) to one below (a beam outside can bridge to one
        // inside): the heights each beam crossed, and between neighbours; a return near the
        // pillar between lo and hi vetoes, a beam through the core shows all of it gone.
        const int extra = static_cast<int>(std::ceil(bridge_tan / l.tan_res));
        const int top = std::min(l.rows - 1, a.row1 + extra);
        const int bottom = std::max(0, a.row0 - extra);
        bool have_prev = false, broken = false, core_passed = false;
        bool passed_own = false, blocked_own = false;
        double prev_tan = 0.0;
        Span prev{0, 0};
        for (int row = top; row >= bottom; --row)
        {
            const bool own = row >= a.row0 && row <= a.row1;
            if (core_passed && !own) break;  // all that is left to look for is a veto
            for (int k = 0; k < a.ncols; ++k)
            {
                const BeamReturn ret = returnAt(row, a.cols[k], a, sky);
                const Beam beam = beamOf(ret, a, row);
                if (beam == Beam::None) continue;  // no return: no evidence
                if (beam == Beam::Passed)
                {
                    passed_own = passed_own || own;
                    if (core_passed) continue;
                    const Span c = crossedCells(ret.tan(), a);
                    if (own && core.lo < core.hi && c.lo < core.hi && core.lo < c.hi)
                        core_passed = true;
                    if (have_prev && !broken && std::abs(prev_tan - ret.tan()) <= bridge_tan)
                        out.push_back({std::min(c.lo, prev.lo), std::max(c.hi, prev.hi)});
                    else
                        out.push_back(c);
                    have_prev = true;
                    broken = false;
                    prev = c;
                    prev_tan = ret.tan();
                }
                else if (own && beam == Beam::Near)
                {
                    out.clear();  // something is there
                    return;
                }
                else
                {
                    broken = true;  // a return near or in front: unknown behind it
                    blocked_own = blocked_own || own;
                }
            }
        }
        if (core_passed)
        {
            out.assign(1, Span{lo, hi});
            return;
        }
        // No beam passed between lo and hi, and one in front of the pillar there: what beams
        // above or below crossed of it is not seen through it.
        if (!passed_own && blocked_own)
        {
            out.clear();
            return;
        }
        // Clipped to [lo, hi), sorted and joined.
        std::size_t w = 0;
        for (const Span& c : out)
        {
            const Span x{std::max(c.lo, lo), std::min(c.hi, hi)};
            if (x.lo < x.hi) out[w++] = x;
        }
        out.resize(w);
        std::sort(out.begin(), out.end(), [](const Span& x, const Span& y) { return x.lo < y.lo; });
        w = 0;
        for (std::size_t k = 1; k < out.size(); ++k)
        {
            if (out[k].lo <= out[w].hi)
                out[w].hi = std::max(out[w].hi, out[k].hi);
            else
                out[++w] = out[k];
        }
        if (!out.empty()) out.resize(w + 1);
    }

    /** Whether the floor [lo, hi) the scan saw in this pillar is ground (Params::
     *  ground_max_slope_deg): every return of the scan within the pillar at those heights (and
     *  at least one) lies on a surface that runs on, nearly level, both ways along its
     *  direction. The next beam above returned farther: at most `slope_tan` per metre higher
     *  or lower (the ground goes on), or beyond the pillar and not lower (something rises
     *  there: a fence, a bank, bushes); and the beams below it, one after the other down to the
     *  lowest that returned, each returned nearer, at most `slope_tan` per metre (plus `step`
     *  metres, a kerb, below the first) lower or higher than the one above it. Ground is
     *  sampled that way, at grazing angles; whatever stands on it breaks the run: its face
     *  returns at nearly the same distance as its foot (the beam above a car's lowest point
     *  hits the car, within the pillar), and a roof is separated from the ground below by the
     *  face under it. A beam that returned nothing where the run continues leaves the question
     *  open: not ground. Needs `runs`. */
    [[nodiscard]] bool onGround(int32_t lo, int32_t hi, double slope_tan, double step) const
    {
        Axis a;
        if (!runs || !axisOf(lo, hi, a)) return false;
        const RangeImageLayout& l = *layout;
        bool any = false;
        // The pillar's extent along the beams reaches a row beyond its axis's on each side.
        for (int row = std::max(0, a.row0 - 1); row <= std::min(l.rows - 1, a.row1 + 1); ++row)
            for (int k = 0; k < a.ncols; ++k)
            {
                const Found p = at(row, a.cols[k]);
                if (!p.found) continue;
                const double z = (sensor_z + p.place.up) / res;
                if (std::abs(p.place.along - a.d) > reach || z < lo || z >= hi) continue;
                const Found above = nextReturn(p, 1);
                const Found below = nextReturn(p, -1);
                if (above.found ? !(levelWith(above.place, p.place, slope_tan, 0.0) ||
                                    (above.place.along - p.place.along > reach &&
                                     above.place.up >= p.place.up))
                                : !groundOutOfReachAbove(p, below, step))
                    return false;
                if (below.found ? !levelWith(p.place, below.place, slope_tan, 0.0) ||
                                      !runDownIsLevel(below, slope_tan, step)
                                : gapBelow(p))
                    return false;
                any = true;
            }
        return any;
    }

    /** For onGround(): per cell of the image, whether the run of returns from the cell's down
     *  to the column's lowest is level (runDownIsLevel()), found once per scan: the cell's
     *  value is (generation << 2) | 1 (level) or 2 (broken); another generation is unknown.
     *  A byte a cell (a 6-bit generation): half the cache misses of two bytes, measured.
     *  Atomic: the gates of one scan run on several threads, and find the same values. */
    std::atomic<uint8_t>* runs = nullptr;
    uint8_t generation = 0;
    /** For onGround(): the range of the scan's farthest return, metres (0: unknown). */
    float farthest_return = 0.0f;
    /** For onGround(): where the sensor's next beam up or down a column lies farther than
     *  bridge_tan (nextBeamRowsTable(), GridAccess::nextBeamRows(); null: nowhere). */
    const uint16_t* next_beam_rows = nullptr;

private:
    /** Where the pillar's axis lies in the image between two heights. */
    struct Axis
    {
        double d = 0.0;             ///< horizontal distance, metres
        double hx = 0.0, hy = 0.0;  ///< its direction
        int row0 = 0, row1 = 0;     ///< rows of the lowest and highest height
        /** Elevation tangent of the world's horizon here: for returnAt()'s sky, found only
         *  where that is asked (passedCells()). */
        double horizon_tan = 0.0;
        /** The columns looked along: the centre's, and half_cols on each side (wrapped). */
        int cols[2 * kMaxHalfCols + 1] = {};
        int ncols = 0;
    };

    /** With `object`, along object_axis where it is set. */
    [[nodiscard]] bool axisOf(int32_t lo, int32_t hi, Axis& a, bool object = false) const
    {
        const RangeImageLayout& l = *layout;
        const Eigen::Vector3d& through = object && object_axis_set ? object_axis : base;
        const Eigen::Vector3d p = through + up * (lo * res);
        const double hi_z = through.z() + up.z() * (hi * res);
        a.d = std::sqrt(p.x() * p.x() + p.y() * p.y());
        if (a.d == 0.0) return false;
        a.hx = p.x() / a.d;
        a.hy = p.y() / a.d;
        a.row0 = imageRow(l, std::max(p.z() / a.d, l.tan_min));
        a.row1 = imageRow(l, std::min(hi_z / a.d, l.tan_max - 1e-12));
        if (a.row0 < 0 || a.row1 < 0) return false;
        const int col = imageCol(l, pseudoAzimuth(p.x(), p.y()));
        a.ncols = 0;
        for (int dc = -half_cols; dc <= half_cols; ++dc)
        {
            const int c = col + dc;  // wrapped around the azimuth
            a.cols[a.ncols++] = wrapCol(c, l.cols);
        }
        return true;
    }

    /** Whether the beam of cell (row, col), which passed the pillar (passesBeyond()) and
     *  returned within the pillar's extent beyond it, met a surface that runs on into the
     *  pillar: along its row on either side (within `span` columns: the pillar's half width
     *  and one more; in each, its row or the one above or below), the returns that follow on
     *  one surface (each within the pillar's reach of the one before in range), and the
     *  straight line through the beam's return (`x`: pointAt(row, col), horizontal()) and the
     *  farthest of them, in the horizontal plane, crosses the pillar (within its half
     *  diagonal, `margin`, of its centre). A facade met at grazing incidence behind the free
     *  part of a pillar it cuts: the beam shows that part empty, not the strip of the pillar
     *  the facade stands in, which this scan may not have hit there. A surface facing the beam
     *  (a car's back, a walker) runs across it beyond the pillar; a return on the other side
     *  of an edge lies on another surface. */
    [[nodiscard]] bool intoPillar(int row, int col, int span, const Eigen::Vector3d& x) const
    {
        const RangeImageLayout& l = *layout;
        const double r = cellAt(row, col).range();
        for (const int side : {-1, 1})
        {
            // The farthest return of the surface along the row: one after the other, each
            // within the pillar's reach of the one before (a longer baseline than the next
            // return's, for the surface's direction).
            double prev = r;
            int far = -1, far_row = row;
            for (int k = 1; k <= span; ++k)
            {
                // In the column, the return of its row or of the row above or below nearest
                // the last one in range: a non-repetitive pattern crosses the rows
                // obliquely, so its next sample on the surface may lie a row up or down.
                const int c = wrapCol(col + side * k, l.cols);
                float best = std::numeric_limits<float>::infinity();
                int best_row = -1;
                for (int rr = std::max(0, row - 1); rr <= std::min(l.rows - 1, row + 1); ++rr)
                {
                    const BeamReturn& nb = cellAt(rr, c);
                    if (nb.range_cm != BeamReturn::kNone &&
                        std::abs(nb.range() - prev) < std::abs(best - prev))
                        best = nb.range(), best_row = rr;
                }
                if (best_row < 0) continue;
                if (std::abs(best - prev) > reach) break;  // another surface
                prev = best;
                far = c;
                far_row = best_row;
            }
            if (far < 0) continue;
            const Eigen::Vector3d along = horizontal(pointAt(far_row, far)) - x;
            const double len = along.norm();
            if (len > 0.0 && along.cross(horizontal(base) - x).norm() <= margin * len) return true;
        }
        return false;
    }

    /** `m`, bits of passedRows() for the rows from block_lo of column `col`, without the
     *  beams that met a surface running on into the pillar (intoPillar()). Only those that
     *  returned within the pillar's extent beyond it and not below its lowest content `lo`
     *  (a height cell) are asked. */
    [[nodiscard]] uint64_t withoutSurfacesInto(const Axis& a, int32_t lo, int col, int block_lo,
                                               uint64_t m) const
    {
        if (!surfaces_into || m == 0) return m;
        int span = 0;  // found for the first beam asked
        const BeamReturn* column = columnOf(col);
        const double floor_up = lo * res - sensor_z;  // the pillar's lowest, above the sensor
        for (uint64_t left = m; left != 0; left &= left - 1)
        {
            const int b = __builtin_ctzll(left);
            const int row = block_lo + b;
            // Returned beyond the pillar's extent (passesBeyond() by 2 reach more), or below
            // its lowest content (the ground beyond it, mostly): not asked.
            if (passesBeyond(column[row].range(), rowDist2(*layout, a.d, row),
                             margin + 2.0 * reach))
                continue;
            const Eigen::Vector3d p = pointAt(row, col);
            if (p.dot(up) < floor_up) continue;
            // The pillar's half width in columns at its distance, and one more (a column spans
            // at least 4 / cols radians of azimuth: pseudoAzimuth()); at most a quarter turn,
            // for a pillar around the sensor.
            if (span == 0)
                span = static_cast<int>(std::ceil(std::atan2(reach, a.d) * layout->cols / 4.0)) + 1;
            if (intoPillar(row, col, span, horizontal(p))) m &= ~(uint64_t{1} << b);
        }
        return m;
    }

    /** `v` without its component along `up`. */
    [[nodiscard]] Eigen::Vector3d horizontal(const Eigen::Vector3d& v) const
    {
        return v - v.dot(up) * up;
    }

    /** What the rows of `a` say of heights [lo, hi) of the pillar: a beam passed through
     *  them, a return near the pillar vetoes, or neither (and whether a return in front of it
     *  blocks the view). */
    enum class Crossing : uint8_t
    {
        Passed,
        Vetoed,
        Blocked,
        None
    };
    [[nodiscard]] Crossing objectCrossing(const Axis& a, int32_t lo, int32_t hi, bool sky) const
    {
        bool passed = false, blocked = false;
        for (int row = a.row1; row >= a.row0; --row)
        {
            if (passed)
            {
                if (anyNear(row, a)) return Crossing::Vetoed;
                continue;
            }
            for (int k = 0; k < a.ncols; ++k)
            {
                const BeamReturn ret = returnAt(row, a.cols[k], a, sky);
                const Beam beam = beamOf(ret, a, row);
                if (beam == Beam::Passed)
                {
                    const Span c = crossedCells(ret.tan(), a);
                    passed = passed || (c.lo < hi && lo < c.hi);
                }
                else if (beam == Beam::Near)
                    return Crossing::Vetoed;  // something is there
                else if (beam == Beam::Front)
                    blocked = true;
            }
        }
        return passed ? Crossing::Passed : (blocked ? Crossing::Blocked : Crossing::None);
    }

    /** Whether beams within one beam spacing (bridge_tan) both above and below the rows of
     *  `a` passed the pillar: only then can two of them bridge across those rows. */
    [[nodiscard]] bool passesAround(const Axis& a, bool sky) const
    {
        if (bridge_tan == 0.0) return false;
        const RangeImageLayout& l = *layout;
        const int extra = static_cast<int>(std::ceil(bridge_tan / l.tan_res));
        auto anyPass = [&](int from, int to)
        {
            for (int row = std::max(0, from); row <= std::min(l.rows - 1, to); ++row)
            {
                for (int k = 0; k < a.ncols; ++k)
                    if (beamOf(returnAt(row, a.cols[k], a, sky), a, row) == Beam::Passed)
                        return true;
            }
            return false;
        };
        return anyPass(a.row1 + 1, a.row1 + extra) && anyPass(a.row0 - extra, a.row0 - 1);
    }

    /** The return in cell (row, col); with `sky`, a cell without one whose row holds a return
     *  within a few columns (a ring of the sensor fired there) and looks above the horizon
     *  reads as a beam that passed far, with that ring's elevation. */
    [[nodiscard]] BeamReturn returnAt(int row, int col, const Axis& a, bool sky) const
    {
        // A ring's beam that returned nothing: the row holds a return within a few columns.
        const BeamReturn& ret = cellAt(row, col);
        if (!sky || ret.range_cm != BeamReturn::kNone) return ret;
        const RangeImageLayout& l = *layout;
        if (l.tan_min + (row + 0.5) * l.tan_res <= a.horizon_tan) return ret;  // below it
        // No return in this block of cells nor the next ones: open sky, or no ring here
        // (blocks run along the rows, buildReturnImage()).
        const std::size_t cell = static_cast<std::size_t>(row) * l.cols + col;
        const std::size_t b = cell / kBlockCols, last = l.cells() / kBlockCols;
        if (!returned_blocks[b] && !returned_blocks[b < last ? b + 1 : 0] &&
            !returned_blocks[b > 0 ? b - 1 : last])
            return ret;
        for (int dc = 1; dc <= kBlockCols; ++dc)
            for (const int c : {wrapCol(col + dc, l.cols), wrapCol(col - dc, l.cols)})
                if (cellAt(row, c).range_cm != BeamReturn::kNone)
                {
                    BeamReturn far = cellAt(row, c);
                    far.range_cm = BeamReturn::kNone - 1;  // 655.34 m: beyond any pillar
                    return far;
                }
        return ret;
    }

    /** A return placed along its column's direction: horizontal distance and height above
     *  the sensor (world frame), metres; with its cell. */
    struct Place
    {
        double along = 0.0;
        double up = 0.0;
    };
    struct Found
    {
        Place place;
        int row = 0, col = 0;
        bool found = false;
    };
    /** The return in cell (row, col), placed, or none. */
    [[nodiscard]] Found at(int row, int col) const
    {
        if (cellAt(row, col).range_cm == BeamReturn::kNone) return {};
        const Eigen::Vector3d p = pointAt(row, col);
        const double h = p.dot(up);
        return {{std::sqrt(std::max(0.0, p.squaredNorm() - h * h)), h}, row, col, true};
    }
    /** The return in cell (row, col) (there must be one) in the sensor frame, along its
     *  column's azimuth. */
    [[nodiscard]] Eigen::Vector3d pointAt(int row, int col) const
    {
        const BeamReturn& ret = cellAt(row, col);
        // The column's azimuth from its pseudo-azimuth (pseudoAzimuth() inverted).
        const double paz = (col + 0.5) * (4.0 / layout->cols);
        const double q = paz - std::floor(paz);
        double x = 0.0, y = 0.0;
        if (paz < 1.0)
            x = 1.0 - q, y = q;
        else if (paz < 2.0)
            x = -q, y = 1.0 - q;
        else if (paz < 3.0)
            x = q - 1.0, y = -q;
        else
            x = q, y = q - 1.0;
        const double t = ret.tan();
        const double s = ret.range() / std::sqrt((1.0 + t * t) * (x * x + y * y));
        return {s * x, s * y, s * std::sqrt(x * x + y * y) * t};
    }
    /** Rows of the image within bridge_tan (one and a half median beam spacings). */
    [[nodiscard]] int bridgeRows() const
    {
        return std::max(1, static_cast<int>(std::ceil(bridge_tan / layout->tan_res)));
    }
    /** The next beam's return above (dir 1) or below (dir -1) `from`: the first within 1.5
     *  vertical spacings (bridge_tan; or of the gap to the sensor's next beam where its beams
     *  lie farther apart, nextBeamRows()), in its column or a neighbouring one (a beam's
     *  returns fill every other column). */
    [[nodiscard]] Found nextReturn(const Found& from, int dir) const
    {
        const RangeImageLayout& l = *layout;
        const int rows = nextBeamRows(next_beam_rows, l.rows, bridgeRows(), from.row, dir);
        const int last = std::clamp(from.row + dir * rows, 0, l.rows - 1);
        for (int r = from.row + dir; dir > 0 ? r <= last : r >= last; r += dir)
            for (const int dc : {0, -1, 1})
            {
                const Found f = at(r, wrapCol(from.col + dc, l.cols));
                if (f.found) return f;
            }
        return {};
    }
    /** With no next beam's return below `from`: whether its column holds one lower down (a
     *  beam that returned nothing within the run), rather than `from` being the lowest. */
    [[nodiscard]] bool gapBelow(const Found& from) const
    {
        const int rows = nextBeamRows(next_beam_rows, layout->rows, bridgeRows(), from.row, -1);
        for (int r = std::min(from.row - rows - 1, layout->rows - 1); r >= 0; --r)
            if (cellAt(r, from.col).range_cm != BeamReturn::kNone) return true;
        return false;
    }
    /** Whether the returns from `from` down, one beam after the other, each lie nearer than the
     *  one above and within `slope_tan` per metre plus `step` of it, down to the column's
     *  lowest (no gap). Every cell walked shares the answer, which `runs` keeps. */
    [[nodiscard]] bool runDownIsLevel(Found from, double slope_tan, double step) const
    {
        const auto cell = [&](const Found& f)
        { return static_cast<std::size_t>(f.col) * layout->rows + f.row; };
        constexpr int kKept = 64;  // cells remembered per walk (the rest are walked again)
        std::size_t walked[kKept];
        int n = 0;
        bool level = false;
        for (;;)
        {
            const uint8_t v = runs[cell(from)].load(std::memory_order_relaxed);
            if (v >> 2 == generation)
            {
                level = (v & 3) == 1;
                break;
            }
            if (n < kKept) walked[n++] = cell(from);
            const Found below = nextReturn(from, -1);
            if (!below.found)
            {
                level = !gapBelow(from);
                break;
            }
            if (!levelWith(from.place, below.place, slope_tan, step)) break;
            from = below;
        }
        const auto v = static_cast<uint8_t>((generation << 2) | (level ? 1 : 2));
        for (int k = 0; k < n; ++k) runs[walked[k]].store(v, std::memory_order_relaxed);
        return level;
    }
    /** `far` lies farther than `near` and at most `slope_tan` per metre plus `step` metres
     *  above or below it. */
    static bool levelWith(const Place& far, const Place& near, double slope_tan, double step)
    {
        const double run = far.along - near.along;
        return run > 0.0 && std::abs(far.up - near.up) <= run * slope_tan + step;
    }
    /** For onGround(), when the beam above `p` returned nothing: whether that is what ground
     *  running on would give. `p` lies on the line of the two returns below it (within `step`),
     *  and the next beam up would meet that line, carried on beyond `p`, farther than the
     *  scan's farthest return (`farthest_return`; or never meet it): a sensor's last rings on
     *  the ground, whose next beam up lands beyond its reach. The next beam up is one gap of
     *  the sensor's beams (PillarGrid::beamGapSlope()) above `p`'s. Something standing on the
     *  ground is off that line by more than a kerb. */
    [[nodiscard]] bool groundOutOfReachAbove(const Found& p, const Found& below, double step) const
    {
        if (!below.found || !grid || farthest_return <= 0.0f) return false;
        const Found below2 = nextReturn(below, -1);
        if (!below2.found) return false;
        const double run1 = p.place.along - below.place.along;
        const double run2 = below.place.along - below2.place.along;
        if (!(run1 > 0.0 && run2 > 0.0)) return false;
        const double s2 = (below.place.up - below2.place.up) / run2;  // the ground's slope
        if (std::abs(p.place.up - (below.place.up + s2 * run1)) > step) return false;
        const double s1 = (p.place.up - below.place.up) / run1;  // on towards p and beyond
        const double t_p = p.place.up / p.place.along;
        const double t_up = t_p + grid->beamGapSlope(t_p);  // the next beam up, about
        // Above the line at p (by a beam spacing); it meets the line farther on only if it
        // falls faster, where t_up * D = p.up + s1 * (D - p.along).
        if (t_up >= s1) return true;
        const double d = (p.place.up - s1 * p.place.along) / (t_up - s1);
        return d * std::sqrt(1.0 + t_up * t_up) > farthest_return;
    }

    /** The image is stored column by column (buildReturnImage()): the walks along a
     *  pillar's axis read one column down, a cache line holding 16 rows. */
    [[nodiscard]] const BeamReturn* columnOf(int col) const
    {
        return image + static_cast<std::size_t>(col) * layout->rows;
    }
    [[nodiscard]] const BeamReturn& cellAt(int row, int col) const { return columnOf(col)[row]; }

    /** Whether a return of `row` lies within the margin of the pillar. */
    [[nodiscard]] bool anyNear(int row, const Axis& a) const
    {
        for (int k = 0; k < a.ncols; ++k)
            if (beamOf(cellAt(row, a.cols[k]), a, row) == Beam::Near) return true;
        return false;
    }

    /** What the return of a cell of `row` says of the pillar (compared with the distance to
     *  its axis along the row, squared: no square root): nothing (no return), passed (farther
     *  than the pillar by more than the margin), near (within the margin of it: something is
     *  there), or in front of it. */
    enum class Beam : uint8_t
    {
        None,
        Passed,
        Near,
        Front
    };
    [[nodiscard]] Beam beamOf(const BeamReturn& ret, const Axis& a, int row) const
    {
        if (ret.range_cm == BeamReturn::kNone) return Beam::None;
        const double r = ret.range();
        const double dist2 = rowDist2(*layout, a.d, row);
        if (passesBeyond(r, dist2, margin)) return Beam::Passed;
        const double near = r + margin;
        return near * near > dist2 ? Beam::Near : Beam::Front;
    }

    /** The cells the elevations of rows [row0, row1) of the image cross within the pillar,
     *  [lo, hi) (not clipped to any interval). */
    [[nodiscard]] Span rowsCells(int row0, int row1, const Axis& a) const
    {
        const Span b = crossedCells(layout->tan_min + row0 * layout->tan_res, a);
        const Span t = crossedCells(layout->tan_min + row1 * layout->tan_res, a);
        return {std::min(b.lo, t.lo), std::max(b.hi, t.hi)};
    }

    /** The cells a beam of elevation tangent `tan_el` crosses within the pillar, [lo, hi)
     *  (not clipped to any interval). */
    [[nodiscard]] Span crossedCells(double tan_el, const Axis& a) const
    {
        // World height (metres) along the beam at horizontal distance s: sensor_z + s * slope.
        const double slope = up.x() * a.hx + up.y() * a.hy + up.z() * tan_el;
        const double inv_res = 1.0 / res;
        const double za = (sensor_z + (a.d - reach) * slope) * inv_res;
        const double zb = (sensor_z + (a.d + reach) * slope) * inv_res;
        constexpr double kMin = std::numeric_limits<int32_t>::min();
        constexpr double kMax = std::numeric_limits<int32_t>::max();
        const double c0 = std::clamp(std::floor(std::min(za, zb)), kMin, kMax - 1.0);
        const double c1 = std::clamp(std::floor(std::max(za, zb)) + 1.0, c0 + 1.0, kMax);
        return {static_cast<int32_t>(c0), static_cast<int32_t>(c1)};
    }
};

/** BeamGate::bridge_tan for the grid's sensor: neighbouring beams are at most 1.5 vertical
 *  spacings apart (the sensor model's, else Params::beam_spacing_deg; 0 when that is 0). */
inline double neighbourBeamsTan(const PillarGrid& grid)
{
    const auto& model = grid.sensorModel();
    const double deg = model ? model->vertical_spacing_deg : grid.params().beam_spacing_deg;
    return std::tan(1.5 * deg * M_PI / 180.0);
}

/** BeamGate::seen_once for the grid: p_empty_init and one hit, in log-odds, when its sensor
 *  model has rings (else -inf). */
inline float seenOnce(const PillarGrid& grid)
{
    const auto& model = grid.sensorModel();
    if (!model || !model->hasRings()) return -std::numeric_limits<float>::infinity();
    const LogOddsModel m = LogOddsModel::of(grid);
    return m.empty_init + m.hit + 1e-4f;
}

/** BeamGate::floor_slope_cells for a grid of geometry `geo`: the rise of ground at the ground
 *  rule's steepest slope (`slope_tan`, LogOddsModel::ground_slope_tan) across a pillar's
 *  diagonal, in whole height cells (0 when the ground rule is off). */
inline int32_t groundSlopeCells(const GridGeometry& geo, double slope_tan)
{
    const double rise = std::sqrt(2.0) * geo.pillar_size * slope_tan;
    return static_cast<int32_t>(std::ceil(rise / geo.height_resolution - 1e-9));
}

/** Half the extent, along the ray from the sensor through its centre, of a pillar of side
 *  `size` whose centre lies (dx, dy) from the sensor (world frame): size / 2 over the larger of
 *  |cos|, |sin| of the ray's azimuth. */
inline double pillarReach(double size, double dx, double dy)
{
    const double m = std::max(std::abs(dx), std::abs(dy));
    return m > 0.0 ? 0.5 * size * std::sqrt(dx * dx + dy * dy) / m : 0.5 * size;
}

/** Fills `img` (layout `l`, stored column by column: cell (row, col) at col * rows + row, so
 *  that BeamGate's walks down a column stay in a few cache lines) with the nearest return of
 *  `points` (sensor frame) in every cell, BeamReturn{} (no return) where none falls, and
 *  `blocks` with a byte per block of kBlockCols cells of the image flattened row by row
 *  (row * cols + col): 1 where any return fell in it. Returns the
 *  range of the scan's farthest return in the image, metres (0 for none).
 *  Four points at a time with AVX when useAvx() (the same bits as one at a time). */
float buildReturnImage(const RangeImageLayout& l, const PointsView& points,
                       std::vector<BeamReturn>& img, std::vector<uint8_t>& blocks);

/** "No return" in a range image in centimetres. */
constexpr uint16_t kNoReturnCm = 0xFFFF;

/** buildRangeImage() in centimetres (rounded; kNoReturnCm where no return, or beyond 655 m),
 *  row by row, and in `blocks` (as buildReturnImage()'s) where a point fell. */
void buildRangeImageCm(const RangeImageLayout& l, const PointsView& points,
                       std::vector<uint16_t>& img, std::vector<uint8_t>& blocks);

}  // namespace hif::detail
