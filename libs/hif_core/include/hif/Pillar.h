// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Pillar.h
 * @brief  A pillar of the global map: its p_empty and its sorted height intervals, each with
 *         the log-odds of being static (Eq. 4).
 *
 * Heights are integers: cell k covers [k r, (k+1) r) with r = GridGeometry::height_resolution.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace hif
{
/** Height interval h_k = (b_k, t_k, p_k) of a global pillar: cells [lo, hi), and the log-odds
 *  of P(static). */
struct Interval
{
    int32_t lo = 0;
    int32_t hi = 0;
    float logodds = 0.0f;
    friend bool operator==(const Interval& a, const Interval& b)
    {
        return a.lo == b.lo && a.hi == b.hi && a.logodds == b.logodds;
    }
};

/** Global pillar P_mn = (p_empty, H_mn) (Eq. 4), plus the highest height cell that any scan
 *  could see in it so far (`seen_top`, exclusive; used by the unseen-height prior).
 *  Invariant: intervals are sorted by lo, non-empty (lo < hi) and non-overlapping
 *  (intervals[k].hi <= intervals[k+1].lo); two touching intervals never have equal log-odds. */
struct Pillar
{
    float logodds_empty = 0.0f;
    int32_t seen_top = std::numeric_limits<int32_t>::min();
    std::vector<Interval> intervals;
    friend bool operator==(const Pillar& a, const Pillar& b)
    {
        return a.logodds_empty == b.logodds_empty && a.seen_top == b.seen_top &&
               a.intervals == b.intervals;
    }
};

/** Interval of `p` containing height cell `z`, or nullptr. */
[[nodiscard]] const Interval* findInterval(const Pillar& p, int32_t z);

[[nodiscard]] inline double logit(double p) { return std::log(p / (1.0 - p)); }
[[nodiscard]] inline double logistic(double l) { return 1.0 / (1.0 + std::exp(-l)); }

}  // namespace hif
