// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FreeSpace.h
 * @brief  The free-space test of a classified scan against the other scans of a window
 *         (Params::free_space_window).
 */
#pragma once

#include <cstddef>
#include <vector>

#include "hif/FreeSpaceTest.h"
#include "hif/PillarGrid.h"
#include "hif/detail/InsertSteps.h"

namespace hif::detail
{
/** The value markSeenThrough() writes into `is_dynamic`: dynamic, and shown gone by the test
 *  (the caller counts them once their repeats have followed, then writes 1). */
constexpr uint8_t kSeenThrough = 3;

/** Marks, in `is_dynamic` (one entry per input point, 0 = static so far), the points of the
 *  pillars of `scan` whose tested points the scans of `test` showed gone (see
 *  Params::free_space_window and FreeSpaceTest for which scans judge) with kSeenThrough, for
 *  the entries of `scan` only (their repeats follow them). Returns the number of entries
 *  marked; `judges` is set to the number of the test's scans that judged. */
std::size_t markSeenThrough(const PillarGrid& grid, const ScanBuckets& scan, const PointsView& pts,
                            const Eigen::Isometry3d& sensor_to_world, const FreeSpaceTest& test,
                            std::vector<uint8_t>& is_dynamic, std::size_t& judges);

}  // namespace hif::detail
