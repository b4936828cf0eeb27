// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   BuildSpans.cpp
 * @brief  Step 2 of an insertion: each pillar's heights in the scan turned into spans (Eq. 4),
 *         and the highest height the scan could see there.
 */
#include <cmath>

#include "GridAccess.h"
#include "RangeImage.h"

namespace hif::detail
{
void buildSpans(const PillarGrid& grid, ScanBuckets& scan)
{
    const GridGeometry& geo = grid.geometry();
    const Params& prm = grid.params();
    const std::size_t np = scan.pillarCount();
    scan.ceilings.resize(np);
    scan.span_counts.resize(np);
    scan.spans.resize(scan.entryCount());
    // Params::pillar_edge_margin: the surfaces seen at each pillar's edges, as spans too.
    const bool edges = !scan.edge_offsets.empty();
    scan.edge_span_counts.assign(edges ? np : 0, 0);
    scan.edge_spans.resize(scan.edge_cells.size());
    const double res = geo.height_resolution;
    const bool need_ceiling = (prm.high_height_preservation || prm.unseen_height_prior) &&
                              std::isfinite(scan.top_slope_sq);
    // tan(top beam elevation) from its signed square.
    const double top_slope =
        need_ceiling ? std::copysign(std::sqrt(std::abs(scan.top_slope_sq)), scan.top_slope_sq)
                     : 0.0;
    const Eigen::Vector3d& t = scan.sensor;
    forRanges(GridAccess::arena(grid), np, 256,
              [&](std::size_t p0, std::size_t p1)
              {
                  for (std::size_t p = p0; p < p1; ++p)
                  {
                      const uint32_t b = scan.offsets[p], e = scan.offsets[p + 1];
                      int32_t* cells = scan.cells.data() + b;
                      const std::size_t distinct = sortDistinct(cells, e - b);

                      // Horizontal distance from the sensor to the pillar's centre.
                      const PillarIndex idx = unpackKey(scan.keys[p]);
                      const double dx = geo.centreX(idx.m) - t.x();
                      const double dy = geo.centreY(idx.n) - t.y();
                      const double d = std::sqrt(dx * dx + dy * dy);
                      // The gap between the beams that reach the pillar's middle height (the
                      // edge spans take the same).
                      const double mid_z = (cells[distinct / 2] + 0.5) * res - t.z();
                      const IntervalWidths w =
                          IntervalWidths::of(grid, d, d > 0.0 ? mid_z / d : 0.0);
                      scan.span_counts[p] = static_cast<uint32_t>(
                          spansFromCells(cells, distinct, w.gap, w.pad, scan.spans.data() + b));
                      if (edges && scan.edge_offsets[p + 1] > scan.edge_offsets[p])
                      {
                          const uint32_t eb = scan.edge_offsets[p];
                          int32_t* edge_cells = scan.edge_cells.data() + eb;
                          scan.edge_span_counts[p] = static_cast<uint32_t>(spansFromCells(
                              edge_cells, sortDistinct(edge_cells, scan.edge_offsets[p + 1] - eb),
                              w.gap, w.pad, scan.edge_spans.data() + eb));
                      }

                      int32_t ceiling = kAllHeights;
                      if (need_ceiling)
                      {
                          const double top = (t.z() + d * top_slope) / res;
                          if (top < static_cast<double>(kAllHeights))
                              ceiling = static_cast<int32_t>(std::max<double>(
                                  std::ceil(top), std::numeric_limits<int32_t>::min() + 1.0));
                      }
                      scan.ceilings[p] = ceiling;
                  }
              });
}

}  // namespace hif::detail
