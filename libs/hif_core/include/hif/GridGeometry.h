// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   GridGeometry.h
 * @brief  The fixed geometry of a HIF map: the global pillar grid (Eq. 1-2) and the height
 *         cells of interval endpoints. Set when a map is created; never changes after.
 */
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include "hif/FieldTable.h"
#include "hif/PillarIndex.h"

namespace hif
{
/** Pillar P_mn covers [origin_x + m pillar_size, origin_x + (m+1) pillar_size) x
 *  [origin_y + n pillar_size, ...) (Eq. 2); height cell k covers [k height_resolution,
 *  (k+1) height_resolution). */
struct GridGeometry
{
    /** The finest pillar edge and height cell, metres: a micrometre. Finer has no meaning for a
     *  LiDAR (its range noise is centimetres), and the inverse of a cell must stay finite (a
     *  subnormal height_resolution made it infinite, and heights NaN). */
    static constexpr double kMinCell = 1e-6;

    /** Pillar edge length in x and y, metres (Eq. 1-2; paper: 1 m). */
    double pillar_size = 1.0;
    /** Global grid origin O = (x_o, y_o) on the XY plane, metres (Eq. 1). */
    double origin_x = 0.0;
    double origin_y = 0.0;
    /** Vertical resolution, metres: interval endpoints are snapped to multiples of it, so an
     *  interval is a run of whole height cells [b, t). Not in the paper (which keeps exact
     *  heights); with it, overlap tests are exact and intervals per pillar are bounded. */
    double height_resolution = 0.05;

    /** The fields, for loops over them (see FieldTable.h). */
    [[nodiscard]] static const std::array<Field<GridGeometry>, 4>& fields();

    /** Throws std::invalid_argument naming the first invalid field and its value; also when the
     *  world's origin (0, 0) has no pillar index (|origin| / pillar_size must be below 2^31),
     *  which would leave every point of a real map outside the grid. */
    void validate() const
    {
        constexpr const char* kOwner = "hif::GridGeometry";
        validateFields(*this, kOwner);
        constexpr double kIndexRange = 2147483648.0;  // 2^31 pillars on each side of the origin
        if (!(std::abs(origin_x) / pillar_size < kIndexRange))
            throwInvalid(kOwner, "origin_x", origin_x,
                         "such that |origin_x| / pillar_size < 2^31 (the grid's index range)");
        if (!(std::abs(origin_y) / pillar_size < kIndexRange))
            throwInvalid(kOwner, "origin_y", origin_y,
                         "such that |origin_y| / pillar_size < 2^31 (the grid's index range)");
    }

    /** Pillar containing world (x, y) (Eq. 1); nullopt if the index does not fit in int32. */
    [[nodiscard]] std::optional<PillarIndex> pillarOf(double x, double y) const
    {
        const auto m = quantize(x, origin_x, pillar_size);
        const auto n = quantize(y, origin_y, pillar_size);
        if (!m || !n) return std::nullopt;
        return PillarIndex{*m, *n};
    }
    /** Height cell containing z; nullopt if it does not fit in int32. */
    [[nodiscard]] std::optional<int32_t> heightCellOf(double z) const
    {
        return quantize(z, 0.0, height_resolution);
    }
    /** Height of the bottom of cell `k`, metres. */
    [[nodiscard]] double cellBottom(int32_t k) const { return k * height_resolution; }
    /** World x of the centre of pillar column `m` (y: centreY). */
    [[nodiscard]] double centreX(int32_t m) const { return origin_x + (m + 0.5) * pillar_size; }
    [[nodiscard]] double centreY(int32_t n) const { return origin_y + (n + 0.5) * pillar_size; }

    friend bool operator==(const GridGeometry& a, const GridGeometry& b)
    {
        return fieldsEqual(a, b);
    }
    friend bool operator!=(const GridGeometry& a, const GridGeometry& b) { return !(a == b); }
};

static_assert(memberCount<GridGeometry>() ==
                  std::tuple_size_v<std::decay_t<decltype(GridGeometry::fields())>>,
              "every member of hif::GridGeometry needs its row in GridGeometry::fields()");

inline const std::array<Field<GridGeometry>, 4>& GridGeometry::fields()
{
    using G = GridGeometry;
    static const std::array<Field<G>, 4> table{{
        {"pillar_size", &G::pillar_size, Bounds::atLeast(kMinCell), 0, "Pillar edge [m] (Eq. 1-2)"},
        {"origin_x", &G::origin_x, Bounds::any(), 0, "Grid origin x [m] (Eq. 1)"},
        {"origin_y", &G::origin_y, Bounds::any(), 0, "Grid origin y [m] (Eq. 1)"},
        {"height_resolution", &G::height_resolution, Bounds::atLeast(kMinCell), 0,
         "Interval endpoints are multiples of this [m]"},
    }};
    return table;
}

}  // namespace hif
