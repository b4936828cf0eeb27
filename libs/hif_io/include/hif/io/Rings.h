// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Rings.h
 * @brief  The rings of a spinning LiDAR's scan, recovered from the order of its points (KITTI's
 *         .bin files hold them ring after ring, each ring swept in one direction).
 */
#pragma once

#include <cstdint>
#include <vector>

#include "hif/io/Cloud.h"

namespace hif::io
{
/** For each point of `scan` (sensor frame, in file order), the number of its ring: a ring ends
 *  where the azimuth jumps by more than pi (it wrapped round), once the ring has swept some
 *  degrees (11), so that points jittering across the seam do not start rings of their own.
 *  Points without an azimuth (at the axis, or not finite) stay in the current ring. A scan that
 *  starts mid-ring has its first and last physical ring split in two. */
[[nodiscard]] std::vector<uint32_t> ringOfEachPoint(const Cloud& scan);

}  // namespace hif::io
