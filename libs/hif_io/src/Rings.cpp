// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Rings.cpp
 * @brief  Rings from the point order.
 */
#include "hif/io/Rings.h"

#include <cmath>

namespace hif::io
{
namespace
{
// A ring sweeps a whole turn (the first and the last of a scan, part of one); points that
// jitter across the seam at +-pi sweep a few hundredths of a radian between their wraps.
constexpr double kMinSweep = 0.2;  // radians, about 11 degrees
}  // namespace

std::vector<uint32_t> ringOfEachPoint(const Cloud& scan)
{
    std::vector<uint32_t> ring(scan.size(), 0);
    uint32_t current = 0;
    bool have_prev = false;
    double prev = 0.0, swept = 0.0;  // azimuth of the point before; how far this ring went
    for (std::size_t i = 0; i < scan.size(); ++i)
    {
        const double x = scan.x[i], y = scan.y[i];
        if (std::isfinite(x) && std::isfinite(y) && (x != 0.0 || y != 0.0))
        {
            const double az = std::atan2(y, x);
            if (have_prev)
            {
                const double step = az - prev;
                if (std::abs(step) > M_PI && swept >= kMinSweep)
                {
                    ++current;  // wrapped round: the next ring
                    swept = 0.0;
                }
                else if (std::abs(step) <= M_PI)
                    swept += std::abs(step);
            }
            prev = az;
            have_prev = true;
        }
        ring[i] = current;
    }
    return ring;
}

}  // namespace hif::io
