// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   WidePoints.h
 * @brief  The readers' one rule for float64 coordinates: kept as float32 offsets from the
 *         file's first finite point (PcdCloud::origin).
 */
#pragma once

#include <cmath>
#include <cstddef>

#include "hif/io/CloudFiles.h"

namespace hif::io
{
/** Stores points into `out`; with `wide` (the file's coordinates are float64), relative to the
 *  first finite point stored, which becomes out.origin; otherwise as they are. */
class WidePoints
{
public:
    WidePoints(PcdCloud& out, bool wide) : out_(out), have_origin_(!wide) {}

    void store(std::size_t p, double x, double y, double z)
    {
        if (!have_origin_ && std::isfinite(x) && std::isfinite(y) && std::isfinite(z))
        {
            out_.origin = Eigen::Vector3d(x, y, z);
            have_origin_ = true;
        }
        out_.x[p] = static_cast<float>(x - out_.origin.x());
        out_.y[p] = static_cast<float>(y - out_.origin.y());
        out_.z[p] = static_cast<float>(z - out_.origin.z());
    }

private:
    PcdCloud& out_;
    bool have_origin_;
};

}  // namespace hif::io
