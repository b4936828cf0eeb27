// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarUpdate.cpp
 * @brief  Interval construction and the per-pillar Bayes update (Eq. 4, 8-18).
 */
#include "hif/detail/PillarUpdate.h"

#include "RangeImage.h"
#include "hif/PillarGrid.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace hif::detail
{
LogOddsModel LogOddsModel::fromParams(const Params& p)
{
    LogOddsModel m;
    m.hit = static_cast<float>(std::log(p.alpha / p.beta));
    m.miss = static_cast<float>(std::log((1.0 - p.alpha) / (1.0 - p.beta)));
    m.lmin = static_cast<float>(logit(p.p_min));
    m.lmax = static_cast<float>(logit(p.p_max));
    m.empty_init = static_cast<float>(logit(p.p_empty_init));
    m.lhp = p.low_height_preservation;
    m.hhp = p.high_height_preservation;
    m.unseen_prior = p.unseen_height_prior;
    m.ground_slope_tan = std::tan(p.ground_max_slope_deg * M_PI / 180.0);
    m.ground_step = p.ground_max_step;
    return m;
}

LogOddsModel LogOddsModel::of(const PillarGrid& grid)
{
    LogOddsModel m = fromParams(grid.params());
    m.empty_init = static_cast<float>(logit(grid.pEmptyInit()));
    return m;
}

void PillarUpdater::update(Pillar& g, const Span* t, std::size_t nt, int32_t ceiling,
                           const BeamGate* gate)
{
    const LogOddsModel& model = model_;
    std::vector<Interval>& out = pieces_;
    const float empty_prior = g.logodds_empty;
    const int32_t seen_top = g.seen_top;
    const PassedCells passed_before = g.passed;  // where empty_prior is evidence
    const Interval* const gi = g.intervals.data();
    const std::size_t ng = g.intervals.size();
    // LHP (Eq. 15): b_base is the lowest height the scan saw in this pillar.
    const int32_t base = nt > 0 ? t[0].lo : std::numeric_limits<int32_t>::max();
    // Eq. 8 below: the pillar's free space seen empty again; with the gate, only when a beam of
    // the scan passed through the pillar between its lowest content and the top of the view.
    bool seen_empty = true;
    if (gate && (ng > 0 || nt > 0))
    {
        int32_t lo = std::numeric_limits<int32_t>::max();
        int32_t hi = std::numeric_limits<int32_t>::min();
        if (ng > 0)
        {
            lo = gi[0].lo;
            hi = gi[ng - 1].hi;
        }
        if (nt > 0)
        {
            lo = std::min(lo, t[0].lo);
            hi = std::max(hi, t[nt - 1].hi);
        }
        if (ceiling != kAllHeights) hi = std::max(hi, ceiling);
        seen_empty = gate->seenEmpty(lo, hi, g.passed);
    }

    // The sweep below yields at most 2 (ng + nt) - 1 pieces, and two more for each run of
    // heights a beam passed through (the gate). They are written field by field through a
    // pointer: building each Interval as a temporary and copying it costs a store-forwarding
    // stall per piece.
    if (out.size() < 2 * (ng + nt)) out.resize(2 * (ng + nt));  // grows, never shrinks
    Interval* o = out.data();
    std::size_t count = 0;
    auto emit = [&](int32_t lo, int32_t hi, float l)
    {
        l = model.clamp(l);  // Eq. 17-18
        if (count > 0 && o[count - 1].hi == lo && o[count - 1].logodds == l)
        {
            o[count - 1].hi = hi;  // lossless: both halves carry the same belief
            return;
        }
        if (count == out.size())
        {
            out.resize(2 * out.size());
            o = out.data();
        }
        o[count].lo = lo;
        o[count].hi = hi;
        o[count].logodds = l;
        ++count;
    };

    // Sweep over the sorted endpoints of both sets (Eq. 9): between two consecutive endpoints
    // [x, next) coverage by g and by t is constant, so each step is one h_k^new of Eq. 10, and
    // it lies inside at most one g interval and one t span (Eq. 11 sets have <= 1 element).
    std::size_t i = 0, j = 0;
    int ground = -1;  // whether t[0] lies on the ground (BeamGate::onGround()): not asked yet
    int64_t x = std::numeric_limits<int64_t>::max();
    if (ng > 0) x = gi[0].lo;
    if (nt > 0) x = std::min<int64_t>(x, t[0].lo);
    for (;;)
    {
        while (i < ng && gi[i].hi <= x) ++i;
        while (j < nt && t[j].hi <= x) ++j;
        if (i == ng && j == nt) break;
        const bool in_g = i < ng && gi[i].lo <= x;
        const bool in_t = j < nt && t[j].lo <= x;
        int64_t next = std::numeric_limits<int64_t>::max();
        if (i < ng) next = std::min<int64_t>(next, in_g ? gi[i].hi : gi[i].lo);
        if (j < nt) next = std::min<int64_t>(next, in_t ? t[j].hi : t[j].lo);
        const auto lo = static_cast<int32_t>(x);
        const auto hi = static_cast<int32_t>(next);
        if (in_g && in_t)
            emit(lo, hi, gi[i].logodds + model.hit);  // Eq. 12: seen again
        else if (in_g)
        {
            if (model.lhp && hi <= base)
                emit(lo, hi, gi[i].logodds);  // Eq. 16: below b_base, unknown: keep
            else if (model.hhp && lo >= ceiling)
                emit(lo, hi, gi[i].logodds);  // HHP: above the field of view, unknown: keep
            else if (gate && !model.missChanges(gi[i].logodds))
                emit(lo, hi, gi[i].logodds);  // at p_min: a miss leaves it there
            else if (gate)
            {
                // Eq. 13 where beams of the scan passed through; elsewhere the scan could not
                // see: keep (BeamGate::floorOrObject(); the lowest interval alone is the floor,
                // as slivers under it taken for the floor here, BeamGate::floorTop(), cost 04
                // and 08 at 16 rings 0.2-0.3 DA, doc/algorithm.md).
                const Span core = gate->floorOrObject(gi, 0, i, lo, hi);
                gate->passedCells(lo, hi, {std::max(core.lo, lo), std::min(core.hi, hi)}, passed_,
                                  gate->skyFor(gi[i].logodds),
                                  i > 0 && model.heldFirmly(gi[i].logodds));
                int32_t at = lo;
                for (const Span& s : passed_)
                {
                    if (s.lo > at) emit(at, s.lo, gi[i].logodds);
                    emit(s.lo, s.hi, gi[i].logodds + model.miss);
                    at = s.hi;
                }
                if (at < hi) emit(at, hi, gi[i].logodds);
            }
            else
                emit(lo, hi, gi[i].logodds + model.miss);  // Eq. 13: expected, not seen
        }
        else if (in_t)
        {
            // Eq. 14: new, prior p_empty; unseen-height prior: p_empty_init where no scan
            // could look before. With the gate, p_empty is evidence only of the heights beams
            // were seen passing through, to within the merge gap (heights closer than that are
            // one surface to the map): elsewhere (between two rings of a sparse LiDAR, behind
            // what hid it before) the prior is p_empty_init too.
            float prior = model.unseen_prior && lo >= seen_top ? model.empty_init : empty_prior;
            if (gate && prior != model.empty_init && !passed_before.any(lo, hi))
            {
                const int64_t gap = gate->widthsOf(lo, hi).gap;  // only asked where needed
                constexpr int64_t kMin = std::numeric_limits<int32_t>::min();
                constexpr int64_t kMax = std::numeric_limits<int32_t>::max();
                if (!passed_before.any(static_cast<int32_t>(std::max(lo - gap, kMin)),
                                       static_cast<int32_t>(std::min(hi + gap, kMax))))
                    prior = model.empty_init;
            }
            // Ground floors: no prior against a surface that does not move (neutral, 0.5) where
            // it was seen (the floor's core: its padding is a guess around it, where a car's
            // lower half may stand); asked once per pillar, only where a new piece arises.
            if (j == 0 && gate && model.ground_slope_tan > 0.0)
            {
                if (ground < 0)
                    ground =
                        gate->onGround(t[0].lo, t[0].hi, model.ground_slope_tan, model.ground_step);
                if (ground == 1)
                {
                    const Span c = gate->widthsOf(t[0].lo, t[0].hi).core(t[0].lo, t[0].hi);
                    const int32_t a = std::clamp(c.lo, lo, hi), b = std::clamp(c.hi, a, hi);
                    if (a > lo) emit(lo, a, prior + model.hit);
                    if (b > a) emit(a, b, std::max(prior, 0.0f) + model.hit);
                    if (hi > b) emit(b, hi, prior + model.hit);
                    x = next;
                    continue;
                }
            }
            emit(lo, hi, prior + model.hit);
        }
        // neither: not covered by any observation, discarded.
        x = next;
    }
    if (count > max_intervals_) count = capIntervals(o, count, max_intervals_);
    // A copy, not a swap: the pillar keeps its own storage, so steady state allocates nothing.
    // Storage grows in powers of two: exact-size reallocations, pillar after pillar, fragment
    // the heap (peak memory grew with the length of the run).
    if (g.intervals.capacity() < count)
    {
        std::size_t c = 4;
        while (c < count) c *= 2;
        g.intervals.reserve(c);
    }
    g.intervals.assign(o, o + count);
    if (seen_empty) g.logodds_empty = model.clamp(empty_prior + model.miss);  // Eq. 8
    g.seen_top = std::max(seen_top, ceiling);
}

std::size_t capIntervals(Interval* iv, std::size_t n, std::size_t max_intervals)
{
    while (n > max_intervals && n > 1)
    {
        // The pair with the smallest (gap, |log-odds difference|), the first on ties: both as
        // one unsigned key (the gap is >= 0 and below 2^32; a non-negative float's bits order
        // like its value), so the search has no branch to mispredict.
        std::size_t best = 0;
        uint64_t best_key = std::numeric_limits<uint64_t>::max();
        for (std::size_t k = 0; k + 1 < n; ++k)
        {
            const auto gap = static_cast<uint64_t>(static_cast<int64_t>(iv[k + 1].lo) - iv[k].hi);
            const float dl = std::abs(iv[k + 1].logodds - iv[k].logodds);
            uint32_t dl_bits = 0;
            std::memcpy(&dl_bits, &dl, sizeof dl_bits);
            const uint64_t key = (gap << 32) | dl_bits;
            const bool better = key < best_key;
            best = better ? k : best;
            best_key = better ? key : best_key;
        }
        Interval& a = iv[best];
        const Interval& b = iv[best + 1];
        const double wa = static_cast<double>(a.hi) - a.lo;
        const double wb = static_cast<double>(b.hi) - b.lo;
        a.logodds = static_cast<float>((wa * a.logodds + wb * b.logodds) / (wa + wb));
        a.hi = b.hi;
        std::copy(iv + best + 2, iv + n, iv + best + 1);
        --n;
    }
    // A merge can make a new neighbour pair touch with equal log-odds.
    return joinEqualNeighbours(iv, n);
}

std::size_t joinEqualNeighbours(Interval* iv, std::size_t n)
{
    if (n == 0) return 0;
    std::size_t w = 0;
    for (std::size_t k = 1; k < n; ++k)
    {
        if (iv[w].hi == iv[k].lo && iv[w].logodds == iv[k].logodds)
            iv[w].hi = iv[k].hi;
        else
            iv[++w] = iv[k];
    }
    return w + 1;
}

}  // namespace hif::detail
