// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Pillar.h
 * @brief  A pillar's height intervals (Eq. 4) and its Bayes update by one scan (Eq. 8-18).
 *
 * Heights are integers: cell k covers [k r, (k+1) r) with r = Params::height_resolution.
 */
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "hif/Params.h"

namespace hif
{
/** Height cells [lo, hi) seen occupied in one pillar by one scan (h^t without probability). */
struct Span
{
    int32_t lo = 0;
    int32_t hi = 0;
    friend bool operator==(const Span& a, const Span& b) { return a.lo == b.lo && a.hi == b.hi; }
};

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

/** "No height limit": a scan whose field of view covers every height of the pillar. */
constexpr int32_t kAllHeights = std::numeric_limits<int32_t>::max();

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

[[nodiscard]] inline double logit(double p) { return std::log(p / (1.0 - p)); }
[[nodiscard]] inline double logistic(double l) { return 1.0 / (1.0 + std::exp(-l)); }

/** Bayes filter of Eq. 5, in probability form: Ps p / (Ps p + Pd (1 - p)). */
[[nodiscard]] inline double bayesFilter(double p, double ps, double pd)
{
    return ps * p / (ps * p + pd * (1.0 - p));
}

/** Eq. 5-6 in log-odds form: Bayesfilter(p, Ps, Pd) is logit(p) + log(Ps / Pd), so an
 *  observation adds `hit` = log(alpha / beta) and a miss adds `miss` = log((1-alpha)/(1-beta));
 *  clipping to [p_min, p_max] (Eq. 17) is clamping to [lmin, lmax]. */
struct LogOddsModel
{
    float hit = 0.0f;
    float miss = 0.0f;
    float lmin = 0.0f;
    float lmax = 0.0f;
    float empty_init = 0.0f;
    bool lhp = true;
    bool hhp = true;
    bool unseen_prior = true;

    [[nodiscard]] static LogOddsModel fromParams(const Params& p);
    [[nodiscard]] float clamp(float l) const { return l < lmin ? lmin : (l > lmax ? lmax : l); }
};

/** Heights (already as cells, sorted ascending) of one pillar in one scan merged into spans
 *  (Eq. 4): consecutive cells whose empty gap is at most `gap_cells` share a span; each span is
 *  widened by `pad_cells` on both sides, and spans that then touch or overlap are joined.
 *  Writes the spans to `out`, which must have room for `n` (there are never more), and
 *  returns their count. */
std::size_t buildSpans(const int32_t* sorted_cells, std::size_t n, int32_t gap_cells,
                       int32_t pad_cells, Span* out);

/** Updates global pillar `g` with the spans `t` (sorted, disjoint, non-empty) seen by one
 *  scan: elementary intervals from the union of endpoints (Eq. 9-10), the three overlap cases
 *  (Eq. 11-14), LHP (Eq. 15-16), clipping (Eq. 17-18), then p_empty (Eq. 8). Touching
 *  results of equal log-odds are merged (lossless); then the count is capped at `max_intervals`
 *  (see capIntervals). `scratch` is reused storage. `ceiling` is the first height cell above
 *  what the scan could see in this pillar (kAllHeights: no limit); with model.hhp, intervals
 *  at or above it are kept as they are, and with model.unseen_prior, new intervals at or above
 *  the pillar's previous seen_top start from model.empty_init. */
void updatePillar(Pillar& g, const Span* t, std::size_t nt, const LogOddsModel& model,
                  std::size_t max_intervals, std::vector<Interval>& scratch,
                  int32_t ceiling = kAllHeights);

/** Merges neighbours of iv[0, n) until at most `max_intervals` remain: each step joins the
 *  pair with the smallest gap between them (ties: the smallest log-odds difference) into one
 *  interval that spans both, with the length-weighted mean of their log-odds. Returns the new
 *  count; the result is iv[0, count). */
std::size_t capIntervals(Interval* iv, std::size_t n, std::size_t max_intervals);

/** Joins touching neighbours of equal log-odds in iv[0, n) (lossless), restoring the invariant
 *  on Pillar after log-odds changed in place. Returns the new count. */
std::size_t joinEqualNeighbours(Interval* iv, std::size_t n);

/** Interval of `p` containing height cell `z`, or nullptr. */
[[nodiscard]] const Interval* findInterval(const Pillar& p, int32_t z);

}  // namespace hif
