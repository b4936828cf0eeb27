// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   HeightCells.h
 * @brief  Height cells of one pillar in one scan: sorted and deduplicated, and metres turned
 *         into whole cells.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "hif/PillarIndex.h"

namespace hif::detail
{
/** floor(v) for v >= -2^31, saturated at INT32_MAX (a gap or padding wider than any map). */
inline int32_t floorCells(double v)
{
    int32_t c = std::numeric_limits<int32_t>::max();
    return floorToInt32(v, c) ? c : std::numeric_limits<int32_t>::max();
}

/** ceil(v) for v > -1, saturated at INT32_MAX. */
inline int32_t ceilCells(double v)
{
    int32_t c = 0;
    return floorToInt32(-v, c) && c > std::numeric_limits<int32_t>::min()
               ? -c
               : std::numeric_limits<int32_t>::max();
}

/** Sorts cells[0, n) ascending and removes duplicates in place; returns the distinct count.
 *  Pillars near the sensor hold hundreds of points in a few height cells: for those, a bitmap
 *  over the pillar's height range is O(n + range / 64) instead of a comparison sort. */
std::size_t sortDistinct(int32_t* cells, std::size_t n);

}  // namespace hif::detail
