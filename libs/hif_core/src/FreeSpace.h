// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FreeSpace.h
 * @brief  The free-space test of a classified scan against the other scans of a window
 *         (Params::free_space_window).
 */
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "hif/PillarGrid.h"
#include "hif/ScanWindow.h"
#include "hif/detail/InsertSteps.h"

namespace hif::detail
{
/** Marks, in `is_dynamic` (one entry per input point, 0 = static so far), the points of the
 *  pillars of `scan` whose tested points other scans of `window` showed gone (see
 *  Params::free_space_window), for the entries of `scan` only (their repeats follow them).
 *  `self` is the window id of the scan classified, if it has one: it is not its own evidence,
 *  and only scans within free_space_window of it count; without, every scan of the window
 *  counts. Returns the number of entries marked. */
std::size_t markSeenThrough(const PillarGrid& grid, const ScanBuckets& scan, const PointsView& pts,
                            const Eigen::Isometry3d& sensor_to_world, const ScanWindow& window,
                            std::optional<std::size_t> self, std::vector<uint8_t>& is_dynamic);

}  // namespace hif::detail
