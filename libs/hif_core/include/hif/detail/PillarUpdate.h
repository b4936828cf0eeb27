// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarUpdate.h
 * @brief  The per-pillar steps of an insertion: a scan's heights into spans (Eq. 4), and the
 *         Bayes update of a global pillar by them (Eq. 5-18). Internal to hif_core; public to
 *         its tests and benchmark.
 */
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "hif/Params.h"
#include "hif/Pillar.h"

namespace hif
{
class PillarGrid;
}

namespace hif::detail
{
/** Height cells [lo, hi) seen occupied in one pillar by one scan (h^t without probability). */
struct Span
{
    int32_t lo = 0;
    int32_t hi = 0;
    friend bool operator==(const Span& a, const Span& b) { return a.lo == b.lo && a.hi == b.hi; }
};

/** "No height limit": a scan whose field of view covers every height of the pillar. */
constexpr int32_t kAllHeights = std::numeric_limits<int32_t>::max();

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
    /** Params::ground_max_slope_deg as a tangent (0: off) and Params::ground_max_step. */
    double ground_slope_tan = 0.0;
    double ground_step = 0.0;

    [[nodiscard]] static LogOddsModel fromParams(const Params& p);
    /** The model `grid` updates with: its parameters, a new pillar's p_empty that in effect
     *  (PillarGrid::pEmptyInit(): it depends on the sensor model too). */
    [[nodiscard]] static LogOddsModel of(const PillarGrid& grid);
    [[nodiscard]] float clamp(float l) const { return l < lmin ? lmin : (l > lmax ? lmax : l); }
    /** Whether an interval of log-odds `l` is held static firmly: within two misses of p_max
     *  (seen at the top, and missed at most twice since). */
    [[nodiscard]] bool heldFirmly(float l) const { return l >= lmax + 2.0f * miss; }
    /** Whether a miss (Eq. 13, clipped by Eq. 17-18) changes log-odds `l`: not at p_min, so
     *  where it does not, nobody needs to ask whether a beam passed. */
    [[nodiscard]] bool missChanges(float l) const { return clamp(l + miss) != l; }
};

/** Heights (already as cells, sorted ascending) of one pillar in one scan merged into spans
 *  (Eq. 4), with the widths of each height: `widthsAt(h)` gives the `gap` and `pad` (cells) at
 *  height h, a cell index (h + 0.5 the middle of cell h; between two cells, their middle), and
 *  no gap is less than `least_gap` (it is asked only of cells farther apart). Consecutive cells
 *  whose empty gap is at most the gap at their middle share a span; each span is widened below
 *  by the pad at its lowest cell and above by the pad at its highest, and spans that then touch
 *  or overlap are joined. Writes the spans to `out`, which must have room for `n` (there are
 *  never more), and returns their count. */
template <class WidthsAt>
std::size_t spansFromCells(const int32_t* sorted_cells, std::size_t n, WidthsAt&& widthsAt,
                           int32_t least_gap, Span* out)
{
    if (n == 0) return 0;
    std::size_t count = 0;
    // Work in int64 so padding near the int32 limits cannot overflow; spans are clamped back.
    constexpr int64_t kLo = std::numeric_limits<int32_t>::min();
    constexpr int64_t kHi = std::numeric_limits<int32_t>::max();
    auto emit = [&](int64_t lo, int64_t last)  // cells lo to last
    {
        const int64_t a = std::max<int64_t>(kLo, lo - widthsAt(static_cast<double>(lo)).pad);
        const int64_t b =
            std::min<int64_t>(kHi, last + 1 + widthsAt(static_cast<double>(last)).pad);
        if (count > 0 && out[count - 1].hi >= a)
            out[count - 1].hi = static_cast<int32_t>(std::max<int64_t>(out[count - 1].hi, b));
        else
            out[count++] = {static_cast<int32_t>(a), static_cast<int32_t>(b)};
    };
    int64_t lo = sorted_cells[0];
    int64_t last = sorted_cells[0];
    for (std::size_t i = 1; i < n; ++i)
    {
        const int64_t c = sorted_cells[i];
        // Cells last and c leave (c - last - 1) empty cells between them.
        if (c - last - 1 > least_gap &&
            c - last - 1 > widthsAt(0.5 * static_cast<double>(last + c)).gap)
        {
            emit(lo, last);
            lo = c;
        }
        last = c;
    }
    emit(lo, last);
    return count;
}

/** The Bayes update of global pillars by one scan's spans, with its reusable storage. One per
 *  thread. */
struct BeamGate;

class PillarUpdater
{
public:
    PillarUpdater(const LogOddsModel& model, std::size_t max_intervals)
        : model_(model), max_intervals_(max_intervals)
    {
    }

    /** Updates pillar `g` with the spans `t` (sorted, disjoint, non-empty) seen by one scan:
     *  elementary intervals from the union of endpoints (Eq. 9-10), the three overlap cases
     *  (Eq. 11-14), LHP (Eq. 15-16), clipping (Eq. 17-18), then p_empty (Eq. 8). Touching
     *  results of equal log-odds are merged (lossless); then the count is capped (see
     *  capIntervals()). `ceiling` is the first height cell above what the scan could see in
     *  this pillar (kAllHeights: no limit); with the model's hhp, intervals at or above it are
     *  kept as they are, and with its unseen_prior, new intervals at or above the pillar's
     *  previous seen_top start from the model's empty_init. With `gate`, an interval (or the
     *  part of it) the scan did not hit gets its Eq. 13 miss only where a beam of the scan
     *  passed through it (BeamGate::passedCells()); elsewhere the scan could not see it and
     *  it is kept as it is; p_empty is lowered (Eq. 8) only when some beam passed through
     *  the pillar between its lowest content and `ceiling` (BeamGate::seenEmpty()), and the
     *  cells those beams crossed are recorded (Pillar::passed); a new interval that no earlier
     *  beam passed within the merge gap of starts from the model's empty_init. */
    void update(Pillar& g, const Span* t, std::size_t nt, int32_t ceiling = kAllHeights,
                const BeamGate* gate = nullptr);

    /** New settings; the storage is kept. */
    void reset(const LogOddsModel& model, std::size_t max_intervals)
    {
        model_ = model;
        max_intervals_ = max_intervals;
    }

    [[nodiscard]] const LogOddsModel& model() const { return model_; }

private:
    LogOddsModel model_;
    std::size_t max_intervals_;
    std::vector<Interval> pieces_;  ///< the sweep's output, reused
    std::vector<Span> passed_;      ///< cells beams passed through (BeamGate), reused
};

/** Merges neighbours of iv[0, n) until at most `max_intervals` remain: each step joins the
 *  pair with the smallest gap between them (ties: the smallest log-odds difference, then the
 *  lowest pair) into one interval that spans both, with the length-weighted mean of their
 *  log-odds. Returns the new count; the result is iv[0, count). */
std::size_t capIntervals(Interval* iv, std::size_t n, std::size_t max_intervals);

/** Joins touching neighbours of equal log-odds in iv[0, n) (lossless), restoring the invariant
 *  on Pillar after log-odds changed in place. Returns the new count. */
std::size_t joinEqualNeighbours(Interval* iv, std::size_t n);

}  // namespace hif::detail
