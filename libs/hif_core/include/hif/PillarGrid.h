// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarGrid.h
 * @brief  The global HIF map G: pillars on a fixed grid, updated scan by scan.
 */
#pragma once

#include <absl/container/flat_hash_map.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "hif/Params.h"
#include "hif/Pillar.h"
#include "hif/PillarIndex.h"

namespace hif
{
/** Read-only view of a point cloud as three coordinate arrays of `size` floats each (the
 *  layout of MRPT's point maps). */
struct PointsView
{
    const float* x = nullptr;
    const float* y = nullptr;
    const float* z = nullptr;
    std::size_t size = 0;
};

/** What one insertScan() (or mergeScan()) did. */
struct InsertStats
{
    std::size_t points_used = 0;      ///< points that updated the map
    std::size_t points_invalid = 0;   ///< non-finite, or outside the int32 index range: skipped
    std::size_t pillars_updated = 0;  ///< existing pillars matched by the scan
    std::size_t pillars_created = 0;  ///< pillars seen for the first time
};

/** What one classify() found. */
struct ClassifyStats
{
    std::size_t static_points = 0;
    std::size_t dynamic_points = 0;
    std::size_t invalid_points = 0;  ///< non-finite: reported dynamic (not part of the map)
};

/** One scan turned into the map's own structure: the pillars it hits, each with the height
 *  cells of its points and, after PillarGrid::buildIntervals(), its spans h^t (Eq. 4). The
 *  three steps of an insertion (bucketScan, buildIntervals, mergeScan) communicate through it;
 *  reusing one object between scans avoids allocation in steady state. */
struct ScanPillars
{
    /** @name Per pillar hit by the scan (bucket order)
     *  @{ */
    std::vector<uint64_t> keys;         ///< packKey() of the pillar
    std::vector<uint32_t> offsets;      ///< pillar p owns items [offsets[p], offsets[p+1])
    std::vector<int32_t> ceilings;      ///< first cell above what the scan could see (kAllHeights)
    std::vector<uint32_t> span_counts;  ///< pillar p's spans: spans[offsets[p]] onwards
    /** @} */

    /** @name Per cell entry, grouped by pillar
     *  A valid input point with the same pillar and height cell as the input point just before
     *  it is a repeat: it is not stored (it would change no interval and no classification).
     *  On KITTI scans, ordered by beam, three points in four are repeats.
     *  @{ */
    /** Height cell of each stored point. After buildIntervals(), each pillar's range starts
     *  with its distinct cells in ascending order (what follows them is unspecified). */
    std::vector<int32_t> cells;
    std::vector<uint32_t> index;  ///< input index of cells[k] (filled for classification only)
    std::vector<Span> spans;      ///< at most one span per entry, so pillar p's fit at offsets[p]
    /** @} */

    /** Per input point (filled for classification only): 1 when the point is a repeat of the
     *  input point before it, so it takes that point's class. */
    std::vector<uint8_t> repeats;

    Eigen::Vector3d sensor = Eigen::Vector3d::Zero();  ///< sensor position, world frame
    /** Top beam's elevation as the largest z * |z| / (x^2 + y^2) of the points farther than
     *  2 m horizontally (sensor frame; monotone in z / range, no square root); -inf if none. */
    double top_slope_sq = -std::numeric_limits<double>::infinity();
    std::size_t points_valid = 0;    ///< valid input points, repeats included
    std::size_t points_invalid = 0;  ///< non-finite, or outside the int32 index range

    [[nodiscard]] std::size_t pillarCount() const { return keys.size(); }
    [[nodiscard]] std::size_t entryCount() const { return cells.size(); }

    /** Scratch of bucketScan(), kept to be reused. */
    std::vector<int32_t> tmp_m, tmp_n, tmp_z;
    std::vector<uint32_t> tmp_src, tmp_bin, tmp_counts;
};

/** The global pillar dictionary G = {H_mn : P_mn} of the paper, with its update and queries.
 *  Copyable. Concurrent const calls (queries, classify) are safe; insertion is not. */
class PillarGrid
{
public:
    /** Throws std::invalid_argument if `params` is invalid (see Params::validate()). */
    explicit PillarGrid(const Params& params = Params());

    /** Integrates one scan. `points` are in the sensor frame, `sensor_to_world` places them in
     *  the world frame (the frame of the grid). Every pillar that receives at least one point
     *  is updated (Eq. 8-18) or created; other pillars are untouched. The same as
     *  bucketScan(), buildIntervals(), mergeScan() in a row, then the see-through misses when
     *  Params::see_through_range > 0. */
    InsertStats insertScan(const PointsView& points, const Eigen::Isometry3d& sensor_to_world =
                                                         Eigen::Isometry3d::Identity());

    /** @name The three steps of insertScan(), public so that each can be timed and reused
     *  @{ */
    /** Step 1: transforms and quantizes every point (Eq. 1), skips invalid ones, and groups
     *  them by pillar in one counting-sort pass (a comparison sort only when the scan spans
     *  more than 2^22 pillars). With `keep_index`, out.index gets each point's input index. */
    void bucketScan(const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
                    ScanPillars& out, bool keep_index = false) const;
    /** Step 2: sorts each pillar's height cells and builds its spans (Eq. 4, with the
     *  range-adaptive gap and padding) and its field-of-view ceiling. */
    void buildIntervals(ScanPillars& scan) const;
    /** Step 3: the Bayes update of every pillar of the scan (Eq. 8-18), or its creation. */
    InsertStats mergeScan(const ScanPillars& scan);
    /** @} */

    /** P(static) at a world point: that of the interval containing it; else the pillar's
     *  p_empty when the pillar exists; else Params::p_empty_init (nothing known). */
    [[nodiscard]] double staticProbability(double x, double y, double z) const;

    /** True when the log-odds of staticProbability(x, y, z) is at least
     *  logit(Params::static_threshold) (that is, the probability is at least the threshold). */
    [[nodiscard]] bool isStatic(double x, double y, double z) const;

    /** Classifies every point (sensor frame, placed by `sensor_to_world`): is_dynamic[i] = 1
     *  unless point i is static. `is_dynamic` is resized to points.size. Points are grouped by
     *  pillar first, so each pillar is looked up once. */
    ClassifyStats classify(
        const PointsView& points, std::vector<uint8_t>& is_dynamic,
        const Eigen::Isometry3d& sensor_to_world = Eigen::Isometry3d::Identity()) const;

    [[nodiscard]] const Params& params() const { return params_; }
    /** Replaces the parameters; the pillars are kept. Throws std::invalid_argument if `params`
     *  is invalid, or changes the grid geometry (pillar_size, origin_x, origin_y,
     *  height_resolution) while the grid is not empty. */
    void setParams(const Params& params);

    /** Threads used by insertion and classification (default 1; more than the machine's
     *  cores run as that many). Work is split by pillar, and pillars are independent, so every
     *  thread count gives the same map bit for bit. */
    void setThreads(std::size_t threads);
    [[nodiscard]] std::size_t threads() const { return threads_; }

    [[nodiscard]] bool empty() const { return pillars_.empty(); }
    [[nodiscard]] std::size_t pillarCount() const { return pillars_.size(); }
    [[nodiscard]] std::size_t intervalCount() const;
    [[nodiscard]] std::size_t maxIntervalsInAPillar() const;
    /** Heap memory held by the map's content: the hash table's slots and control bytes, and
     *  every pillar's interval storage (capacity). Excludes the reusable scan buffers. */
    [[nodiscard]] std::size_t memoryBytes() const;
    void clear() { pillars_.clear(); }

    /** Pillar containing world (x, y); nullopt if the index does not fit in int32. */
    [[nodiscard]] std::optional<PillarIndex> pillarOf(double x, double y) const;
    /** Height cell containing z; nullopt if it does not fit in int32. */
    [[nodiscard]] std::optional<int32_t> heightCellOf(double z) const;
    /** Height of the bottom of cell `k`, metres. */
    [[nodiscard]] double cellBottom(int32_t k) const { return k * params_.height_resolution; }

    [[nodiscard]] const Pillar* findPillar(PillarIndex idx) const;
    /** All pillars sorted by (m, n): a deterministic order for saving and drawing. */
    [[nodiscard]] std::vector<std::pair<PillarIndex, const Pillar*>> sortedPillars() const;
    /** Sets a pillar (used when loading a saved map). Throws std::invalid_argument if the
     *  pillar breaks the invariant documented on Pillar or exceeds the interval bound. */
    void setPillar(PillarIndex idx, Pillar pillar);

    /** Same parameters and same pillars (the thread count is not part of the map). */
    friend bool operator==(const PillarGrid& a, const PillarGrid& b);

private:
    Params params_;
    LogOddsModel model_;
    double static_logodds_ = 0.0;  ///< logit(static_threshold)
    absl::flat_hash_map<uint64_t, Pillar, PackedKeyHash> pillars_;
    std::size_t threads_ = 1;
    struct Arena;                   ///< TBB arena of threads_ threads (kept out of this header)
    std::shared_ptr<Arena> arena_;  ///< null when threads_ == 1; shared by copies

    // Reused between scans so that insertion does not allocate in steady state.
    ScanPillars scan_;
    std::vector<Pillar*> targets_;
    std::vector<Interval> scratch_;
    std::vector<float> see_through_image_;
    std::vector<uint8_t> see_through_hit_;

    /** See-through misses (Params::see_through_range > 0), after mergeScan(): a miss (Eq. 13)
     *  for every interval of a pillar the scan did not hit, within see_through_range of the
     *  sensor, that a beam of the scan passed through. Pillars are split over threads. */
    void seeThroughMisses(const PointsView& pts, const Eigen::Isometry3d& T,
                          const ScanPillars& scan);
    /** The see-through test of one pillar, whose axis is base + up * z in the sensor frame,
     *  against the scan's range image `img`. */
    void seeThroughPillar(Pillar& pil, const Eigen::Vector3d& base, const Eigen::Vector3d& up,
                          const std::vector<float>& img, double margin) const;
    /** Log-odds of P(static) at a world point (logit(p_empty_init) where nothing is known). */
    [[nodiscard]] double logOddsAt(double x, double y, double z) const;

    /** Calls f(begin, end) over [0, n) in chunks: on this thread when threads_ == 1, else in
     *  parallel (TBB) with at most threads_ threads. */
    template <typename F>
    void forRanges(std::size_t n, std::size_t grain, F&& f) const;
};

}  // namespace hif
