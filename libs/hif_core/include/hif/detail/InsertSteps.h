// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   InsertSteps.h
 * @brief  The steps of PillarGrid::insertScan(), one call each, so that the benchmark can time
 *         them and the tests can look at what passes between them. Internal to hif_core.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "hif/PillarGrid.h"
#include "hif/detail/PillarUpdate.h"

namespace hif::detail
{
/** One scan turned into the map's own structure: the pillars it hits, each with the height
 *  cells of its points and, after buildSpans(), its spans h^t (Eq. 4). Reusing one object
 *  between scans avoids allocation in steady state. */
struct ScanBuckets
{
    /** @name Per pillar hit by the scan (bucket order)
     *  @{ */
    std::vector<uint64_t> keys;         ///< packKey() of the pillar
    std::vector<uint32_t> offsets;      ///< pillar p owns items [offsets[p], offsets[p+1])
    std::vector<int32_t> ceilings;      ///< first cell above what the scan could see (kAllHeights)
    std::vector<uint32_t> span_counts;  ///< pillar p's spans: spans[offsets[p]] onwards
    /** Where in pillar p the scan saw what stands above its ground (Pillar::object_u, v):
     *  the sums of the offsets (fractions of the pillar along m and n) of its entries more
     *  than Params::ground_max_step above the pillar's lowest (the first point of each run of
     *  repeats), and their count.
     *  Insertion with Params::miss_needs_beam only (else empty). */
    struct ObjectSightings
    {
        float sum_u = 0.0f, sum_v = 0.0f;
        uint32_t count = 0;
    };
    std::vector<ObjectSightings> object_at;
    /** @} */

    /** @name Per cell entry, grouped by pillar
     *  A valid input point with the same pillar and height cell as the input point just before
     *  it is a repeat: it is not stored (it would change no interval and no classification).
     *  On KITTI scans, ordered by beam, three points in four are repeats.
     *  @{ */
    /** Height cell of each stored point. After buildSpans(), each pillar's range starts with
     *  its distinct cells in ascending order (what follows them is unspecified). */
    std::vector<int32_t> cells;
    std::vector<uint32_t> index;  ///< input index of cells[k] (filled for classification only)
    std::vector<Span> spans;      ///< at most one span per entry, so pillar p's fit at offsets[p]
    /** @} */

    /** @name Surfaces at pillars' edges (insertion with Params::pillar_edge_margin)
     *  Per pillar of the scan: the height cells of the scan's points that lie within the margin
     *  of its edge in the pillars beside it (across an edge or a corner), and after
     *  buildSpans() their spans, sorted and disjoint: where the scan saw a surface that may go
     *  on into the pillar. Empty without the margin.
     *  @{ */
    std::vector<uint32_t> edge_offsets;      ///< pillar p owns edge_cells[edge_offsets[p]...]
    std::vector<int32_t> edge_cells;         ///< sorted and distinct first after buildSpans()
    std::vector<Span> edge_spans;            ///< pillar p's from edge_spans[edge_offsets[p]]
    std::vector<uint32_t> edge_span_counts;  ///< per pillar
    /** @} */

    /** Per row of the grid's range-image layout (buildSpans()): the gap between the sensor's
     *  beams around the row's middle elevation (PillarGrid::beamGapSlope()), for the interval
     *  widths of each height. */
    std::vector<double> gap_slope_by_row;

    /** Pillar p's edge spans (after buildSpans()), their count in `count` (0: none). */
    [[nodiscard]] const Span* edgeSpansOf(std::size_t p, std::size_t& count) const
    {
        count = edge_span_counts.empty() ? 0 : edge_span_counts[p];
        return count == 0 ? nullptr : edge_spans.data() + edge_offsets[p];
    }

    /** Per input point (filled for classification only): 1 when the point is a repeat of the
     *  input point before it, so it takes that point's class. */
    std::vector<uint8_t> repeats;

    /** Per pillar (filled by classification for the free-space test): the top cell of the
     *  map's lowest static interval there, kNoFloor where it holds none. */
    std::vector<int32_t> floors;
    static constexpr int32_t kNoFloor = std::numeric_limits<int32_t>::min();
    /** Per cell entry (filled by classification for the free-space test): 1 when its interval
     *  in the map has log-odds no more than p_empty_init's and one hit, so that what the map
     *  holds static there rests on one sighting at most: online, on this scan's. */
    std::vector<uint8_t> seen_once;
    /** Per cell entry (as seen_once): 1 when no more than p_empty_init's and two hits: this
     *  scan's sighting and one other at most. */
    std::vector<uint8_t> seen_twice;
    /** Per cell entry (filled by classification for the free-space test): 1 when the map holds
     *  less than p_empty_init there (its interval's log-odds, else the pillar's p_empty): beams
     *  saw the place empty more often than occupied, so what stands there now moved in or is
     *  leaving. */
    std::vector<uint8_t> seen_empty;
    /** Per cell entry (as seen_once): 1 when its interval in the map is at p_max, held static
     *  as firmly as the map can: no sign that what stands there now came or goes. */
    std::vector<uint8_t> at_max;

    Eigen::Vector3d sensor = Eigen::Vector3d::Zero();  ///< sensor position, world frame
    Eigen::Matrix3d world_to_sensor = Eigen::Matrix3d::Identity();  ///< rotation
    /** Top beam's elevation as the largest z * |z| / (x^2 + y^2) of the points farther than
     *  2 m horizontally (sensor frame; monotone in z / range, no square root); -inf if none. */
    double top_slope_sq = -std::numeric_limits<double>::infinity();
    std::size_t points_valid = 0;         ///< valid input points, repeats included
    std::size_t points_invalid = 0;       ///< non-finite, or outside the int32 index range
    std::size_t points_outside_grid = 0;  ///< of those, the finite ones
    std::size_t points_near = 0;          ///< nearer the sensor than Params::min_range

    [[nodiscard]] std::size_t pillarCount() const { return keys.size(); }
    [[nodiscard]] std::size_t entryCount() const { return cells.size(); }

    /** Scratch of bucketPoints(), kept to be reused. */
    std::vector<int32_t> tmp_m, tmp_n, tmp_z, tmp_edge, tmp_code;
    std::vector<uint32_t> tmp_src, tmp_bin, tmp_counts, tmp_pillar;
    std::vector<std::pair<uint32_t, int32_t>> tmp_edge_pairs;
};

/** Step 1: transforms and quantizes every point (Eq. 1), skips invalid ones and repeats, and
 *  groups the rest by pillar in one counting-sort pass (a comparison sort only when the scan
 *  spans more than 2^22 pillars). With `keep_index`, out.index and out.repeats are filled. */
void bucketPoints(const PillarGrid& grid, const PointsView& points,
                  const Eigen::Isometry3d& sensor_to_world, ScanBuckets& out,
                  bool keep_index = false);

/** Step 2: sorts each pillar's height cells and builds its spans (Eq. 4, with the
 *  range-adaptive gap and padding) and its field-of-view ceiling. */
void buildSpans(const PillarGrid& grid, ScanBuckets& scan);

/** Whether insertion needs the scan's range image (Params::miss_needs_beam, or the
 *  see-through misses on). */
[[nodiscard]] bool needsScanImage(const Params& params);

/** Step 2b, when needsScanImage(): the scan's range image (sensor frame, laid out for the
 *  grid's sensor model), kept in the grid's workspace for steps 3 and 4. */
void buildScanImage(PillarGrid& grid, const PointsView& points);

/** Step 3: the Bayes update of every pillar of the scan (Eq. 8-18), or its creation; with
 *  Params::miss_needs_beam, an interval the scan did not hit gets its Eq. 13 miss only where
 *  a beam of the scan passed through it (step 2b's image). */
InsertStats updatePillars(PillarGrid& grid, const ScanBuckets& scan);

/** Step 4, when Params::see_through_range > 0: a miss (Eq. 13) for every interval of a pillar
 *  the scan did not hit, within see_through_range of the sensor, that a beam of the scan
 *  passed through (see Params::see_through_range; step 2b's image). */
void seeThroughMisses(PillarGrid& grid, const Eigen::Isometry3d& sensor_to_world,
                      const ScanBuckets& scan);

}  // namespace hif::detail
