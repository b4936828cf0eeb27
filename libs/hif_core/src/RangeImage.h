// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RangeImage.h
 * @brief  A scan's range image for the see-through and free-space tests: the nearest return in
 *         every cell of directions around the sensor (RangeImageLayout: from its sensor model).
 */
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "hif/PillarGrid.h"
#include "hif/SensorModel.h"

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

/** Cell of a range image laid out as `l` for (pseudo-azimuth, tan(elevation)), or -1 outside
 *  its rows. */
inline int imageCell(const RangeImageLayout& l, double paz, double tan_el)
{
    if (!(tan_el >= l.tan_min && tan_el < l.tan_max)) return -1;
    const int c = std::min(l.cols - 1, static_cast<int>(paz * (l.cols / 4.0)));
    const int r = std::min(l.rows - 1, static_cast<int>((tan_el - l.tan_min) / l.tan_res));
    return r * l.cols + c;
}

/** The see-through test of one pillar against a scan's range image (nearest return per cell,
 *  metres): did a beam of the scan pass through heights [lo, hi) (height cells) of the pillar
 *  whose axis is base + up * z in the sensor frame? Yes when, in the direction of the pillar's
 *  centre (and half_cols columns on each side) between those heights, some return lies farther
 *  than the pillar by more than `margin` and none lies within `margin` of it (something
 *  there); a return nearer than that is occlusion and no cell with a return is no evidence. */
struct BeamGate
{
    const RangeImageLayout* layout = nullptr;
    const float* image = nullptr;
    Eigen::Vector3d base = Eigen::Vector3d::Zero();
    Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    double margin = 0.0;
    double res = 0.0;   ///< height cell, metres
    int half_cols = 0;  ///< columns looked along on each side of the centre's

    [[nodiscard]] bool passedThrough(int32_t lo, int32_t hi) const { return test(lo, hi, true); }
    /** Whether any beam between those heights returned beyond the pillar (returns near it do
     *  not veto): some of the pillar's free space was seen empty. */
    [[nodiscard]] bool anyPassedThrough(int32_t lo, int32_t hi) const
    {
        return test(lo, hi, false);
    }

private:
    [[nodiscard]] bool test(int32_t lo, int32_t hi, bool veto) const
    {
        const RangeImageLayout& l = *layout;
        const Eigen::Vector3d p = base + up * (lo * res);
        const double hi_z = base.z() + up.z() * (hi * res);
        const double d = std::sqrt(p.x() * p.x() + p.y() * p.y());
        if (d == 0.0) return false;
        const double paz = pseudoAzimuth(p.x(), p.y());
        const int k0 = imageCell(l, paz, std::max(p.z() / d, l.tan_min));
        const int k1 = imageCell(l, paz, std::min(hi_z / d, l.tan_max - 1e-12));
        if (k0 < 0 || k1 < 0) return false;
        const int c0 = k0 % l.cols;
        const double d2 = d * d;
        bool through = false;
        // From the top row down: beams above what stands in the pillar pass first (an early
        // end for anyPassedThrough()). Distances compared squared: no square root per row.
        for (int row = k1 / l.cols; row >= k0 / l.cols; --row)
        {
            const double tan_el = l.tan_min + (row + 0.5) * l.tan_res;
            const double dist2 = d2 * (1.0 + tan_el * tan_el);  // to the pillar's axis, squared
            for (int dc = -half_cols; dc <= half_cols; ++dc)
            {
                const int c = (c0 + dc + l.cols) % l.cols;
                const double r = image[static_cast<std::size_t>(row) * l.cols + c];
                if (!std::isfinite(r)) continue;  // no return: no evidence
                const double beyond = r - margin, near = r + margin;
                if (beyond > 0.0 && beyond * beyond > dist2)
                {
                    if (!veto) return true;
                    through = true;
                }
                else if (veto && near * near > dist2)
                    return false;  // something is there
                // else: occluded by something closer, no evidence
            }
        }
        return through;
    }
};

/** Fills `img` (layout `l`, row-major) with the nearest return of `points`
 *  (sensor frame) in every cell; +infinity where no return falls. Four points at a time with
 *  AVX when useAvx() (the same bits as one at a time). */
void buildRangeImage(const RangeImageLayout& l, const PointsView& points, std::vector<float>& img);

/** "No return" in a range image in centimetres. */
constexpr uint16_t kNoReturnCm = 0xFFFF;

/** buildRangeImage() in centimetres (rounded; kNoReturnCm where no return, or beyond 655 m). */
void buildRangeImageCm(const RangeImageLayout& l, const PointsView& points,
                       std::vector<uint16_t>& img);

}  // namespace hif::detail
