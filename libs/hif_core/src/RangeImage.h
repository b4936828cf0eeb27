// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RangeImage.h
 * @brief  A scan's range image for the see-through misses: the nearest return in every cell
 *         of about 0.2 x 0.2 degrees around the sensor.
 */
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hif/PillarGrid.h"

namespace hif::detail
{
/** A monotone stand-in for the azimuth of (x, y), in [0, 4) ("diamond angle"): one division
 *  instead of an atan2. Range-image columns are uniform in it, 0.2 degree wide on average. */
inline double pseudoAzimuth(double x, double y)
{
    const double s = std::abs(x) + std::abs(y);
    if (s == 0.0) return 0.0;
    const double a = y / s;
    return x >= 0.0 ? (y >= 0.0 ? a : 4.0 + a) : 2.0 - a;
}

// Range image of the see-through misses: columns uniform in pseudoAzimuth(), rows uniform in
// tan(elevation) for elevations in [-30, +15) degrees, 0.2 degree at the horizon.
constexpr int kImageCols = 1800;
constexpr double kTanMin = -0.57735026918962576;  // tan(-30 degrees)
constexpr double kTanMax = 0.26794919243112270;   // tan(15 degrees)
constexpr double kTanRes = 0.2 * M_PI / 180.0;
constexpr int kImageRows = static_cast<int>((kTanMax - kTanMin) / kTanRes) + 1;

/** Cell of the range image for (pseudo-azimuth, tan(elevation)), or -1 outside its rows. */
inline int imageCell(double paz, double tan_el)
{
    if (!(tan_el >= kTanMin && tan_el < kTanMax)) return -1;
    const int c = std::min(kImageCols - 1, static_cast<int>(paz * (kImageCols / 4.0)));
    const int r = std::min(kImageRows - 1, static_cast<int>((tan_el - kTanMin) / kTanRes));
    return r * kImageCols + c;
}

/** Fills `img` (kImageCols x kImageRows, row-major) with the nearest return of `points`
 *  (sensor frame) in every cell; +infinity where no return falls. Four points at a time with
 *  AVX when useAvx() (the same bits as one at a time). */
void buildRangeImage(const PointsView& points, std::vector<float>& img);

/** "No return" in a range image in centimetres. */
constexpr uint16_t kNoReturnCm = 0xFFFF;

/** buildRangeImage() in centimetres (rounded; kNoReturnCm where no return, or beyond 655 m). */
void buildRangeImageCm(const PointsView& points, std::vector<uint16_t>& img);

}  // namespace hif::detail
