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

/** The height cells of a pillar that beams were seen passing through (Params::
 *  miss_needs_beam): where its p_empty is evidence. One bit a cell, in a window of kCells
 *  cells from `base`, the lowest cell passed through so far (a pillar's free space runs from
 *  its ground up, 6.4 m at the default 5 cm cells); cells above the window are not recorded
 *  (taken as never passed through). */
struct PassedCells
{
    static constexpr int32_t kNone = std::numeric_limits<int32_t>::min();  ///< nothing yet
    static constexpr int32_t kCells = 128;

    int32_t base = kNone;
    uint64_t bits[2] = {0, 0};

    /** Records that beams passed through cells [lo, hi) (the lowest cell, kNone's value, is
     *  not recorded). */
    void add(int32_t lo, int32_t hi);
    /** Whether beams passed through any cell of [lo, hi). */
    [[nodiscard]] bool any(int32_t lo, int32_t hi) const;

    friend bool operator==(const PassedCells& a, const PassedCells& b)
    {
        return a.base == b.base && a.bits[0] == b.bits[0] && a.bits[1] == b.bits[1];
    }
};

/** Global pillar P_mn = (p_empty, H_mn) (Eq. 4), plus the highest height cell that any scan
 *  could see in it so far (`seen_top`, exclusive; used by the unseen-height prior) and the
 *  cells beams passed through (`passed`: a new interval elsewhere does not start from
 *  p_empty). Invariant: intervals are sorted by lo, non-empty (lo < hi) and non-overlapping
 *  (intervals[k].hi <= intervals[k+1].lo); two touching intervals never have equal log-odds. */
struct Pillar
{
    float logodds_empty = 0.0f;
    int32_t seen_top = std::numeric_limits<int32_t>::min();
    PassedCells passed;
    /** Where in the pillar what stands above its ground was seen: the mean of its last
     *  kObjectSightings sightings (ScanBuckets::object_at; a few scans, so that it follows what
     *  stands there now), as offsets from the pillar's low corner along m and n in steps of
     *  1/256 of the pillar (placeOf()), and how many sightings the mean holds (0: none yet).
     *  What the map holds there firmly is judged by the beams toward this place
     *  (BeamGate::object_axis), not toward the pillar's centre. */
    uint8_t object_u = 0, object_v = 0;
    uint16_t object_weight = 0;
    static constexpr uint16_t kObjectSightings = 32;
    /** The offset (a fraction of the pillar) of place step `q` (object_u, object_v): the
     *  middle of the step. */
    [[nodiscard]] static double placeOf(uint32_t q) { return (q + 0.5) / 256.0; }
    std::vector<Interval> intervals;
    friend bool operator==(const Pillar& a, const Pillar& b)
    {
        return a.logodds_empty == b.logodds_empty && a.seen_top == b.seen_top &&
               a.passed == b.passed && a.object_u == b.object_u && a.object_v == b.object_v &&
               a.object_weight == b.object_weight && a.intervals == b.intervals;
    }
};

/** Interval of `p` containing height cell `z`, or nullptr. */
[[nodiscard]] const Interval* findInterval(const Pillar& p, int32_t z);

[[nodiscard]] inline double logit(double p) { return std::log(p / (1.0 - p)); }
[[nodiscard]] inline double logistic(double l) { return 1.0 / (1.0 + std::exp(-l)); }

}  // namespace hif
