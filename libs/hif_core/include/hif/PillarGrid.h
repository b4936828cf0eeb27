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

/** What one insertScan() did. */
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

/** The global pillar dictionary G = {H_mn : P_mn} of the paper, with its update and queries.
 *  Copyable; not thread-safe for concurrent insertScan() calls. */
class PillarGrid
{
public:
    /** Throws std::invalid_argument if `params` is invalid (see Params::validate()). */
    explicit PillarGrid(const Params& params = Params());

    /** Integrates one scan. `points` are in the sensor frame, `sensor_to_world` places them in
     *  the world frame (the frame of the grid). Every pillar that receives at least one point
     *  is updated (Eq. 8-18) or created; other pillars are untouched. */
    InsertStats insertScan(const PointsView& points, const Eigen::Isometry3d& sensor_to_world =
                                                         Eigen::Isometry3d::Identity());

    /** P(static) at a world point: that of the interval containing it; else the pillar's
     *  p_empty when the pillar exists; else Params::p_empty_init (nothing known). */
    [[nodiscard]] double staticProbability(double x, double y, double z) const;

    /** staticProbability(x, y, z) >= Params::static_threshold. */
    [[nodiscard]] bool isStatic(double x, double y, double z) const;

    /** Classifies every point (sensor frame, placed by `sensor_to_world`): is_dynamic[i] = 1
     *  unless point i is static. `is_dynamic` is resized to points.size. */
    ClassifyStats classify(
        const PointsView& points, std::vector<uint8_t>& is_dynamic,
        const Eigen::Isometry3d& sensor_to_world = Eigen::Isometry3d::Identity()) const;

    [[nodiscard]] const Params& params() const { return params_; }
    /** Replaces the parameters; the pillars are kept. Throws std::invalid_argument if `params`
     *  is invalid, or changes the grid geometry (pillar_size, origin_x, origin_y,
     *  height_resolution) while the grid is not empty. */
    void setParams(const Params& params);
    [[nodiscard]] bool empty() const { return pillars_.empty(); }
    [[nodiscard]] std::size_t pillarCount() const { return pillars_.size(); }
    [[nodiscard]] std::size_t intervalCount() const;
    [[nodiscard]] std::size_t maxIntervalsInAPillar() const;
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

    /** Same parameters and same pillars. */
    friend bool operator==(const PillarGrid& a, const PillarGrid& b);

private:
    Params params_;
    LogOddsModel model_;
    absl::flat_hash_map<uint64_t, Pillar, PackedKeyHash> pillars_;

    struct KeyCell
    {
        uint64_t key;
        int32_t z;
    };
    // Reused between scans so that insertion does not allocate in steady state.
    std::vector<KeyCell> buf_points_;
    std::vector<int32_t> buf_cells_;
    std::vector<Span> buf_spans_;
    std::vector<Interval> buf_intervals_;
};

}  // namespace hif
