// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FreeSpace.cpp
 * @brief  The free-space test: was a point of this scan seen through by other scans?
 */
#include "FreeSpace.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "GridAccess.h"
#include "Parallel.h"
#include "RangeImage.h"

namespace hif::detail
{
namespace
{
/** What one other scan says about one point. */
enum class View : uint8_t
{
    None,      ///< no beam near the point's direction, or one that stopped before it
    Occupied,  ///< a return near the point
    Vetoed,    ///< the beam toward it returned clearly beyond, but another one near it
    Free       ///< the beam toward it returned clearly beyond, and none near it
};

/** The test's scans that may judge the classified scan, with what a test needs. */
struct Judge
{
    std::size_t pos;    ///< in FreeSpaceTest::scans()
    Eigen::Vector3d t;  ///< sensor position, world frame
    Eigen::Matrix3d Rt;
    const FreeSpaceTest::Image* image;  ///< centimetres
    const RangeImageLayout* layout;
    /** Where the sensor's next beam up or down a column lies farther than one and a half
     *  median spacings (nextBeamRowsTable(); null: nowhere), for nextInColumn(). */
    const uint16_t* next_beam_rows;
    double baseline = 0.0;  ///< distance to the classified scan's sensor

    /** Scan `s`, at position `pos` in FreeSpaceTest::scans(), of a sensor whose next beams
     *  lie as `next_beam_rows` says. */
    static Judge of(const FreeSpaceTest::Scan& s, std::size_t pos, const uint16_t* next_beam_rows)
    {
        return {pos,
                s.sensor_to_world.translation(),
                s.sensor_to_world.linear().transpose(),
                &s.image,
                &s.layout,
                next_beam_rows};
    }

    /** World point `p` in this scan's sensor frame. */
    [[nodiscard]] Eigen::Vector3d toSensor(const Eigen::Vector3d& p) const { return Rt * (p - t); }

    /** Range of the nearest return in cell (r, c), metres; +inf for none. */
    [[nodiscard]] float at(int r, int c) const
    {
        const uint16_t v = image->at(r, c);
        return v == FreeSpaceTest::kNoReturn ? std::numeric_limits<float>::infinity()
                                             : static_cast<float>(v) * 0.01f;
    }
};

/** Where world point `p` lies in scan `j`'s range image: its cell and its distance from the
 *  sensor. None outside the image's elevations (or at the sensor). */
struct ImageCell
{
    int r, c;
    double d;
    bool upper;  ///< in the upper half of its row
};
std::optional<ImageCell> cellAt(const RangeImageLayout& l, const Eigen::Vector3d& q);
std::optional<ImageCell> cellOf(const Judge& j, const Eigen::Vector3d& p)
{
    return cellAt(*j.layout, j.toSensor(p));
}
/** cellOf() for `q`, a point in the judge's sensor frame (`l`, its image's layout). */
std::optional<ImageCell> cellAt(const RangeImageLayout& l, const Eigen::Vector3d& q)
{
    const double rxy = std::sqrt(q.x() * q.x() + q.y() * q.y());
    if (rxy == 0.0) return std::nullopt;
    const double tan_el = q.z() / rxy;
    if (!(tan_el >= l.tan_min && tan_el < l.tan_max)) return std::nullopt;
    const double row = (tan_el - l.tan_min) / l.tan_res;
    const int r = std::min(l.rows - 1, static_cast<int>(row));
    return ImageCell{
        r, std::min(l.cols - 1, static_cast<int>(pseudoAzimuth(q.x(), q.y()) * (l.cols / 4.0))),
        std::sqrt(rxy * rxy + q.z() * q.z()), row - r >= 0.5};
}

/** The range margin of the test at distance d from a judge: base + per_m * d, metres
 *  (Params::free_space_margin, free_space_margin_per_m). */
struct RangeMargin
{
    double base;
    double per_m;

    [[nodiscard]] double at(double d) const { return base + per_m * d; }
};

/** Whether scan `j`'s beams toward world point `p` (in its `cell`), none of which returned
 *  (look(): no return in the cell or the eight around it), passed it into open sky: `p` lies
 *  above the scan's sensor, and in the rows of `cell` and beside it the scan's beams returned
 *  from beyond `p` (by more than the margin) within `half_width` metres of it to one side or
 *  the other at its distance. Those rings were firing there and reached that far; had something
 *  stood at `p`, they would have returned from it. Below the sensor the ground returns them. */
bool skyBeyond(const Judge& j, const Eigen::Vector3d& p, const ImageCell& cell,
               const RangeMargin& margin, double half_width)
{
    if (!((p - j.t).z() > 0.0)) return false;
    const RangeImageLayout& l = *j.layout;
    const double beyond = cell.d + margin.at(cell.d);
    const int span = std::min(
        l.cols / 2, static_cast<int>(std::ceil(half_width / cell.d / (2.0 * M_PI / l.cols))));
    for (int dc = 1; dc <= span; ++dc)
        for (const int c : {wrapCol(cell.c + dc, l.cols), wrapCol(cell.c - dc, l.cols)})
            for (int r = std::max(0, cell.r - 1); r <= std::min(l.rows - 1, cell.r + 1); ++r)
                if (const float f = j.at(r, c); std::isfinite(f) && f > beyond) return true;
    return false;
}

/** What one scan saw at a point, and with which beam. */
struct Look
{
    View view;
    float range;  ///< of the beam through the point (that of its cell, else the nearest one)
    /** The row of the image that beam lies in: the point's own, or one above (greater) or
     *  below it; -1 for beams that passed into open sky (skyBeyond()), which returned nothing. */
    int row;
};
/** Where the surface of a point goes on in the image of the scan it was seen in: whether the
 *  next beam up its column, and the next one down, returned on it (surfaceAround()). */
struct SurfaceAround
{
    bool up = true;
    bool down = true;
};
/** What scan `j` saw at a world point in its `cell`: from the beam of that cell, else (none
 *  there, unless `own_beam_only`) from the nearest one around it. With `sky` (the point, in the
 *  world frame), where none around it returned, Free if they passed into open sky
 *  (skyBeyond(), within `sky_half_width` metres). */
Look look(const Judge& j, const ImageCell& cell, const RangeMargin& margin,
          bool own_beam_only = false, const Eigen::Vector3d* sky = nullptr,
          double sky_half_width = 0.0)
{
    const int r = cell.r, c = cell.c;
    const double d = cell.d;
    const RangeImageLayout& l = *j.layout;
    const double m = margin.at(d);
    // The beam through the point: that of its own cell, else the nearest one around it.
    const float own = j.at(r, c);
    if (own <= d + m) return {own > d - m ? View::Occupied : View::None, own, r};  // or occluded
    if (own_beam_only && !std::isfinite(own)) return {View::None, own, r};
    float e = own;
    int row = r;
    bool near = false;
    int best = std::numeric_limits<int>::max();
    const int cols[3] = {wrapCol(c - 1, l.cols), c, wrapCol(c + 1, l.cols)};
    for (int dr = -1; dr <= 1 && !(near && std::isfinite(own)); ++dr)
    {
        const int rr = r + dr;
        if (rr < 0 || rr >= l.rows) continue;
        for (int dc = -1; dc <= 1; ++dc)
        {
            if (dr == 0 && dc == 0) continue;  // own: beyond the margin, or no return
            const float f = j.at(rr, cols[dc + 1]);
            if (!std::isfinite(f)) continue;
            near = near || (f > d - m && f <= d + m);
            const int dist = dr * dr + dc * dc;
            if (!std::isfinite(own) && (dist < best || (dist == best && f > e)))
            {
                best = dist;
                e = f;
                row = rr;
            }
        }
    }
    if (!std::isfinite(e))  // no beam near the point's direction: into open sky, or unknown
    {
        if (sky && skyBeyond(j, *sky, cell, margin, sky_half_width)) return {View::Free, e, -1};
        return {View::None, e, row};
    }
    if (e <= d + m) return {e > d - m ? View::Occupied : View::None, e, row};
    return {near ? View::Vetoed : View::Free, e, row};  // passed, unless something is near it
}

/** Where a beam toward a world point in `cell` returned (`range`, +inf: nothing), relative
 *  to the point: the return's range minus the point's (negative: nearer), with the margin at
 *  that distance. None when the beam returned nothing. */
struct BeamOffset
{
    double offset;
    double margin;
};
std::optional<BeamOffset> offsetOf(float range, const ImageCell& cell, const RangeMargin& margin)
{
    if (!std::isfinite(range)) return std::nullopt;
    return BeamOffset{static_cast<double>(range) - cell.d, margin.at(cell.d)};
}

/** offsetOf() for scan `j`'s beam of the point's own cell. */
std::optional<BeamOffset> beamOffset(const Judge& j, const ImageCell& cell,
                                     const RangeMargin& margin)
{
    return offsetOf(j.at(cell.r, cell.c), cell, margin);
}

/** offsetOf() for scan `j`'s beam nearest the point's elevation: that of its own cell, else of
 *  the row next to it on the point's side, else of the other (the image's rows are finer than
 *  the sensor's beams, so a cell between two beams holds no return). */
std::optional<BeamOffset> nearestBeamOffset(const Judge& j, const ImageCell& cell,
                                            const RangeMargin& margin)
{
    float range = j.at(cell.r, cell.c);
    const int rows = j.layout->rows;
    const int first = cell.upper ? cell.r + 1 : cell.r - 1;
    const int second = cell.upper ? cell.r - 1 : cell.r + 1;
    if (!std::isfinite(range) && first >= 0 && first < rows) range = j.at(first, cell.c);
    if (!std::isfinite(range) && second >= 0 && second < rows) range = j.at(second, cell.c);
    return offsetOf(range, cell, margin);
}

/** The range of judge `j`'s return in cell (r, c), else the nearer of the cells beside it in
 *  its row (a beam's returns fill every other column); +inf for none. */
float columnReturn(const Judge& j, int r, int c)
{
    const int cols = j.layout->cols;
    const float f = j.at(r, c);
    if (std::isfinite(f)) return f;
    return std::min(j.at(r, wrapCol(c + 1, cols)), j.at(r, wrapCol(c - 1, cols)));
}

/** The next beam's return in column `col` of judge `j`'s image from `row`, up (`dir` 1) or down
 *  (-1): the first of the rows within one and a half beam spacings (three rows of half a
 *  spacing; more where the sensor's beams lie farther apart, nextBeamRows()) whose
 *  columnReturn() holds one. Its row (-1: none) and its range (`range`, +inf for none). */
int nextInColumn(const Judge& j, int row, int col, int dir, float& range)
{
    constexpr int kRows = 3;
    const int rows = nextBeamRows(j.next_beam_rows, j.layout->rows, kRows, row, dir);
    for (int k = 1; k <= rows; ++k)
    {
        const int r = row + dir * k;
        if (r < 0 || r >= j.layout->rows) break;
        range = columnReturn(j, r, col);
        if (std::isfinite(range)) return r;
    }
    range = std::numeric_limits<float>::infinity();
    return -1;
}

/** Where the surface of world point `p` goes on in the image of scan `own` (the scan it was
 *  seen in): up its column, where the next beam up (within one and a half beam spacings,
 *  nextInColumn()) returned within the margin of it; down, the same. Where that beam returned
 *  beyond the margin, in front of it or not at all, the surface ends between the two beams: the
 *  top of a bush or a hedge, a kerb, a ring's far edge on terrain. */
SurfaceAround surfaceAround(const Judge& own, const Eigen::Vector3d& p, const RangeMargin& margin)
{
    const auto cell = cellOf(own, p);
    if (!cell) return {};
    const double m = margin.at(cell->d);
    auto goesOn = [&](int dir)
    {
        float f = 0.0f;
        return nextInColumn(own, cell->r, cell->c, dir, f) >= 0 && std::abs(f - cell->d) <= m;
    };
    return {goesOn(1), goesOn(-1)};
}

/** For a ringed sensor (`ring_tan`: the tangents of its beams' elevations, ascending), whether
 *  the beam in row `row` of judge `j`'s image passed above world point `p` (true) or below it
 *  (false), by where the sensor's ring lies in that row; none when no ring lies in it (a row
 *  between two rings, or one whose return came from a ring estimated just outside it). */
std::optional<bool> beamAbove(const Judge& j, int row, const Eigen::Vector3d& p,
                              const std::vector<double>& ring_tan)
{
    const RangeImageLayout& l = *j.layout;
    const double lo = l.tan_min + row * l.tan_res;
    const auto ring = std::lower_bound(ring_tan.begin(), ring_tan.end(), lo);
    if (ring == ring_tan.end() || *ring >= lo + l.tan_res) return std::nullopt;
    const Eigen::Vector3d q = j.toSensor(p);
    return *ring * std::hypot(q.x(), q.y()) > q.z();
}

/** Whether world point `p` lies on a surface that runs along the beams of scan `own` (the
 *  scan it was seen in), met at grazing incidence: in its column of `own`'s image, the nearest
 *  beam on one side (up to one and a half beam spacings away: three rows of half a spacing)
 *  returned beyond the margin of it and the nearest on the other side in front of it. The
 *  ground, mostly: a beam a little above the point's direction lands beyond it on the same
 *  surface, so another scan's beam that does so says nothing of the point. A surface that
 *  faces the beams (a car's sill, a walker's legs) returns its neighbouring beams near it. */
bool alongBeams(const Judge& own, const Eigen::Vector3d& p, const RangeMargin& margin)
{
    const auto cell = cellOf(own, p);
    if (!cell) return false;
    const double m = margin.at(cell->d);
    int sides[2] = {0, 0};  // below, above: +1 beyond, -1 in front, 0 near the point or none
    for (int dir = -1; dir <= 1; dir += 2)
    {
        float f = 0.0f;
        if (nextInColumn(own, cell->r, cell->c, dir, f) < 0) continue;
        sides[dir > 0] = f > cell->d + m ? 1 : f < cell->d - m ? -1 : 0;
    }
    return sides[0] * sides[1] == -1;
}

/** How many of a range image's columns (`cols` in all) one horizontal step of the sensor spans
 *  at column `c`, two at least: the columns are half a step on average
 *  (RangeImageLayout::forSensor()), but pseudoAzimuth() packs them up to pi / 2 times denser
 *  toward the axes (straight ahead, behind and to the sides), where a ring's neighbouring
 *  returns lie up to four columns apart. */
int stepColumns(int cols, int c)
{
    const double q = (c + 0.5) / (cols / 4.0);
    const double f = q - std::floor(q);  // across its quarter of the turn, 0 to 1
    return std::max(2, static_cast<int>(std::ceil(M_PI * (f * f + (1.0 - f) * (1.0 - f)))));
}

/** Whether the world point in `cell` of scan `own`'s image (the scan it was seen in) lies on
 *  a surface that faces the beams of `own`: in `own`'s image, the nearest returns beside it
 *  in its row (within a horizontal step of the sensor, stepColumns()) and above and below it
 *  in its column (within one and a half beam spacings) that lie on its surface (within the
 *  margin of it; in the row and in the column, at least one does) lie within the margin's
 *  share for range noise and pose error (half its base) of its range. A beam a fraction of a
 *  cell off the point's direction then returns where one toward the point would: a walker, a
 *  car's back. On a surface met at grazing incidence (a facade along the street, a
 *  windscreen) or in foliage, neighbouring beams return farther apart; returns beyond the
 *  margin are another surface (the point lies on an edge). The ground seen by one ring
 *  returns its row at one range, but the next ring lands beyond the margin: no surface in the
 *  column. With `row_only`, a surface seen by one ring (nothing on it up or down the column)
 *  faces the beams when its row does so (a return up or down the column that lies on it still
 *  must). Where it faces them, `largest_step` (if given) gets the largest range step from the
 *  point to those of the returns that lie on its surface (0 for none): a beam half a spacing
 *  off the point's direction meets the surface about half of it nearer or farther (nothing on a
 *  walker's front, a few centimetres on a wall met obliquely). */
bool facesBeams(const Judge& own, const ImageCell& cell, const RangeMargin& margin,
                bool row_only = false, double* largest_step = nullptr);

/** How the point in `cell` of scan `own`'s image faces its beams (facingOf()). */
enum class Facing : uint8_t
{
    No,
    /** A thing one beam wide that stands out in front of its row faces the beams where its
     *  column does: the nearest returns beside it in its row lie behind it by more than the
     *  margin, or there are none (a leg, an arm, a head against what lies behind; not a
     *  corner, whose other face lies beside it at its range or nearer). A beam of another scan
     *  a fraction of a cell off the point's direction either meets the same thin thing, at the
     *  point's range to within the thing's own depth, or passes beside it to what lies behind:
     *  never a slanted surface. */
    OneBeamWide,
    Yes  ///< facesBeams()
};

/** facesBeams(), telling a thing one beam wide (Facing::OneBeamWide) from what does not face
 *  the beams; `largest_step` as there, for either. */
Facing facingOf(const Judge& own, const ImageCell& cell, const RangeMargin& margin, bool row_only,
                double* largest_step)
{
    const int cols = own.layout->cols;
    const double m = margin.at(cell.d);
    bool in_row = false, in_column = false;
    bool stands_out = true;  // nothing beside it in its row at its range or nearer
    double step = 0.0;
    // Whether the return at `f` leaves the surface facing the beams; `on` if it lies on it.
    auto check = [&](float f, bool& on)
    {
        const double off = std::abs(static_cast<double>(f) - cell.d);
        if (!(off <= m)) return true;  // another surface, or none
        on = true;
        step = std::max(step, off);
        return off <= 0.5 * margin.base;
    };
    const int reach = stepColumns(cols, cell.c);
    for (int dir = -1; dir <= 1; dir += 2)
    {
        float f = std::numeric_limits<float>::infinity();
        for (int k = 1; k <= reach && !std::isfinite(f); ++k)
            f = own.at(cell.r, wrapCol(cell.c + dir * k, cols));
        if (!check(f, in_row)) return Facing::No;
        if (std::isfinite(f) && static_cast<double>(f) - cell.d <= m) stands_out = false;
        nextInColumn(own, cell.r, cell.c, dir, f);
        if (!check(f, in_column)) return Facing::No;
    }
    if (largest_step) *largest_step = step;
    if (!in_column && !row_only) return Facing::No;
    if (in_row) return Facing::Yes;
    return stands_out && in_column ? Facing::OneBeamWide : Facing::No;
}

bool facesBeams(const Judge& own, const ImageCell& cell, const RangeMargin& margin, bool row_only,
                double* largest_step)
{
    return facingOf(own, cell, margin, row_only, largest_step) == Facing::Yes;
}

/** facingOf() for world point `p`, in its cell of `own`'s image (Facing::No outside it). */
Facing facingOf(const Judge& own, const Eigen::Vector3d& p, const RangeMargin& margin,
                double* largest_step)
{
    const auto cell = cellOf(own, p);
    return cell ? facingOf(own, *cell, margin, false, largest_step) : Facing::No;
}

/** facesBeams() for world point `p`, in its cell of `own`'s image (false outside it). */
bool facesBeams(const Judge& own, const Eigen::Vector3d& p, const RangeMargin& margin)
{
    return facingOf(own, p, margin, nullptr) == Facing::Yes;
}

/** Returns of one column of scan `own`'s image placed along the azimuth of world point `p`,
 *  in the world frame: horizontal distance from the sensor and height, metres. */
struct ColumnPlaces
{
    const Judge& own;
    double ux = 0.0, uy = 0.0;  ///< the azimuth's direction, sensor frame

    /** Along the azimuth of `q`, a point in the sensor frame of `j`. */
    ColumnPlaces(const Judge& j, const Eigen::Vector3d& q) : own(j)
    {
        const double rxy = std::sqrt(q.x() * q.x() + q.y() * q.y());
        ux = q.x() / rxy;
        uy = q.y() / rxy;
    }
    /** A return of `row` at `range`. */
    [[nodiscard]] Eigen::Vector2d at(int row, float range) const
    {
        const RangeImageLayout& l = *own.layout;
        const double tan_el = l.tan_min + (row + 0.5) * l.tan_res;
        const double s = static_cast<double>(range) / std::sqrt(1.0 + tan_el * tan_el);
        const Eigen::Vector3d w = own.Rt.transpose() * Eigen::Vector3d(s * ux, s * uy, s * tan_el);
        return {std::sqrt(w.x() * w.x() + w.y() * w.y()), w.z()};
    }
    /** Whether the line from `a` to `b` stands more than 45 degrees from the horizontal. */
    [[nodiscard]] static bool steep(const Eigen::Vector2d& a, const Eigen::Vector2d& b)
    {
        return std::abs(a.y() - b.y()) > std::abs(a.x() - b.x());
    }
};

/** Whether scan `own` could not see below world point `p`, the lowest return of a pillar: in
 *  its column of `own`'s image, the beams below it returned in front of it by more than the
 *  margin, from something standing there. Either the nearest two (each within one and a half
 *  beam spacings, three rows of half a spacing, of the one above) met a face within 45 degrees
 *  of the vertical (a fence, a hedge, a parked car's side, a barrier between the lanes), or,
 *  for a `p` on a surface that faces the beams (facesBeams(): a head, a car's side; not ground
 *  or foliage), walking on down the column over the returns still in front of `p`, such faces
 *  one under the other stand at least `face` (an object's height) tall below what the first
 *  two met: a parked car's roof, its side under it, with a walker's head and shoulders over it.
 *  What stands behind shows above it, its lower part and its ground out of sight. Ground
 *  returns its beams one after the other nearer and lower along the surface, flatter than
 *  that, and a kerb's face is lower than an object; a beam below that returned nothing says
 *  nothing. */
bool groundHidden(const Judge& own, const Eigen::Vector3d& p, const RangeMargin& margin,
                  double face, bool row_only = false)
{
    const auto cell = cellOf(own, p);
    if (!cell) return false;
    const double in_front = cell->d - margin.at(cell->d);
    float f1 = 0.0f, f = 0.0f;
    const int r1 = nextInColumn(own, cell->r, cell->c, -1, f1);
    if (r1 < 0 || !(f1 < in_front)) return false;
    int r = nextInColumn(own, r1, cell->c, -1, f);
    if (r < 0) return false;
    const ColumnPlaces column(own, own.toSensor(p));
    Eigen::Vector2d above = column.at(r, f);
    if (ColumnPlaces::steep(column.at(r1, f1), above)) return true;
    if (!facesBeams(own, *cell, margin, row_only)) return false;
    bool in_face = false;
    double face_top = 0.0;
    while ((r = nextInColumn(own, r, cell->c, -1, f)) >= 0 && f < in_front)
    {
        const Eigen::Vector2d below = column.at(r, f);
        const bool steep = ColumnPlaces::steep(above, below);
        if (steep && !in_face) face_top = above.y();
        in_face = steep;
        if (in_face && face_top - below.y() >= face) return true;
        above = below;
    }
    return false;
}

/** Whether `q`, a point of scan `own` (the scan it was seen in) in that scan's sensor frame,
 *  stands `rise` metres or more above the foot of what stands in front of it there. Walking
 *  down its column from it over the returns in front of it by more than the margin (each next
 *  beam within one and a half beam spacings): a face (steps more than 45 degrees from the
 *  horizontal, ColumnPlaces::steep()), then the first step after it that is not, where the
 *  face's foot meets the ground; the height is over the lowest return up to there, and there
 *  is none when the walk meets no face. Over a parked car, the road at the car's side: a
 *  walker's head stands its height above it; the road on the far side of a barrier, however
 *  much the road climbs towards it, little more than the barrier's foot. */
bool risesOverFront(const Judge& own, const Eigen::Vector3d& q, const RangeMargin& margin,
                    double rise)
{
    const auto cell = cellAt(*own.layout, q);
    if (!cell) return false;
    const double in_front = cell->d - margin.at(cell->d);
    const ColumnPlaces column(own, q);
    const double height = own.Rt.col(2).dot(q);  // above the sensor, world frame
    // Down the column over the returns in front: the run of steep steps (the face that hides
    // what lies below `q`), then the first step after it that is not (the ground at its foot).
    double lowest = height;
    bool face = false;
    std::optional<Eigen::Vector2d> above;
    float f = 0.0f;
    for (int r = cell->r; (r = nextInColumn(own, r, cell->c, -1, f)) >= 0 && f < in_front;)
    {
        const Eigen::Vector2d b = column.at(r, f);
        const bool steep = above && ColumnPlaces::steep(*above, b);
        lowest = std::min(lowest, b.y());
        if (face && !steep) return height - lowest >= rise;
        face = face || steep;
        above = b;
    }
    return face && height - lowest >= rise;
}

/** Whether world point `p`, the lowest return of a pillar, stands above ground out of sight of
 *  scan `own`: it lies on a surface that faces the beams (facesBeams(): a car's side, a
 *  walker's legs) and rises from it (the next beam up its column of `own`'s image returned
 *  within the margin of it), more than `above` metres above the line of the two returns below
 *  it in that column (the ground in front carried on under it). Ground is met at grazing
 *  incidence, and the ground at the foot of what stands there lies on that line; the ground
 *  behind a face is hidden by it. */
bool standsAboveGround(const Judge& own, const Eigen::Vector3d& p, const RangeMargin& margin,
                       double above)
{
    const auto cell = cellOf(own, p);
    if (!cell) return false;
    float up = 0.0f;
    if (nextInColumn(own, cell->r, cell->c, 1, up) < 0 ||
        !(std::abs(static_cast<double>(up) - cell->d) <= margin.at(cell->d)) ||
        !facesBeams(own, *cell, margin))
        return false;
    float f1 = 0.0f, f2 = 0.0f;
    const int r1 = nextInColumn(own, cell->r, cell->c, -1, f1);
    const int r2 = r1 < 0 ? -1 : nextInColumn(own, r1, cell->c, -1, f2);
    if (r2 < 0) return false;
    const ColumnPlaces column(own, own.toSensor(p));
    const Eigen::Vector2d a = column.at(r1, f1), b = column.at(r2, f2);
    if (!(a.x() - b.x() > 0.0)) return false;  // no line running away from the sensor
    const Eigen::Vector3d w = p - own.t;       // from the sensor, world axes
    const double d = std::sqrt(w.x() * w.x() + w.y() * w.y());
    return w.z() - (a.y() + (d - a.x()) * (a.y() - b.y()) / (a.x() - b.x())) > above;
}

/** What the test's scans say about one point, all opinions taken together. */
enum class Verdict : uint8_t
{
    Unjudged,  ///< no scan gave an opinion
    Held,      ///< some did, none showed it gone
    Gone       ///< a scan outside the stretch of time it was seen occupied saw through it
};

/** The view limit (Params::free_space_max_parallax_deg): judge `j` gives an opinion about
 *  world point `p` only if it sees `p` within that angle of the direction the classified scan
 *  saw it from (`from_self`: p minus that scan's sensor, `self_dist` long). */
struct Parallax
{
    double sin_limit;
    double cos_limit;

    [[nodiscard]] bool inView(const Judge& j, const Eigen::Vector3d& p,
                              const Eigen::Vector3d& from_self, double self_dist) const
    {
        // Seen from a point at distance a, two sensors a baseline b apart subtend at most
        // asin(b / a): within the limit without computing the angle when b <= a sin(limit).
        if (j.baseline <= self_dist * sin_limit) return true;
        const Eigen::Vector3d from_j = p - j.t;
        return from_self.dot(from_j) >= cos_limit * self_dist * from_j.norm();
    }
};

/** What a pillar's points must be to be tested, in the scan's height cells and metres. */
struct ObjectTest
{
    /** Entries an object needs: two returns free_space_min_extent apart in height stand above
     *  the ground (texture and kerbs are flat). Not three: a 16-beam LiDAR puts two beams on a
     *  person from about 15 m (2 degrees apart), a 32-beam one from about 35 m. */
    static constexpr std::size_t kMinEntries = 2;

    int32_t clearance;  ///< cells above the pillar's ground (ground())
    double range2;      ///< squared range from the sensor
    double min_extent;  ///< metres spanned
    double res;         ///< metres per cell

    /** The height cell of pillar `p`'s ground for the test: its lowest return in the scan,
     *  unless the map holds a static floor (its lowest static interval, ScanBuckets::floors)
     *  at least min_extent below that return, whose top cell it is then. With sparse rings a
     *  pillar's ground is often not sampled under what stands on it, so its lowest return is
     *  a mover's own lowest ring (a walker's knees, a car's sill), which the clearance would
     *  keep out of the test; the floor the map saw there before shows where the ground is. A
     *  return less than an object's height above the floor is taken for the ground itself
     *  (terrain, kerbs, a floor seen at another place in the pillar). Without such a floor,
     *  where the scan could not see below the lowest return (`hidden`, groundHidden()), that
     *  return is no ground either: the ground lies below it, out of sight, and the lowest
     *  return is clear of it. */
    [[nodiscard]] int32_t ground(const ScanBuckets& scan, std::size_t p, int32_t lowest,
                                 bool hidden) const
    {
        const int32_t top = scan.floors[p];
        if (top != ScanBuckets::kNoFloor && (static_cast<double>(lowest) - top) * res >= min_extent)
            return top;
        return hidden ? static_cast<int32_t>(std::max<int64_t>(std::numeric_limits<int32_t>::min(),
                                                               int64_t{lowest} - clearance))
                      : lowest;
    }

    /** Entries clear of the ground, counted with the height they span. */
    struct Extent
    {
        std::size_t count = 0;
        int32_t top = std::numeric_limits<int32_t>::min();
        int32_t bottom = std::numeric_limits<int32_t>::max();

        void add(int32_t cell)
        {
            ++count;
            top = std::max(top, cell);
            bottom = std::min(bottom, cell);
        }
    };

    struct Found
    {
        int32_t low;  ///< the pillar's ground (ground())
        bool object;  ///< there are entries to test, and with those dynamic already make an object
        /** Those already dynamic (the map's verdict) make one; or the map found every return
         *  of the pillar dynamic, its lowest included, and they make one from the lowest up:
         *  nothing there is ground, which the map holds static (a car far away on a road that
         *  climbs, whose lowest ring the test would otherwise take for the ground). */
        bool moving;
        /** All entries within range from the lowest up make one: the lowest return counted as
         *  part of what stands there would make it an object. */
        bool from_lowest;
    };

    /** The entry of pillar `p` of `scan` in its lowest height cell (the first of them). */
    [[nodiscard]] static uint32_t lowestEntry(const ScanBuckets& scan, std::size_t p)
    {
        uint32_t lowest = scan.offsets[p];
        for (uint32_t k = lowest + 1; k < scan.offsets[p + 1]; ++k)
            if (scan.cells[k] < scan.cells[lowest]) lowest = k;
        return lowest;
    }

    [[nodiscard]] bool isObject(const Extent& x) const
    {
        return x.count >= kMinEntries && (x.top - x.bottom + 1) * res >= min_extent;
    }

    /** The entries of pillar `p` of `scan` to test (into `tested`): `clear` cells or more
     *  above the pillar's ground (ground()), within range, not dynamic already; whether all
     *  entries clear of the ground, those to test and those dynamic already, make an object
     *  (at least kMinEntries spanning min_extent: what the map found dynamic of an object is
     *  still part of it; a car far away seen by two or three rings, its top ring dynamic
     *  already, is an object only with it); and whether those dynamic already make one. */
    Found entries(const ScanBuckets& scan, std::size_t p, const PointsView& pts,
                  const std::vector<uint8_t>& is_dynamic, std::vector<uint32_t>& tested,
                  int32_t clear, bool hidden = false) const
    {
        const uint32_t b = scan.offsets[p], e = scan.offsets[p + 1];
        const int32_t lowest = scan.cells[lowestEntry(scan, p)];
        const int32_t low = ground(scan, p, lowest, hidden);
        // Below the ground the scan saw (the lowest return, when hidden): part of the object,
        // not tested (other scans' beams toward it meet what hid it, or what it stands in).
        const int32_t test_from = ground(scan, p, lowest, false);
        tested.clear();
        Extent all, dynamic, every;  // every: all within range, from the lowest up
        bool every_dynamic = true;
        for (uint32_t k = b; k < e; ++k)
        {
            const uint32_t i = scan.index[k];
            const double x = pts.x[i], y = pts.y[i], z = pts.z[i];
            if (x * x + y * y + z * z > range2) continue;
            every.add(scan.cells[k]);
            every_dynamic = every_dynamic && is_dynamic[i] != 0;
            if (scan.cells[k] < low + clear) continue;
            all.add(scan.cells[k]);
            if (is_dynamic[i])
                dynamic.add(scan.cells[k]);
            else if (scan.cells[k] >= test_from + clear)
                tested.push_back(k);
        }
        return {low, !tested.empty() && isObject(all),
                isObject(dynamic) || (every_dynamic && isObject(every)), isObject(every)};
    }
};

/** A return of the classified scan in its own image: its cell and range, metres. */
struct Sample
{
    int r, c;
    float d;
};

/** Whether the classified scan's own image shows one surface across two pillars: a sample of
 *  each (`a`, `b`, each sorted by row) next to each other, within one and a half beam
 *  spacings in the column (three rows of half a spacing) and two columns in the row (`cols`,
 *  the image's columns, wrap around the azimuth), at ranges within `tol` of each other. Near
 *  the axes a ring's neighbouring returns can lie farther apart (stepColumns(), which
 *  facesBeams() reads): there two samples of one surface in the same row may not meet. */
bool oneSurface(const std::vector<Sample>& a, const std::vector<Sample>& b, int cols, double tol)
{
    constexpr int kRows = 3;
    std::size_t from = 0;  // the first of b's samples within kRows of the current one of a
    for (const Sample& x : a)
    {
        while (from < b.size() && b[from].r < x.r - kRows) ++from;
        for (std::size_t j = from; j < b.size() && b[j].r <= x.r + kRows; ++j)
        {
            const int dc = std::abs(x.c - b[j].c);
            if (std::min(dc, cols - dc) <= 2 &&
                std::abs(static_cast<double>(x.d) - static_cast<double>(b[j].d)) <= tol)
                return true;
        }
    }
    return false;
}

/** Judges (whose beams returned) that must show a surface moving steadily along the beams
 *  (markSeenThrough()); for the steady drift, kSteadyJudgesFacing where the point lies on a
 *  surface that faces the beams (facesBeams()). */
constexpr std::size_t kSteadyJudges = 3;
constexpr std::size_t kSteadyJudgesFacing = 2;
/** Judges in a row that must have seen a place empty just before (or after) what stands there
 *  now (markSeenThrough()): one is a flicker (a gap in a hedge that one scan sees through). */
constexpr std::size_t kEmptyBeforeJudges = 2;

/** Gone points needed among `judged` for a share `fraction`: at least one. */
std::size_t needed(double fraction, std::size_t judged)
{
    return std::max<std::size_t>(
        1, static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(judged) - 1e-9)));
}

/** Whether the verdicts of `tested` (in order, from `verdict(k)`) reach `fraction` of the
 *  judged ones. Stops as soon as the outcome is known: the rest all gone would not reach it,
 *  or the rest all held would not undo it. */
template <typename VerdictOf>
bool reachesShare(const std::vector<uint32_t>& tested, double fraction, VerdictOf&& verdict)
{
    std::size_t gone = 0, judged = 0, left = tested.size();
    for (uint32_t k : tested)
    {
        const std::size_t need = needed(fraction, judged + left);
        if (gone >= need) return true;
        if (gone + left < need) return false;
        const Verdict v = verdict(k);
        gone += v == Verdict::Gone;
        judged += v != Verdict::Unjudged;
        --left;
    }
    return gone >= needed(fraction, judged);
}

}  // namespace

/** The stretch rule's walk over one side of the classified scan (`count` judges, the k-th
 *  nearest in time judgeAt(k)): walking in from the farthest, the first judge `j` for which
 *  `settles(j)` holds settles the side. How far in time it is (k + 1), or 0 for none. */
template <typename JudgeAt, typename Settles>
std::size_t settledAt(std::size_t count, JudgeAt&& judgeAt, Settles&& settles)
{
    for (std::size_t k = count; k-- > 0;)
        if (settles(judgeAt(k))) return k + 1;
    return 0;
}

namespace
{
/** Where a judge sees the point being judged (within the view limit). */
enum class Seen : uint8_t
{
    Unknown,
    Out,  ///< beyond the view limit or outside the judge's image
    In
};
/** What the free-space test writes as it judges, one per thread: where each judge sees the
 *  point being judged (found at most once per judge and point: the rules ask the same judges
 *  again) and the entries a pillar's test asks about. */
struct TestScratch
{
    explicit TestScratch(std::size_t judges) : seen(judges), cells(judges) {}
    std::vector<Seen> seen;
    std::vector<ImageCell> cells;
    std::vector<uint32_t> tested;
};
/** The scratch of the pillar loop's range this thread runs (markSeenThrough()); null on the
 *  calling thread outside it. */
thread_local TestScratch* t_scratch = nullptr;
/** Makes `s` this thread's scratch for its lifetime. */
struct ScratchOnThisThread
{
    explicit ScratchOnThisThread(TestScratch& s) : previous(t_scratch) { t_scratch = &s; }
    ~ScratchOnThisThread() { t_scratch = previous; }
    ScratchOnThisThread(const ScratchOnThisThread&) = delete;
    ScratchOnThisThread& operator=(const ScratchOnThisThread&) = delete;
    TestScratch* previous;
};
}  // namespace

std::size_t markSeenThrough(const PillarGrid& grid, const ScanBuckets& scan, const PointsView& pts,
                            const Eigen::Isometry3d& T, const FreeSpaceTest& test,
                            std::vector<uint8_t>& is_dynamic, std::size_t& judge_count)
{
    const Params& prm = grid.params();
    const double res = grid.geometry().height_resolution;
    // The scan classified, if the test holds it: it is not its own evidence, and only the
    // scans within free_space_window of it count. Otherwise it is newer than all of them.
    const std::optional<std::size_t> self = test.find(pts, T);
    // A ringed sensor: the next return up or down a column of a scan's image is its next beam,
    // and each beam's elevation is one of its rings'.
    const bool rings = grid.sensorModel() && grid.sensorModel()->hasRings();
    const std::vector<double>& ring_tan = GridAccess::beamTangents(grid);
    // The grid's table of where the next beam lies, for the scans whose images have its layout
    // (a scan added before the sensor model was estimated again has another).
    auto judgeOf = [&](const FreeSpaceTest::Scan& s, std::size_t pos)
    {
        return Judge::of(s, pos,
                         s.layout == grid.imageLayout() ? GridAccess::nextBeamRows(grid) : nullptr);
    };
    std::vector<Judge> judges;
    const auto& scans = test.scans();
    for (std::size_t k = 0; k < scans.size(); ++k)
    {
        if (self && (k == *self || (k < *self ? *self - k : k - *self) > prm.free_space_window))
            continue;
        judges.push_back(judgeOf(scans[k], k));
    }
    judge_count = judges.size();
    if (judges.empty()) return 0;

    const Eigen::Matrix3d R = T.linear();
    const Eigen::Vector3d t = T.translation();
    for (Judge& j : judges) j.baseline = (j.t - t).norm();
    const ObjectTest object{static_cast<int32_t>(std::ceil(prm.free_space_clearance / res - 1e-9)),
                            prm.free_space_range * prm.free_space_range, prm.free_space_min_extent,
                            res};
    const int32_t below = object.clearance / 2;  // marked from half the clearance up (mark())
    const RangeMargin margin{prm.free_space_margin, prm.free_space_margin_per_m};
    const Parallax parallax{prm.free_space_max_parallax_deg >= 90.0
                                ? 1.0
                                : std::sin(prm.free_space_max_parallax_deg * M_PI / 180.0),
                            std::cos(prm.free_space_max_parallax_deg * M_PI / 180.0)};
    // Where the classified scan sits among the judges in time (one the test does not hold is
    // newer than all of them, as online).
    const std::size_t self_pos =
        self ? static_cast<std::size_t>(std::lower_bound(judges.begin(), judges.end(), *self,
                                                         [](const Judge& j, std::size_t pos)
                                                         { return j.pos < pos; }) -
                                        judges.begin())
             : judges.size();
    // The k-th nearest judge in time before the classified scan, and after it.
    auto earlier = [&](std::size_t k) { return self_pos - 1 - k; };
    auto later = [&](std::size_t k) { return self_pos + k; };

    // Each thread's own scratch (TestScratch), this one on the calling thread.
    TestScratch main_scratch(judges.size());
    auto scratch = [&]() -> TestScratch& { return t_scratch ? *t_scratch : main_scratch; };

    // The scan's own image (groundHidden(), alongBeams(), facesBeams()), built when the test
    // does not hold the scan.
    std::optional<FreeSpaceTest> unheld;
    std::optional<Judge> own;
    auto ownJudge = [&]() -> const Judge&
    {
        if (!own)
        {
            if (!self)
            {
                unheld.emplace(1);
                unheld->add(pts, T, grid.imageLayout());
            }
            own = self ? judgeOf(scans[*self], *self) : judgeOf(unheld->scans().front(), 0);
        }
        return *own;
    };
    // Input point i in the world frame.
    auto worldOf = [&](uint32_t i) -> Eigen::Vector3d
    { return R * Eigen::Vector3d(pts.x[i], pts.y[i], pts.z[i]) + t; };
    // What the judges say about input point i: the judges that saw it occupied, with
    // this scan, span a stretch of time; only a judge outside it that saw through the point
    // shows it gone. On each side of the scan, walking in from the farthest judge, the first
    // one with an opinion decides that side: seen through, gone; occupied, the stretch reaches
    // it, so no nearer judge of that side can show the point gone.
    // With `sky` (an entry held static by one sighting alone, ScanBuckets::seen_once), a judge
    // whose beams toward the point passed into open sky (skyBeyond()) saw through it as well:
    // the map's own rule for such an interval (BeamGate::skyFor()).
    const double sky_half_width = grid.geometry().pillar_size;
    // With `at_max` (its entry's interval held at p_max by the map, ScanBuckets::at_max),
    // nothing there came lately, and the walk for a place seen empty just before what stands
    // there is not made.
    // With `drift_only` (the middle of an entry's run, entryVerdict()), only a steady drift
    // along the beams shows the point gone; every other verdict is Held.
    auto pointVerdict = [&](uint32_t i, bool sky, bool at_max, bool drift_only = false)
    {
        TestScratch& here = scratch();
        std::vector<Seen>& seen = here.seen;
        std::vector<ImageCell>& cells = here.cells;
        const Eigen::Vector3d p_w = worldOf(i);
        const Eigen::Vector3d from_self = p_w - t;
        const double self_dist = from_self.norm();
        std::fill(seen.begin(), seen.end(), Seen::Unknown);
        auto cellIn = [&](std::size_t j) -> const ImageCell*
        {
            if (seen[j] == Seen::Unknown)
            {
                std::optional<ImageCell> c;
                if (parallax.inView(judges[j], p_w, from_self, self_dist))
                    c = cellOf(judges[j], p_w);
                seen[j] = c ? Seen::In : Seen::Out;
                if (c) cells[j] = *c;
            }
            return seen[j] == Seen::In ? &cells[j] : nullptr;
        };
        // The first judge of each side is read first: both of their cells are fetched now,
        // so that the second read does not wait for memory after the first.
        if (self_pos > 0)
            if (const ImageCell* c = cellIn(0)) judges[0].image->prefetch(c->r, c->c);
        if (judges.size() > self_pos)
            if (const ImageCell* c = cellIn(judges.size() - 1))
                judges.back().image->prefetch(c->r, c->c);
        bool judged = false;
        // Whether a beam that returned `offset` from the point (within the margin `m` there)
        // shows a steady drift's full size (see `steady` below): beyond the margin less its
        // share for range noise and pose error (half the margin at no distance). Where the
        // point's own scan shows it on a surface that faces the beams (facesBeams()), the
        // margin's share per metre, for a neighbouring beam on a slanted surface, has only the
        // surface's own slope there to cover: a judge's beam toward the point may lie half a
        // beam spacing off its direction, and meet the surface up to half the range step to
        // the point's neighbouring returns on it nearer or farther (facesBeams()'s largest
        // step). Beyond that and the noise share, a drift has its size (a slow walker 15 m
        // away, its front flat to the beams: 0.15 m instead of 0.45). Asked once per point,
        // only for such offsets.
        std::optional<Facing> facing;  // not asked yet
        double largest_step = 0.0;     // where it faces them
        auto facingHere = [&]
        {
            if (!facing) facing = facingOf(ownJudge(), p_w, margin, &largest_step);
            return *facing;
        };
        auto facesTheBeams = [&] { return facingHere() == Facing::Yes; };
        // facesTheBeams() for a drift's measure: a thing one beam wide in its row that stands
        // out in front of it faces the beams by its column (Facing::OneBeamWide: a leg, an
        // arm, a head; the edges of a walker's body, where the returns beside it in the row lie
        // on what is behind). Another scan's beam that returned within the margin of such a
        // point met the same thin thing, so its offset measures the thing's own motion. Not for
        // the rules that read a beam that passed the point (a place seen empty just before,
        // surfaceAt()): beside a thing one beam wide, a beam a fraction of a cell off passes it.
        auto facesTheBeamsForDrift = [&] { return facingHere() != Facing::No; };
        auto driftSize = [&](double offset, double m)
        {
            const double noise = 0.5 * margin.base;
            if (std::abs(offset) > m - noise) return true;
            return std::abs(offset) > noise && facesTheBeamsForDrift() &&
                   std::abs(offset) > noise + 0.5 * largest_step;
        };
        // Where the point's surface goes on in its own scan (surfaceAround()), asked at most
        // once per point, where a judge's beam that passed it saw through (below). On a
        // surface that faces the beams, a beam beside the point returns where one toward it
        // would (facesBeams()): it goes on everywhere there.
        std::optional<SurfaceAround> around;
        auto surfaceAt = [&]() -> const SurfaceAround&
        {
            if (!around)
                around = facesTheBeams() ? SurfaceAround{} : surfaceAround(ownJudge(), p_w, margin);
            return *around;
        };
        // A judge whose beam toward the point passed it on a side where the point's surface
        // ends and returned beyond it: a neighbouring row's beam (its own cell held no return),
        // or its own cell's, by where the sensor's ring lies in that row (beamAbove()). That
        // beam may have passed beside the surface (over a bush, under a hedge's foot, a ring's
        // far edge on terrain), not through where it was. Such a "free" settles a side only
        // with the next judge in that has an opinion: free too, gone; occupied, held. A mover
        // that left is seen through by both; a static edge is seen occupied again by a judge
        // whose beam meets it. Only with rings (the next beam up a column; in a rosette's image
        // the next return there is no neighbouring beam of the same sweep).
        bool unconfirmed = false;
        // Whether judge j settles this side: gone, or occupied (`at`: where its beam returned,
        // from the point, and the margin there).
        BeamOffset at{0.0, 0.0};
        auto settles = [&](std::size_t j, bool& gone)
        {
            const ImageCell* c = cellIn(j);
            if (!c) return false;
            const Look v =
                look(judges[j], *c, margin, false, sky && rings ? &p_w : nullptr, sky_half_width);
            // Which side of the point the beam passed: a neighbouring row's by its row, the
            // point's own row's (its cell's beam, not one beside it) by the ring in that row.
            std::optional<bool> above;
            if (rings && v.view == View::Free && v.row >= 0)
            {
                if (v.row != c->r)
                    above = v.row > c->r;
                else if (std::isfinite(judges[j].at(c->r, c->c)))
                    above = beamAbove(judges[j], c->r, p_w, ring_tan);
            }
            const bool past_edge = above && (*above ? !surfaceAt().up : !surfaceAt().down);
            if (past_edge && !unconfirmed)
            {
                unconfirmed = true;
                return false;
            }
            judged = judged || v.view != View::None;
            gone = v.view == View::Free;
            at = {static_cast<double>(v.range) - c->d, margin.at(c->d)};
            return gone || v.view == View::Occupied;
        };
        // Each side, walking in from the farthest judge: how far in time (in judges) the one
        // that settled it was (0: none did).
        bool gone = false;
        auto settlesSide = [&](std::size_t j) { return settles(j, gone); };
        const std::size_t settled_before = settledAt(self_pos, earlier, settlesSide);
        const BeamOffset at_before = settled_before ? at : BeamOffset{0.0, 0.0};
        if (gone) return drift_only ? Verdict::Held : Verdict::Gone;
        unconfirmed = false;
        const std::size_t settled_after = settledAt(judges.size() - self_pos, later, settlesSide);
        const BeamOffset at_after = settled_after ? at : BeamOffset{0.0, 0.0};
        if (gone) return drift_only ? Verdict::Held : Verdict::Gone;
        // A surface that moved along the beams between the two judges that settled the sides:
        // each saw it within the margin of the point, but the earlier one on one side of it and
        // the later one on the other (nearer, then farther: it went away; farther, then nearer:
        // it came closer), the two more than the margin apart. A person walking half a metre
        // along the line of sight in a clip stays within the margin for every judge, yet is
        // seen in front of the point from one side in time and behind it from the other. A
        // static surface is seen around the point by the noise, which the margin covers at each
        // judge; where a beam a fraction of a cell off the point's direction lands far along the
        // surface (one met at grazing incidence, foliage), the offsets scatter as widely, so the
        // point must lie on a surface that faces the beams (facesBeams()).
        if (!drift_only && settled_before > 0 && settled_after > 0 &&
            at_before.offset * at_after.offset < 0.0 &&
            std::abs(at_after.offset - at_before.offset) >
                std::max(at_before.margin, at_after.margin) &&
            facesTheBeams())
            return Verdict::Gone;
        // A surface that moved along the beams toward the sensor (a person walking along the
        // line of sight): walking out from the nearest judge in time, each one's beam toward
        // the point returned within the margin of where the previous one's did (the same
        // surface), and at last nearer than the point by more than the margin, with no judge
        // farther out in time seeing the point occupied again. A static surface stays where it
        // is, and one that something passes in front of is cut off, not drifted from.
        // Where judge j's beam toward the point returned (none out of view), and the judges
        // of each side walking out from the nearest in time.
        auto offsetFrom = [&](std::size_t j) -> std::optional<BeamOffset>
        {
            const ImageCell* c = cellIn(j);
            if (!c) return std::nullopt;
            return beamOffset(judges[j], *c, margin);
        };
        auto drifted = [&](std::size_t count, auto judgeAt, std::size_t settled)
        {
            // The judges beyond the one that settled the side gave no opinion, so the beam
            // can only have left the margin at the next one out; none settled, or the
            // farthest saw the point occupied (a static point, mostly): nothing to find.
            if (settled == 0 || settled >= count) return false;
            const auto last = offsetFrom(judgeAt(settled));
            if (!last || last->offset >= -last->margin) return false;
            double previous = 0.0;  // the point itself
            for (std::size_t k = 0; k <= settled; ++k)
            {
                const auto o = k == settled ? last : offsetFrom(judgeAt(k));
                if (!o || std::abs(o->offset - previous) > o->margin || o->offset > o->margin)
                    return false;
                previous = o->offset;
            }
            judged = true;
            return true;
        };
        if (!drift_only && (drifted(self_pos, earlier, settled_before) ||
                            drifted(judges.size() - self_pos, later, settled_after)))
            return Verdict::Gone;
        // A place seen empty just before what stands there now (or just after): walking out
        // from the nearest judge in time on one side, past those that see the point occupied
        // (what stands there now), kEmptyBeforeJudges in a row that saw through it, before any
        // sees it occupied again or returns near it. The walk in from the farthest judge settles
        // such a side as occupied all along where something stood there earlier still (a
        // cyclist riding in another's track, half a second behind): it guards against a gap
        // that one scan sees in a hedge or foliage. Two scans in a row are no flicker, and the
        // point must lie on a surface that faces the beams (facesBeams(): not foliage).
        auto emptyBefore = [&](std::size_t count, auto judgeAt)
        {
            std::size_t run = 0;
            for (std::size_t k = 0; k < count; ++k)
            {
                const std::size_t j = judgeAt(k);
                const ImageCell* c = cellIn(j);
                if (!c) return false;
                const View v = look(judges[j], *c, margin).view;
                if (v == View::Free && ++run >= kEmptyBeforeJudges) return true;
                if (run > 0 && (v == View::Vetoed || v == View::Occupied)) return false;
            }
            return false;
        };
        // facesTheBeams() first: it reads a few cells of the point's own image, once per point,
        // where the walks read every judge out to the first that sees the place empty, all of
        // them for a point that is seen occupied throughout (most are).
        if (!drift_only && !at_max && facesTheBeams() &&
            (emptyBefore(self_pos, earlier) || emptyBefore(judges.size() - self_pos, later)))
        {
            judged = true;
            return Verdict::Gone;
        }
        // Walking out from the nearest judge in time on one side (`count` judges, the k-th
        // nearest judgeAt(k)): each beam toward the point that returned goes to take(offset,
        // k), which says whether the walk goes on, has found the surface it looks for, or has
        // lost it; a judge that cannot see the point ends the walk.
        enum class Walk : uint8_t
        {
            On,
            Found,
            Lost
        };
        auto walkOut = [&](std::size_t count, auto judgeAt, auto take)
        {
            for (std::size_t k = 0; k < count; ++k)
            {
                const std::size_t j = judgeAt(k);
                const ImageCell* c = cellIn(j);
                if (!c) return false;
                const auto o = nearestBeamOffset(judges[j], *c, margin);
                if (!o) continue;
                const Walk w = take(*o, k);
                if (w == Walk::Lost) return false;
                if (w == Walk::Found)
                {
                    judged = true;
                    return true;
                }
            }
            return false;
        };
        // A surface that moved steadily along the beams, either way, by less than the margin
        // (a person walking along the line of sight, seen occupied by every judge): walking
        // out from the nearest judge in time, each beam toward the point that returned did so
        // on the same side of it as the others and no nearer to it than the previous one,
        // within the margin of the previous one (the same surface), kSteadyJudges of them at
        // least, the last a drift's size from the point (a static surface's offsets scatter
        // around the point, and foliage's jitter in and out; what a beam on a slanted surface
        // and the pose add does not grow judge after judge). The beam toward the point is the
        // one nearest its elevation; a judge whose beams there returned nothing says nothing
        // either way; one that cannot see the point ends the walk. Two judges suffice
        // (kSteadyJudgesFacing) where the point's own scan shows it on a surface that faces
        // the beams (facesBeams(): its neighbouring beams return within the margin's share for
        // range noise and pose error), or on a thing one beam wide that stands out in front
        // of its row (facesTheBeamsForDrift()): there a beam beside the point returns where one
        // toward it would, or misses the thing, so a second offset that grew beyond that share
        // is the surface's own motion, not a slanted surface seen from a new place (online,
        // the third scan of a walker coming along the line of sight has two scans of past).
        // Asked last: facesBeams() reads the image around the point.
        auto enoughJudges = [&](std::size_t n)
        { return n >= kSteadyJudges || (n >= kSteadyJudgesFacing && facesTheBeamsForDrift()); };
        auto steady = [&](std::size_t count, auto judgeAt)
        {
            double previous = 0.0;
            int side = 0;
            std::size_t returned = 0;  // judges whose beam toward the point returned
            return walkOut(count, judgeAt,
                           [&](const BeamOffset& o, std::size_t)
                           {
                               if (std::abs(o.offset - previous) > o.margin ||
                                   std::abs(o.offset) < std::abs(previous))
                                   return Walk::Lost;
                               const int sign = (o.offset > 0.0) - (o.offset < 0.0);
                               if (sign != 0 && side != 0 && sign != side) return Walk::Lost;
                               if (sign != 0) side = sign;
                               previous = o.offset;
                               return ++returned >= kSteadyJudgesFacing &&
                                              driftSize(previous, o.margin) &&
                                              enoughJudges(returned)
                                          ? Walk::Found
                                          : Walk::On;
                           });
        };
        // Only where it can be found: the judge that settled the side is the farthest out
        // that saw the point within the margin, so a steady drift reaches its size there
        // (what it saw, taken with the beam that look() took), enoughJudges() or more out.
        auto mayDrift = [&](std::size_t settled, const BeamOffset& o)
        {
            return settled >= kSteadyJudgesFacing && driftSize(o.offset, o.margin) &&
                   enoughJudges(settled);
        };
        if ((mayDrift(settled_before, at_before) && steady(self_pos, earlier)) ||
            (mayDrift(settled_after, at_after) && steady(judges.size() - self_pos, later)))
            return Verdict::Gone;
        if (drift_only) return Verdict::Held;
        // A surface that moved along the beams at a constant speed of more than the margin a
        // scan (a car driving ahead of the sensor, seen from behind): each scan before it saw
        // the point hidden by that surface, nearer by the same step for every scan further
        // away in time, so that no judge settled the side. Walking out from the nearest judge
        // in time, each beam toward the point that returned did so within the margin of n
        // steps in front of it (n: the judge's distance in scans, the step that of the first
        // one that returned), kSteadyJudges of them, the last beyond the margin. What hides a
        // static point from other places stays where it is: its offset is the same from
        // judge to judge (or changes with the view), not a multiple of the time since the
        // point was seen, from nothing, at the classified scan. The test keeps consecutive
        // scans of the sensor, so scans are a constant time apart.
        // Two judges are enough when the second returned n steps in front to within the
        // margin's share for range noise and pose error (half its base, as for a drift's
        // size): an offset that stays the same cannot be twice itself and beyond the margin,
        // and one that changes with the view (a surface met at grazing incidence, foliage)
        // lands that close to the multiple only by chance. Online, the third scan of a run has
        // two scans of past.
        auto constantSpeed = [&](std::size_t count, auto judgeAt)
        {
            double step = 0.0;
            std::size_t returned = 0;
            return walkOut(count, judgeAt,
                           [&](const BeamOffset& o, std::size_t k)
                           {
                               const double scans_away = static_cast<double>(k + 1);
                               const double off_step = std::abs(o.offset - step * scans_away);
                               if (returned == 0)
                                   step = o.offset / scans_away;
                               else if (off_step > o.margin)
                                   return Walk::Lost;
                               ++returned;
                               if (std::abs(o.offset) <= o.margin) return Walk::On;
                               return returned >= kSteadyJudges ||
                                              (returned == 2 && off_step <= 0.5 * margin.base)
                                          ? Walk::Found
                                          : Walk::On;
                           });
        };
        if ((settled_before == 0 && constantSpeed(self_pos, earlier)) ||
            (settled_after == 0 && constantSpeed(judges.size() - self_pos, later)))
            return Verdict::Gone;
        // A surface that moved along the beams, where the judges lie on one side of the scan in
        // time only (online, the past; offline, the first and the last scan), so that the two
        // rules above may have too few of them (the second scan of an online run has one):
        // walking out from the nearest judge in time, the first whose beam toward the point
        // returned did so in front of it by more than the margin, at a place `q` (on the line
        // of sight to the point) that the classified scan's own beams see through (look():
        // returned beyond it, none near it) and that the map does not hold static. What hid the
        // point there has left, and was no part of the static scene: a car driving away, whose
        // back the scan before saw a step nearer, where the scan's beams now pass on to its back
        // farther away (mirrored in time, one coming nearer). What a static thing hides (a pole,
        // a parked car, a hedge) the map holds static at `q`, wherever the scan's beams pass
        // beside it.
        auto vacated = [&](std::size_t count, auto judgeAt)
        {
            return walkOut(count, judgeAt,
                           [&](const BeamOffset& o, std::size_t k)
                           {
                               if (o.offset >= -o.margin) return Walk::Lost;
                               const std::size_t jk = judgeAt(k);
                               const Judge& j = judges[jk];
                               const double d = cells[jk].d;
                               const Eigen::Vector3d q = j.t + (p_w - j.t) * ((d + o.offset) / d);
                               if (grid.isStatic(q.x(), q.y(), q.z())) return Walk::Lost;
                               const auto at_q = cellOf(ownJudge(), q);
                               return at_q && look(ownJudge(), *at_q, margin).view == View::Free
                                          ? Walk::Found
                                          : Walk::Lost;
                           });
        };
        if ((self_pos == judges.size() && settled_before == 0 && vacated(self_pos, earlier)) ||
            (self_pos == 0 && settled_after == 0 && vacated(judges.size(), later)))
            return Verdict::Gone;
        return judged ? Verdict::Held : Verdict::Unjudged;
    };

    // What they say about entry k: it stands for a run of input points in one height cell of
    // the pillar (its repeats follow it), on KITTI the points of one ring across an object.
    // The run's two ends are the object's edges along the sweep, where a mover shows up first
    // and leaves last: the first of them shown gone shows the entry gone. (The first point
    // alone would test only the edge the sweep meets first: a walker moving with the sweep
    // would show only its trailing edge.)
    // The last input point of the run that input point `first` begins (its repeats follow it).
    auto lastOfRun = [&](uint32_t first)
    {
        uint32_t last = first;
        while (last + 1 < pts.size && scan.repeats[last + 1]) ++last;
        return last;
    };
    // An entry's verdict from its run's points' (`of`, the run from input point `first` to
    // `last`): its first point's, unless that is not gone and its last point's is known.
    auto runVerdictOf = [&](uint32_t first, uint32_t last, auto&& of)
    {
        const Verdict a = of(first);
        if (a == Verdict::Gone || last == first) return a;
        const Verdict b = of(last);
        if (b != Verdict::Unjudged) return b;
        return a;
    };
    // runVerdictOf() for entry k's run.
    auto runVerdict = [&](uint32_t k, auto&& of)
    {
        const uint32_t first = scan.index[k];
        return runVerdictOf(first, lastOfRun(first), of);
    };
    // An entry's verdict by pointVerdict(), with a judge's beams into open sky counted or not.
    // Where neither end of its run is shown gone, the run's middle point is asked about a
    // steady drift along the beams alone: the ends lie on the object's outline, where the
    // rings above and below end a little sooner or later (their returns in the end's column
    // fall off the object) and a rounded body meets the beams at grazing incidence, so an end
    // seldom faces the beams by facesBeams() and a drift there needs three judges and most of
    // the margin; the middle of a walker's back or a cyclist faces them, where two judges and
    // the noise share are enough. The other rules read beams that passed the point, and the
    // ends are where those show a mover (its edges); a middle point of foliage or a porous
    // fence gives them more gaps to see through.
    auto entryVerdict = [&](uint32_t k, bool sky)
    {
        const bool at_max = scan.at_max[k] != 0;
        const uint32_t first = scan.index[k], last = lastOfRun(first);
        const Verdict v =
            runVerdictOf(first, last, [&](uint32_t i) { return pointVerdict(i, sky, at_max); });
        if (v == Verdict::Gone || last - first < 2) return v;
        return pointVerdict(first + (last - first) / 2, sky, at_max, true) == Verdict::Gone
                   ? Verdict::Gone
                   : v;
    };
    auto verdict = [&](uint32_t k) { return entryVerdict(k, false); };
    // verdict(), with a judge's beams into open sky counted where the entry is new
    // (ScanBuckets::seen_once) and that one sighting makes it static in the map (online's
    // p_empty_init; offline's holds it dynamic already, and the test has nothing to add).
    const LogOddsModel model = LogOddsModel::of(grid);
    const bool new_is_static = grid.isStaticLogOdds(model.empty_init + model.hit);
    auto newVerdict = [&](uint32_t k)
    { return entryVerdict(k, new_is_static && scan.seen_once[k]); };

    // The verdict of the judges on input point i by the beams through its own cell alone (the
    // stretch rule of pointVerdict(), walking in from the farthest judge on each side): where a
    // judge's cell holds no return, a neighbouring cell's beam is no evidence about a point on
    // the ground, which it meets at grazing incidence a beam spacing higher or lower, metres
    // beyond or in front. With `below_only`, a beam that returned beyond the point shows it
    // gone only where the sensor's ring in its row passed below the point (beamAbove()): a
    // beam a little below the top of something standing meets it while it is there, one a
    // little above passes over it (or over a roof's edge, met at grazing incidence).
    auto ownBeamsVerdict = [&](uint32_t i, bool below_only = false)
    {
        const Eigen::Vector3d p_w = worldOf(i);
        const Eigen::Vector3d from_self = p_w - t;
        const double self_dist = from_self.norm();
        bool gone = false;
        auto settles = [&](std::size_t j)
        {
            if (!parallax.inView(judges[j], p_w, from_self, self_dist)) return false;
            const auto c = cellOf(judges[j], p_w);
            if (!c) return false;
            const View v = look(judges[j], *c, margin, true).view;
            if (below_only && v == View::Free && beamAbove(judges[j], c->r, p_w, ring_tan) != false)
                return false;
            gone = v == View::Free;
            return gone || v == View::Occupied;
        };
        const bool before = settledAt(self_pos, earlier, settles) != 0;
        if (before && gone) return Verdict::Gone;
        const bool after = settledAt(judges.size() - self_pos, later, settles) != 0;
        if (after && gone) return Verdict::Gone;
        return before || after ? Verdict::Held : Verdict::Unjudged;
    };
    // Below half the clearance, a mover's pillar holds the ground under it, or the mover's own
    // lowest part at the ground's height: a car's wheels and sill, a walker's feet, where a
    // ring meets them at road level (with sparse rings, which ring does depends on the LiDAR:
    // 01's car 28 m away at 16 rings, its lowest ring 0.05 m above the road around it). Each
    // such entry goes with the mover on its own evidence: not on a surface along the beams
    // (alongBeams(): ground met at grazing incidence) and seen through outside the time it was
    // seen occupied, by the beams through its own cell (ownBeamsVerdict(); either end of its
    // run, as verdict()). The ground under a mover is seen occupied by the scans before and
    // after the mover stood on it.
    // Whether entry k lies on a surface along the beams (alongBeams(), in the scan's own image).
    auto alongBeamsAt = [&](uint32_t k)
    { return alongBeams(ownJudge(), worldOf(scan.index[k]), margin); };
    // Whether the beams through entry k's own cells show it gone (ownBeamsVerdict()); never for
    // one on a surface along the beams.
    auto ownEvidence = [&](uint32_t k)
    { return !alongBeamsAt(k) && runVerdict(k, ownBeamsVerdict) == Verdict::Gone; };
    std::atomic<std::size_t> marked{0};  // the pillars' own tests run on the map's threads
    // Marks pillar p's points from half the clearance above its ground `low` up, and those
    // below with their own evidence.
    auto mark = [&](std::size_t p, int32_t low)
    {
        for (uint32_t k = scan.offsets[p]; k < scan.offsets[p + 1]; ++k)
        {
            const uint32_t i = scan.index[k];
            const double x = pts.x[i], y = pts.y[i], z = pts.z[i];
            if (is_dynamic[i] || x * x + y * y + z * z > object.range2) continue;
            if (scan.cells[k] < low + below && !ownEvidence(k)) continue;
            is_dynamic[i] = kSeenThrough;
            ++marked;
        }
    };
    std::vector<std::pair<int64_t, int64_t>> gone;  // pillars of a mover, (m, n)
    // Pillars with too little above the ground for an object, and whether the map found part
    // of one dynamic where beams had seen the place empty (ScanBuckets::seen_empty).
    struct Small
    {
        std::size_t p;
        bool seen_empty;
        std::optional<bool> lowest_hidden;  ///< lowestHidden(p), where it was asked already
    };
    std::vector<Small> small;
    // Pillars with an object clear of their ground, or a mover's, for carryOn() below (kept
    // only where it runs: carry_on).
    struct ObjectPillar
    {
        std::size_t p;
        int32_t low;  ///< its ground (ObjectTest::Found::low)
        bool gone;    ///< shown gone here, or found moving by the map
    };
    std::vector<ObjectPillar> objects;
    // What the map found dynamic of a pillar, or the test shows gone, is part of a mover, and so
    // is the pillar's lowest return where the scan could not see below it: what hid the ground
    // stands in front of it (groundHidden()), or, with a ringed sensor, the return lies on a
    // surface facing the beams above the ground carried on from in front by more than half the
    // clearance (standsAboveGround(): a car's side 24 m away, where a 16-beam LiDAR's lower
    // ring meets it 0.4 m above the road, the road at its foot behind it; within half the
    // clearance of that line, marked only on its own evidence as mark() does, it is the ground
    // at the foot of what stands there). Without rings the next return down an image column
    // is no next beam of the same sweep (`rings`, above).
    // carryOn() runs only with a ringed sensor where the judges lie on one side of the scan in
    // time.
    const bool carry_on = rings && (self_pos == 0 || self_pos == judges.size());
    auto lowestOf = [&](std::size_t p)
    { return worldOf(scan.index[ObjectTest::lowestEntry(scan, p)]); };
    auto onFace = [&](const Eigen::Vector3d& lowest)
    { return rings && standsAboveGround(ownJudge(), lowest, margin, below * res); };
    auto lowestOnFace = [&](std::size_t p) { return onFace(lowestOf(p)); };
    auto lowestHidden = [&](std::size_t p)
    {
        const Eigen::Vector3d lowest = lowestOf(p);
        return groundHidden(ownJudge(), lowest, margin, object.min_extent) || onFace(lowest);
    };
    // The ground of pillar p when its lowest return is part of what stands there (hidden).
    auto groundBelowLowest = [&](std::size_t p)
    { return object.ground(scan, p, scan.cells[ObjectTest::lowestEntry(scan, p)], true); };
    // The ground at the sensor's feet, for topSeenByOneRingGone() (ringed sensors): the lowest
    // return of the pillars nearest the sensor (within two pillars of the nearest that holds
    // any). Less than an object's height above it, nothing that far below lies in front (the
    // ground along the beams, most pillars): asked before anything in the image.
    int32_t feet = std::numeric_limits<int32_t>::min();
    if (rings)
    {
        const GridGeometry& geo = grid.geometry();
        std::vector<double> dist2(scan.pillarCount());
        double nearest2 = std::numeric_limits<double>::infinity();
        for (std::size_t p = 0; p < scan.pillarCount(); ++p)
        {
            const PillarIndex idx = unpackKey(scan.keys[p]);
            const double dx = geo.centreX(idx.m) - t.x(), dy = geo.centreY(idx.n) - t.y();
            dist2[p] = dx * dx + dy * dy;
            nearest2 = std::min(nearest2, dist2[p]);
        }
        const double within = std::sqrt(nearest2) + 2.0 * geo.pillar_size;
        for (std::size_t p = 0; p < scan.pillarCount(); ++p)
            if (dist2[p] <= within * within)
            {
                const int32_t c = scan.cells[ObjectTest::lowestEntry(scan, p)];
                feet = feet == std::numeric_limits<int32_t>::min() ? c : std::min(feet, c);
            }
    }
    // What shows above something standing in front of it, seen by one ring of a sparse LiDAR
    // (a walker's head over a parked car, 12 m from an HDL-32E): too little for an object, and
    // with no neighbouring ring on it, not known to face the beams (facesBeams()), so the rule
    // below does not test it. Where pillar p's lowest return is hidden that way (groundHidden(),
    // its surface facing the beams along its ring), stands at least an object's height above
    // the foot of what hides it (risesOverFront(): not the ground or a kerb behind a barrier),
    // and every entry of the pillar lies on a surface smooth along its ring (facesBeams() by
    // the row alone: not foliage, whose returns scatter in range from beam to beam), the
    // pillar is the top of what stands behind. Its entries are judged by the beams through
    // their own cells that passed below them (ownBeamsVerdict()): between two rings, a
    // neighbouring row's beam passes over or under such a top, and one a little above it
    // passes over it whether or not it is there. Not asked to lie off a surface along the
    // beams (alongBeams()): the next ring up passes over such a top and lands beyond, the next
    // one down meets what hides it, as on the ground. Whether that shows it gone is the
    // answer: a pillar that is not goes on to the tests of the small ones below.
    auto topSeenByOneRingGone = [&](std::size_t p)
    {
        const uint32_t low_k = ObjectTest::lowestEntry(scan, p);
        if (feet != std::numeric_limits<int32_t>::min() &&
            (static_cast<double>(scan.cells[low_k]) - feet) * res < object.min_extent)
            return false;
        // The scan's own points are in its sensor frame, its own image's.
        auto sensorPoint = [&](uint32_t i)
        { return Eigen::Vector3d(pts.x[i], pts.y[i], pts.z[i]); };
        const uint32_t low = scan.index[low_k];
        if (!risesOverFront(ownJudge(), sensorPoint(low), margin, object.min_extent)) return false;
        for (uint32_t k = scan.offsets[p]; k < scan.offsets[p + 1]; ++k)
        {
            const auto c = cellAt(*ownJudge().layout, sensorPoint(scan.index[k]));
            if (!c || !facesBeams(ownJudge(), *c, margin, true)) return false;
        }
        if (!groundHidden(ownJudge(), worldOf(low), margin, object.min_extent, true)) return false;
        std::vector<uint32_t>& tested = scratch().tested;
        tested.clear();
        for (uint32_t k = scan.offsets[p]; k < scan.offsets[p + 1]; ++k) tested.push_back(k);
        return reachesShare(
            tested, prm.free_space_fraction,
            [&](uint32_t k)
            { return runVerdict(k, [&](uint32_t i) { return ownBeamsVerdict(i, true); }); });
    };
    // Each pillar's own test (an object clear of its ground, or a top seen by one ring) reads
    // and marks its own points only, and writes what it found at its index: the pillars are
    // split over the map's threads, each with its own scratch, and what they found is gathered
    // in the pillars' order below, as one thread finds it. The scan's own image is made first
    // (ownJudge()): the threads share it.
    struct PillarFound
    {
        bool mover = false;
        std::optional<Small> small;
        std::optional<ObjectPillar> object;
    };
    std::vector<PillarFound> found_at(scan.pillarCount());
    ThreadArena* const arena = GridAccess::arena(grid);
    if (arena && scan.pillarCount() > 0) ownJudge();
    constexpr std::size_t kPillarsAtOnce = 32;
    forRanges(
        arena, scan.pillarCount(), kPillarsAtOnce,
        [&](std::size_t p0, std::size_t p1)
        {
            TestScratch range_scratch(judges.size());
            const ScratchOnThisThread on_this_thread(range_scratch);
            std::vector<uint32_t>& tested = range_scratch.tested;
            for (std::size_t p = p0; p < p1; ++p)
            {
                PillarFound& out = found_at[p];
                bool any_dynamic = false;
                for (uint32_t k = scan.offsets[p]; k < scan.offsets[p + 1] && !any_dynamic; ++k)
                    any_dynamic = is_dynamic[scan.index[k]] != 0;
                bool hidden = any_dynamic && lowestHidden(p);  // kept for the small ones (below)
                auto found =
                    object.entries(scan, p, pts, is_dynamic, tested, object.clearance, hidden);
                // Too little clear of the lowest return for an object, but enough with it where it
                // stands on a face above the ground: a car 24 m away met by two rings of a 16-beam
                // LiDAR, 0.4 and 1.2 m above the road. Asked only where it can make the object.
                // (groundHidden() asked here too removed static points, vegetation and fences, and
                // few moving ones: 03 at 16 rings SA -0.06.)
                if (!found.object && !any_dynamic && !tested.empty() && found.from_lowest &&
                    lowestOnFace(p))
                {
                    hidden = true;
                    found =
                        object.entries(scan, p, pts, is_dynamic, tested, object.clearance, true);
                }
                // What shows above something standing in front of it, on a surface that faces the
                // beams, is the top of what stands behind, however little of it shows: a walker's
                // head and shoulders over a parked car, a car's roof over a barrier. Its lowest
                // return is no ground (the scan could not see below it, groundHidden()) and faces
                // the beams (facesBeams(): not foliage, not ground met at grazing incidence), so
                // two entries make an object whatever height they span: ObjectTest::min_extent,
                // there to keep out the texture and kerbs of ground in sight, is 0 for it. So is
                // the height a floor the map holds must lie under the lowest return to be the
                // ground the test measures from, and that return is then judged too.
                if (!found.object && !any_dynamic && !tested.empty() && rings)
                {
                    const Eigen::Vector3d lowest = lowestOf(p);
                    if (groundHidden(ownJudge(), lowest, margin, object.min_extent) &&
                        facesBeams(ownJudge(), lowest, margin))
                    {
                        ObjectTest any_height = object;
                        any_height.min_extent = 0.0;
                        hidden = true;
                        found = any_height.entries(scan, p, pts, is_dynamic, tested,
                                                   object.clearance, true);
                    }
                }
                bool mover = found.moving;
                if (found.object)
                {
                    if (reachesShare(tested, prm.free_space_fraction, verdict))
                    {
                        if (!any_dynamic && (hidden || lowestHidden(p)))
                            found.low = groundBelowLowest(p);
                        mark(p, found.low);
                        mover = true;
                    }
                }
                else if (!any_dynamic && rings && topSeenByOneRingGone(p))
                    mark(p, scan.cells[ObjectTest::lowestEntry(scan, p)] - below);
                else
                {
                    bool seen_empty = false;
                    for (uint32_t k = scan.offsets[p]; k < scan.offsets[p + 1] && !seen_empty; ++k)
                        seen_empty = is_dynamic[scan.index[k]] != 0 && scan.seen_empty[k] != 0;
                    out.small = Small{p, seen_empty,
                                      any_dynamic ? std::optional<bool>(hidden) : std::nullopt};
                }
                out.mover = mover;
                if (carry_on && (found.object || mover))
                    out.object = ObjectPillar{p, found.low, mover};
            }
        });
    for (std::size_t p = 0; p < scan.pillarCount(); ++p)
    {
        const PillarFound& f = found_at[p];
        if (f.small) small.push_back(*f.small);
        if (f.mover)
        {
            const PillarIndex idx = unpackKey(scan.keys[p]);
            gone.emplace_back(idx.m, idx.n);
        }
        if (f.object) objects.push_back(*f.object);
    }
    // A mover's surface carried on across pillars. Pillars with an object are joined where the
    // scan's own image shows one surface across their boundary (oneSurface(), within the
    // margin's share for range noise, half its base): a car's side cut into pillars. Where
    // free_space_fraction of such a surface's points lie in pillars shown gone (or found moving
    // by the map), the rest moved with them: a rigid body leaves no part of itself behind. The
    // case is a car crossing the view, online: its side slides along itself, so the scan before
    // saw the part it still covers occupied, and only its leading part seen through (01's car
    // 27 m away in scan 1: 175 of its 301 points shown gone, the other 126 held, in the two
    // pillars it covered in scan 0 too). The rest goes only where the map saw it at most twice
    // (ScanBuckets::seen_twice: this scan's sighting and one other), as a mover's place is seen
    // while it passes; what stands still was seen by every scan that could, and a judge's
    // wrong "free" in one of its pillars (a traffic sign's edge) does not take the rest: the
    // surface ends at such a pillar, whose points count against the share. Only where the
    // judges lie on one side of the scan in time (online; offline, the first and last scans):
    // with judges on both sides, those of the other side see through the part the first saw
    // occupied. Only with a ringed sensor: one without rings samples a surface at new heights
    // every scan, so there what stands still is seen once or twice too (the rosette's SA -0.1
    // to -0.6 with it).
    auto carryOn = [&]
    {
        if (std::none_of(objects.begin(), objects.end(),
                         [](const ObjectPillar& o) { return o.gone; }))
            return;
        // Object pillars by key, and their samples clear of the ground (the first and last
        // point of each entry's run: its ends along the ring), with their points, repeats
        // included; found when first asked.
        std::vector<std::pair<std::pair<int64_t, int64_t>, std::size_t>> by_key;
        by_key.reserve(objects.size());
        for (std::size_t o = 0; o < objects.size(); ++o)
        {
            const PillarIndex idx = unpackKey(scan.keys[objects[o].p]);
            by_key.push_back({{idx.m, idx.n}, o});
        }
        std::sort(by_key.begin(), by_key.end());
        // The samples' cells, in the layout of the scan's own image (the grid's), from the
        // points in the sensor frame.
        const RangeImageLayout& layout = grid.imageLayout();
        std::vector<std::vector<Sample>> samples(objects.size());
        std::vector<std::size_t> points(objects.size(), 0);
        std::vector<uint8_t> sampled(objects.size(), 0), joined(objects.size(), 0);
        auto sample = [&](std::size_t o)
        {
            if (sampled[o]) return;
            sampled[o] = 1;
            const ObjectPillar& ob = objects[o];
            for (uint32_t k = scan.offsets[ob.p]; k < scan.offsets[ob.p + 1]; ++k)
            {
                const uint32_t first = scan.index[k];
                const double x = pts.x[first], y = pts.y[first], z = pts.z[first];
                if (scan.cells[k] < ob.low + object.clearance ||
                    x * x + y * y + z * z > object.range2)
                    continue;
                const uint32_t last = lastOfRun(first);
                points[o] += last - first + 1;
                for (const uint32_t i : {first, last})
                {
                    const double sx = pts.x[i], sy = pts.y[i], sz = pts.z[i];
                    const double rxy = std::sqrt(sx * sx + sy * sy);
                    const int r = rxy > 0.0 ? imageRow(layout, sz / rxy) : -1;
                    if (r >= 0)
                        samples[o].push_back({r, imageCol(layout, pseudoAzimuth(sx, sy)),
                                              static_cast<float>(std::sqrt(rxy * rxy + sz * sz))});
                }
            }
            std::sort(samples[o].begin(), samples[o].end(),
                      [](const Sample& x, const Sample& y) { return x.r < y.r; });
        };
        // Whether every entry of pillar `ob` clear of its ground was seen twice at most.
        auto seenTwiceAtMost = [&](const ObjectPillar& ob)
        {
            bool any = false;
            for (uint32_t k = scan.offsets[ob.p]; k < scan.offsets[ob.p + 1]; ++k)
            {
                if (scan.cells[k] < ob.low + object.clearance) continue;
                if (!scan.seen_twice[k]) return false;
                any = true;
            }
            return any;
        };
        const int cols = layout.cols;
        const double tol = 0.5 * margin.base;
        std::vector<uint8_t> fresh_of(objects.size());
        for (std::size_t o = 0; o < objects.size(); ++o) fresh_of[o] = seenTwiceAtMost(objects[o]);
        auto fresh = [&](std::size_t o) { return fresh_of[o] != 0; };
        // `f(v)` for each of the 8 neighbours of pillar u (of `objects`) that is in `objects`.
        auto forNeighbours = [&](std::size_t u, auto&& f)
        {
            const PillarIndex idx = unpackKey(scan.keys[objects[u].p]);
            for (int dm = -1; dm <= 1; ++dm)
                for (int dn = -1; dn <= 1; ++dn)
                {
                    if (dm == 0 && dn == 0) continue;
                    const std::pair<int64_t, int64_t> key(int64_t{idx.m} + dm, int64_t{idx.n} + dn);
                    const auto it =
                        std::lower_bound(by_key.begin(), by_key.end(), key,
                                         [](const auto& e, const std::pair<int64_t, int64_t>& k)
                                         { return e.first < k; });
                    if (it != by_key.end() && it->first == key) f(it->second);
                }
        };
        // Only a surface that holds a pillar to carry on (not gone, seen twice at most) can
        // change anything: the pillars shown gone or seen twice at most are first joined by
        // neighbourhood alone (a surface lies within such a group), and a surface is followed
        // only from a group that holds both.
        std::vector<std::size_t> group(objects.size());
        for (std::size_t o = 0; o < objects.size(); ++o) group[o] = o;
        auto root = [&](std::size_t o)
        {
            while (group[o] != o) o = group[o] = group[group[o]];
            return o;
        };
        for (std::size_t o = 0; o < objects.size(); ++o)
        {
            if (!objects[o].gone && !fresh(o)) continue;
            forNeighbours(o,
                          [&](std::size_t v)
                          {
                              if (v > o && (objects[v].gone || fresh(v))) group[root(o)] = root(v);
                          });
        }
        std::vector<uint8_t> to_carry(objects.size(), 0);  // per group's root
        for (std::size_t o = 0; o < objects.size(); ++o)
            if (!objects[o].gone && fresh(o)) to_carry[root(o)] = 1;
        // The surface through a pillar shown gone, pillar by pillar across the 8 neighbours,
        // on through the pillars shown gone and those the map saw at most twice; a pillar it
        // saw more often that the surface reaches ends it there, its points counted with the
        // surface's (once per surface: `counted_for`).
        std::vector<std::size_t> surface;
        std::vector<std::size_t> counted_for(objects.size(), objects.size());
        for (std::size_t start = 0; start < objects.size(); ++start)
        {
            if (!objects[start].gone || joined[start] || !to_carry[root(start)]) continue;
            surface.assign(1, start);
            joined[start] = 1;
            sample(start);
            std::size_t held_points = 0;  // of the pillars that end the surface
            for (std::size_t q = 0; q < surface.size(); ++q)
            {
                const std::size_t u = surface[q];
                forNeighbours(u,
                              [&](std::size_t v)
                              {
                                  if (joined[v]) return;
                                  const bool goes_on = objects[v].gone || fresh(v);
                                  if (!goes_on && counted_for[v] == start) return;
                                  sample(v);
                                  if (!oneSurface(samples[u], samples[v], cols, tol)) return;
                                  if (goes_on)
                                  {
                                      joined[v] = 1;
                                      surface.push_back(v);
                                  }
                                  else
                                  {
                                      counted_for[v] = start;
                                      held_points += points[v];
                                  }
                              });
            }
            std::size_t gone_points = 0, all_points = held_points;
            for (const std::size_t o : surface)
            {
                all_points += points[o];
                if (objects[o].gone) gone_points += points[o];
            }
            if (static_cast<double>(gone_points) <
                prm.free_space_fraction * static_cast<double>(all_points))
                continue;
            for (const std::size_t o : surface)
            {
                if (objects[o].gone) continue;
                mark(objects[o].p, objects[o].low);
                const PillarIndex idx = unpackKey(scan.keys[objects[o].p]);
                gone.emplace_back(idx.m, idx.n);
            }
        }
    };
    carryOn();
    // A mover (shown gone here, or by the map) reaches into the pillars around it with its
    // lowest parts (feet, wheels, bumpers): too little there to make an object of their own,
    // they are tested as part of it. So is what the map kept of it in its own pillar (a pillar
    // whose points the map found dynamic, but for too little to test alone: the wheels below a
    // rider, a walker's last ring), and what it kept of a pillar where it found part of one
    // dynamic because beams had seen that place empty (the map's own evidence that something
    // moved there, not only its prior: with sparse rings a car that keeps pace 28 m ahead,
    // seen by two rings, the upper one in space earlier beams passed through, the lower one
    // held static, the car's body having covered the pillar for several scans). A pillar with
    // nothing clear of its ground (all of it within the clearance of its lowest return: one
    // ring, with sparse rings a car's sill alone in its pillar) is tested from its ground up:
    // the ground there is seen occupied by the beams that meet it, a mover's low ring is seen
    // through outside its time.
    std::sort(gone.begin(), gone.end());
    auto inOrNextToGone = [&](PillarIndex idx)
    {
        for (int dm = -1; dm <= 1; ++dm)
            for (int dn = -1; dn <= 1; ++dn)
                if (std::binary_search(
                        gone.begin(), gone.end(),
                        std::pair<int64_t, int64_t>(int64_t{idx.m} + dm, int64_t{idx.n} + dn)))
                    return true;
        return false;
    };
    // Tested from its ground up, the pillar's ground is among what is tested: an entry on a
    // surface along the beams (alongBeams(), seen in the scan's own image) is not judged.
    auto groundUpVerdict = [&](uint32_t k)
    { return alongBeamsAt(k) ? Verdict::Unjudged : newVerdict(k); };
    // Whether the scan could not see below the lowest return of small pillar `sm`.
    auto hiddenBelow = [&](const Small& sm)
    { return sm.lowest_hidden ? *sm.lowest_hidden : lowestHidden(sm.p); };
    // A pillar too small for an object, tested as new (below): whether it was shown gone.
    auto testNew = [&](const Small& sm)
    {
        const std::size_t p = sm.p;
        // Not next to a mover, but new: every entry clear of its ground held static by this
        // sighting alone (ScanBuckets::seen_once; online, the first sighting there: a car 36 m
        // away behind a fence, two rings of it over the fence, each pillar too little for an
        // object). Something that stands where the beams of other scans passed is a mover; what
        // is seen for the first time from a new place (out of reach or hidden before) was not
        // seen through either, and stays. Judged as from the ground up: an entry on a surface
        // along the beams (terrain on a slope) is no evidence. (Offline, with p_empty_init under
        // 0.5, what was seen once is dynamic by the map already.)
        std::vector<uint32_t>& tested = scratch().tested;
        const auto first = scan.seen_once.begin() + scan.offsets[p];
        if (std::none_of(first, scan.seen_once.begin() + scan.offsets[p + 1],
                         [](uint8_t once) { return once != 0; }))
            return false;
        const auto found =
            object.entries(scan, p, pts, is_dynamic, tested, object.clearance, false);
        const bool fresh =
            !tested.empty() && std::all_of(tested.begin(), tested.end(),
                                           [&](uint32_t k) { return scan.seen_once[k] != 0; });
        if (!fresh || !reachesShare(tested, prm.free_space_fraction, groundUpVerdict)) return false;
        // Its lowest return is part of it where the scan could not see below it (the ground
        // out of sight: a car behind a fence, its lowest ring the pillar's lowest return).
        const bool hidden = hiddenBelow(sm);
        mark(p, hidden ? groundBelowLowest(p) : found.low);
        return true;
    };
    // A pillar too small for an object next to a mover, or where the map saw part of it empty:
    // tested as part of the mover, from its ground up where nothing is clear of it.
    auto testWithMover = [&](const Small& sm)
    {
        const std::size_t p = sm.p;
        std::vector<uint32_t>& tested = scratch().tested;
        const bool hidden = hiddenBelow(sm);
        auto found = object.entries(scan, p, pts, is_dynamic, tested, object.clearance, hidden);
        bool share = false;
        if (!tested.empty())
            share = reachesShare(tested, prm.free_space_fraction, newVerdict);
        else
        {
            found = object.entries(scan, p, pts, is_dynamic, tested, 0);
            share = reachesShare(tested, prm.free_space_fraction, groundUpVerdict);
        }
        if (share) mark(p, found.low);
    };
    // The pillars shown gone as new are a mover's too (a car crossing 36 m away, seen by two or
    // three rings: where two meet it, the pillar is shown new and gone; at its ends one ring
    // alone, its pillars' ground to the test, holds nothing to test as new): those next to them
    // that were tested as new and not shown gone are then tested with the mover, once.
    std::vector<std::pair<int64_t, int64_t>> gone_new;
    std::vector<std::size_t> tested_new;  // of `small`, tested as new and not shown gone
    for (std::size_t s = 0; s < small.size(); ++s)
    {
        const Small& sm = small[s];
        const PillarIndex idx = unpackKey(scan.keys[sm.p]);
        if (sm.seen_empty || inOrNextToGone(idx))
            testWithMover(sm);
        else if (testNew(sm))
            gone_new.emplace_back(idx.m, idx.n);
        else
            tested_new.push_back(s);
    }
    // A few pillars shown new (a handful of movers), thousands tested as new: each of the latter
    // is compared with the former, within their bounding box.
    if (gone_new.empty()) return marked;
    int64_t m0 = gone_new[0].first, m1 = m0, n0 = gone_new[0].second, n1 = n0;
    for (const auto& [m, n] : gone_new)
    {
        m0 = std::min(m0, m), m1 = std::max(m1, m);
        n0 = std::min(n0, n), n1 = std::max(n1, n);
    }
    for (const std::size_t s : tested_new)
    {
        const PillarIndex idx = unpackKey(scan.keys[small[s].p]);
        const int64_t m = idx.m, n = idx.n;
        if (m < m0 - 1 || m > m1 + 1 || n < n0 - 1 || n > n1 + 1) continue;
        if (std::any_of(gone_new.begin(), gone_new.end(),
                        [&](const auto& g)
                        { return std::abs(g.first - m) <= 1 && std::abs(g.second - n) <= 1; }))
            testWithMover(small[s]);
    }
    return marked;
}

}  // namespace hif::detail
