// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SeeThrough.cpp
 * @brief  See-through misses (Params::see_through_range): after a scan, a miss (Eq. 13) for
 *         every interval of a nearby pillar the scan did not hit that a beam passed through.
 */
#include <cmath>

#include "GridAccess.h"
#include "RangeImage.h"
#include "hif/FreeSpaceTest.h"

namespace hif::detail
{
namespace
{
/** The see-through misses of one pillar the scan did not hit: Eq. 13 where beams passed
 *  through its intervals (BeamGate::floorTop(), floorOrObject()). `passed` and `pieces` are
 * scratch. */
void seeThroughPillar(Pillar& pil, const BeamGate& gate, const LogOddsModel& model, std::size_t cap,
                      std::vector<Span>& passed, std::vector<Interval>& pieces)
{
    pieces.clear();
    bool changed = false;
    const std::size_t floor_top = gate.floorTop(pil.intervals.data(), pil.intervals.size());
    for (const Interval& iv : pil.intervals)
    {
        if (!model.missChanges(iv.logodds))
        {
            pieces.push_back(iv);  // at p_min: a miss leaves it there
            continue;
        }
        const auto k = static_cast<std::size_t>(&iv - pil.intervals.data());
        gate.passedCells(iv.lo, iv.hi,
                         gate.floorOrObject(pil.intervals.data(), floor_top, k, iv.lo, iv.hi),
                         passed, gate.skyFor(iv.logodds));
        int32_t at = iv.lo;
        for (const Span& s : passed)
        {
            if (s.lo > at) pieces.push_back({at, s.lo, iv.logodds});
            pieces.push_back({s.lo, s.hi, model.clamp(iv.logodds + model.miss)});  // Eq. 13
            at = s.hi;
            changed = true;
        }
        if (at < iv.hi) pieces.push_back({at, iv.hi, iv.logodds});
    }
    if (!changed) return;
    std::size_t n = joinEqualNeighbours(pieces.data(), pieces.size());
    if (n > cap) n = capIntervals(pieces.data(), n, cap);
    pil.intervals.assign(pieces.begin(), pieces.begin() + static_cast<std::ptrdiff_t>(n));
}
}  // namespace

bool needsScanImage(const Params& p) { return p.miss_needs_beam || p.see_through_range > 0.0; }

void buildScanImage(PillarGrid& grid, const PointsView& pts)
{
    Workspace& ws = GridAccess::workspace(grid);
    ws.farthest_return =
        buildReturnImage(grid.imageLayout(), pts, ws.range_image, ws.returned_blocks);
    // Online, the free-space test keeps the scan just inserted: it takes this image then.
    const Params& p = grid.params();
    const bool kept = p.online && p.free_space_window > 0;
    ws.range_image_points = kept ? FreeSpaceTest::pointsFingerprint(pts) : 0;
    ws.range_image_layout = kept ? grid.imageLayout() : RangeImageLayout{0, 0};
}

void seeThroughMisses(PillarGrid& grid, const Eigen::Isometry3d& T, const ScanBuckets& scan)
{
    Workspace& ws = GridAccess::workspace(grid);
    PillarTable& pillars = GridAccess::pillars(grid);
    const GridGeometry& geo = grid.geometry();
    const Params& prm = grid.params();
    const LogOddsModel model = LogOddsModel::of(grid);

    // The map's pillars within see_through_range of the sensor that the scan did not hit.
    const double ps = geo.pillar_size;
    const double range = prm.see_through_range, margin = prm.see_through_margin;
    const Eigen::Vector3d t = T.translation();
    const Eigen::Matrix3d Rt = T.linear().transpose();
    int32_t cm = 0, cn = 0;
    if (!floorToInt32((t.x() - geo.origin_x) / ps, cm) ||
        !floorToInt32((t.y() - geo.origin_y) / ps, cn))
        return;
    const int64_t w = static_cast<int64_t>(std::ceil(range / ps));
    const int64_t side = 2 * w + 1;
    std::vector<uint8_t>& hit = ws.hit;
    hit.assign(static_cast<std::size_t>(side * side), 0);
    for (uint64_t key : scan.keys)
    {
        const PillarIndex idx = unpackKey(key);
        const int64_t a = int64_t{idx.m} - cm + w, b = int64_t{idx.n} - cn + w;
        if (a >= 0 && a < side && b >= 0 && b < side)
            hit[static_cast<std::size_t>(a * side + b)] = 1;
    }
    // Rows of the window are independent (each pillar is in one row): split them over threads.
    const Eigen::Vector3d up = Rt.col(2);  // world z axis in the sensor frame
    const std::size_t cap = prm.max_intervals_per_pillar;
    const double bridge = neighbourBeamsTan(grid);
    const float seen_once = seenOnce(grid);
    const int32_t slope_cells = groundSlopeCells(geo, model.ground_slope_tan);
    forRanges(GridAccess::arena(grid), static_cast<std::size_t>(side), 8,
              [&](std::size_t a0, std::size_t a1)
              {
                  std::vector<Span> passed;
                  std::vector<Interval> pieces;
                  for (auto a = static_cast<int64_t>(a0); a < static_cast<int64_t>(a1); ++a)
                      for (int64_t b = 0; b < side; ++b)
                      {
                          const int64_t m = cm + a - w, n = cn + b - w;
                          if (hit[static_cast<std::size_t>(a * side + b)] || m < INT32_MIN ||
                              m > INT32_MAX || n < INT32_MIN || n > INT32_MAX)
                              continue;
                          const PillarIndex idx{static_cast<int32_t>(m), static_cast<int32_t>(n)};
                          const auto it = pillars.find(packKey(idx));
                          if (it == pillars.end()) continue;
                          const double dx = geo.centreX(idx.m) - t.x();
                          const double dy = geo.centreY(idx.n) - t.y();
                          if (dx * dx + dy * dy > range * range) continue;
                          // The pillar's axis in the sensor frame: base + up * z.
                          BeamGate gate{&grid.imageLayout(),
                                        ws.range_image.data(),
                                        Rt * Eigen::Vector3d(dx, dy, -t.z()),
                                        up,
                                        margin,
                                        geo.height_resolution,
                                        0,
                                        pillarReach(ps, dx, dy),
                                        bridge,
                                        &grid,
                                        t.z(),
                                        seen_once,
                                        ws.returned_blocks.data()};
                          gate.floor_slope_cells = slope_cells;
                          seeThroughPillar(it->second, gate, model, cap, passed, pieces);
                      }
              });
}

}  // namespace hif::detail
