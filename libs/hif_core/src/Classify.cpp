// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Classify.cpp
 * @brief  Classification of a scan's points as static or dynamic, pillar by pillar.
 */
#include <atomic>
#include <cmath>

#include "FreeSpace.h"
#include "GridAccess.h"
#include "hif/detail/PillarUpdate.h"

namespace hif
{
namespace
{
/** The top cell of the lowest interval of `pil` that `grid` keeps (its floor), or
 *  ScanBuckets::kNoFloor: for the free-space test's ground. */
int32_t floorTop(const PillarGrid& grid, const Pillar* pil)
{
    if (pil)
        for (const Interval& iv : pil->intervals)
            if (grid.isStaticLogOdds(iv.logodds)) return iv.hi - 1;
    return detail::ScanBuckets::kNoFloor;
}
}  // namespace

ClassifyStats PillarGrid::classify(const PointsView& pts, std::vector<uint8_t>& is_dynamic,
                                   const Eigen::Isometry3d& T,
                                   const FreeSpaceTest* free_space) const
{
    // The grid's own buffer for this call (reused by later calls, freed with the grid).
    const auto lease = detail::GridAccess::workspace(*this).classify_buffers.take();
    detail::ScanBuckets& scan = *lease.buffer;
    detail::bucketPoints(*this, pts, T, scan, true);
    constexpr uint8_t kUnset = 2;
    is_dynamic.assign(pts.size, kUnset);

    const bool prior_static = isStaticLogOdds(logit(pEmptyInit()));
    const bool free_space_test =
        free_space && !free_space->empty() && params_.free_space_window > 0;
    // ScanBuckets::seen_once and seen_twice: at most p_empty_init and one or two hits;
    // ScanBuckets::seen_empty: less than p_empty_init (in the update's own floats).
    float seen_once = 0.0f, seen_twice = 0.0f, empty_init = 0.0f, at_max = 0.0f;
    if (free_space_test)
    {
        scan.floors.resize(scan.pillarCount());
        scan.seen_once.resize(scan.cells.size());
        scan.seen_twice.resize(scan.cells.size());
        scan.seen_empty.resize(scan.cells.size());
        scan.at_max.resize(scan.cells.size());
        const detail::LogOddsModel model = detail::LogOddsModel::of(*this);
        seen_once = model.empty_init + model.hit + 1e-4f;
        seen_twice = model.empty_init + 2.0f * model.hit + 1e-4f;
        empty_init = model.empty_init;
        at_max = model.lmax - 1e-4f;
    }
    std::atomic<std::size_t> n_static{0};
    detail::forRanges(detail::GridAccess::arena(*this), scan.pillarCount(), 256,
                      [&](std::size_t p0, std::size_t p1)
                      {
                          std::size_t local_static = 0;
                          for (std::size_t p = p0; p < p1; ++p)
                          {
                              const uint32_t b = scan.offsets[p], e = scan.offsets[p + 1];
                              const Pillar* pil = findPillar(unpackKey(scan.keys[p]));
                              if (free_space_test) scan.floors[p] = floorTop(*this, pil);
                              for (uint32_t k = b; k < e; ++k)
                              {
                                  bool stat = prior_static;
                                  bool once = false, twice = false, emptied = false, held = false;
                                  if (pil)
                                  {
                                      const Interval* iv = findInterval(*pil, scan.cells[k]);
                                      const float l = iv ? iv->logodds : pil->logodds_empty;
                                      stat = isStaticLogOdds(l);
                                      once = iv && iv->logodds <= seen_once;
                                      twice = iv && iv->logodds <= seen_twice;
                                      emptied = l < empty_init;
                                      held = iv && iv->logodds >= at_max;
                                  }
                                  if (free_space_test)
                                  {
                                      scan.seen_once[k] = once;
                                      scan.seen_twice[k] = twice;
                                      scan.seen_empty[k] = emptied;
                                      scan.at_max[k] = held;
                                  }
                                  is_dynamic[scan.index[k]] = stat ? 0 : 1;
                                  local_static += stat;
                              }
                          }
                          n_static += local_static;
                      });
    ClassifyStats st;
    st.static_points = n_static;
    if (free_space_test)
    {
        const std::size_t marked = detail::markSeenThrough(*this, scan, pts, T, *free_space,
                                                           is_dynamic, st.free_space_scans);
        st.static_points -= marked;
    }
    // A repeat has the pillar and height cell of the point before it, hence its class.
    for (std::size_t i = 1; i < pts.size; ++i)
        if (scan.repeats[i])
        {
            is_dynamic[i] = is_dynamic[i - 1];
            st.static_points += is_dynamic[i] == 0;
        }
    // The points the free-space test removed, their repeats included.
    if (free_space_test)
        for (uint8_t& d : is_dynamic)
            if (d == detail::kSeenThrough)
            {
                d = 1;
                ++st.seen_through_points;
            }
    // Points that bucketPoints() skipped: non-finite ones are invalid (dynamic), those nearer
    // than the minimum range dynamic; finite ones beyond the int32 index range lie in unknown
    // space, which has the prior.
    if (scan.points_invalid > 0 || scan.points_near > 0)
    {
        const double min_r2 = params_.min_range * params_.min_range;
        for (std::size_t i = 0; i < pts.size; ++i)
        {
            if (is_dynamic[i] != kUnset) continue;
            const double x = pts.x[i], y = pts.y[i], z = pts.z[i];
            const bool finite = std::isfinite(x) && std::isfinite(y) && std::isfinite(z);
            const bool near = finite && x * x + y * y + z * z < min_r2;
            st.invalid_points += !finite;
            st.near_points += near;
            const bool stat = finite && !near && prior_static;
            is_dynamic[i] = stat ? 0 : 1;
            st.static_points += stat;
        }
    }
    st.dynamic_points = pts.size - st.static_points;
    return st;
}
}  // namespace hif
