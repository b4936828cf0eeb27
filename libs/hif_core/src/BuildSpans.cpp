// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   BuildSpans.cpp
 * @brief  Step 2 of an insertion: each pillar's heights in the scan turned into spans (Eq. 4),
 *         and the highest height the scan could see there.
 */
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "GridAccess.h"
#include "RangeImage.h"

namespace hif::detail
{
namespace
{
/** The interval widths of one pillar at horizontal distance `d` from the sensor, by height
 *  (spansFromCells()): those of the gap between the sensor's beams around each height's
 *  elevation, read from `slopes` (ScanBuckets::gap_slope_by_row, per row of the image layout
 *  `l`). A sensor whose beams lie unevenly (a VLP-32C: a third of a degree apart near the
 *  horizon, 4.7 degrees at the top) samples the ground and the top of a facade in one pillar at
 *  different spacings. */
class WidthsByHeight
{
public:
    WidthsByHeight(const PillarGrid& grid, const RangeImageLayout& l,
                   const std::vector<double>& slopes, double d, double res, double sensor_z)
        : grid_(grid),
          l_(l),
          slopes_(slopes),
          d_(d),
          inv_d_(d > 0.0 ? 1.0 / d : 0.0),
          inv_tan_res_(1.0 / l.tan_res),
          res_(res),
          sensor_z_(sensor_z)
    {
    }

    /** The widths at height `cell` (a cell index; its middle at cell + 0.5). */
    IntervalWidths operator()(double cell)
    {
        const double tan_el = ((cell + 0.5) * res_ - sensor_z_) * inv_d_;
        const double at = (tan_el - l_.tan_min) * inv_tan_res_;
        const int row = at <= 0.0 ? 0 : (at >= l_.rows - 1 ? l_.rows - 1 : static_cast<int>(at));
        if (row != row_)
        {
            row_ = row;
            widths_ = IntervalWidths::ofBeamGap(grid_, d_ * slopes_[static_cast<std::size_t>(row)]);
        }
        return widths_;
    }

private:
    const PillarGrid& grid_;
    const RangeImageLayout& l_;
    const std::vector<double>& slopes_;
    double d_, inv_d_, inv_tan_res_, res_, sensor_z_;
    int row_ = -1;  ///< the row widths_ holds for
    IntervalWidths widths_;
};
}  // namespace

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
    // The gap between the sensor's beams around each row of the image's elevations.
    const RangeImageLayout& layout = grid.imageLayout();
    scan.gap_slope_by_row.resize(static_cast<std::size_t>(layout.rows));
    for (int r = 0; r < layout.rows; ++r)
        scan.gap_slope_by_row[static_cast<std::size_t>(r)] =
            grid.beamGapSlope(layout.tan_min + (r + 0.5) * layout.tan_res);
    // No height's gap is less than the merge gap's (IntervalWidths::of()).
    const int32_t least_gap = IntervalWidths::of(grid, 0.0, 0.0).gap;
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
                      // The gap between the beams that reach each height (the edge spans take
                      // the same).
                      WidthsByHeight widths(grid, layout, scan.gap_slope_by_row, d, res, t.z());
                      scan.span_counts[p] = static_cast<uint32_t>(spansFromCells(
                          cells, distinct, widths, least_gap, scan.spans.data() + b));
                      if (edges && scan.edge_offsets[p + 1] > scan.edge_offsets[p])
                      {
                          const uint32_t eb = scan.edge_offsets[p];
                          int32_t* edge_cells = scan.edge_cells.data() + eb;
                          scan.edge_span_counts[p] = static_cast<uint32_t>(spansFromCells(
                              edge_cells, sortDistinct(edge_cells, scan.edge_offsets[p + 1] - eb),
                              widths, least_gap, scan.edge_spans.data() + eb));
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
