// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarGrid.h
 * @brief  The global HIF map G: pillars on a fixed grid, updated scan by scan, and the
 *         classification of points as static or dynamic.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "hif/FreeSpaceTest.h"
#include "hif/GridGeometry.h"
#include "hif/Params.h"
#include "hif/Pillar.h"
#include "hif/PillarIndex.h"
#include "hif/SensorModel.h"

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
    std::size_t points_used = 0;     ///< points that updated the map
    std::size_t points_invalid = 0;  ///< non-finite, or outside the int32 index range: skipped
    /** Of points_invalid, the finite points whose pillar or height cell does not fit in int32
     *  (more than 2^31 pillars or height cells from the origin): a pose or an origin far off. */
    std::size_t points_outside_grid = 0;
    std::size_t points_near = 0;      ///< nearer the sensor than Params::min_range: skipped
    std::size_t pillars_updated = 0;  ///< existing pillars matched by the scan
    std::size_t pillars_created = 0;  ///< pillars seen for the first time
    /** With Params::sensor_from_scans: the model was estimated from this scan (the first one
     *  with enough points, or one of the next kSensorSettleScans that saw more of the sensor),
     *  or this scan was checked against it. */
    bool sensor_estimated = false;
    bool sensor_checked = false;
    /** Why the scan checked does not look like the model's sensor (SensorModel::
     *  contradiction()); empty when it does or when not checked. */
    std::string sensor_contradiction;
};

/** What one classify() found. */
struct ClassifyStats
{
    std::size_t static_points = 0;
    std::size_t dynamic_points = 0;
    std::size_t invalid_points = 0;  ///< non-finite: reported dynamic (not part of the map)
    std::size_t near_points = 0;     ///< nearer the sensor than Params::min_range: dynamic
    /** Points of the map's static intervals that the free-space test showed gone. */
    std::size_t seen_through_points = 0;
    /** Scans of the free-space test that judged this one (0: the map's verdict alone). */
    std::size_t free_space_scans = 0;
};

namespace detail
{
struct GridAccess;
}  // namespace detail

/** The global pillar dictionary G = {H_mn : P_mn} of the paper, with its update and queries.
 *  Copyable. Const calls (queries, classify) never change the map, and may run concurrently
 *  with each other; insertion and the setters may not run concurrently with anything. */
class PillarGrid
{
public:
    /** Throws std::invalid_argument if `geometry` or `params` is invalid (see
     *  Params::validateWith()). */
    explicit PillarGrid(const GridGeometry& geometry = GridGeometry(),
                        const Params& params = Params());

    /** @name Insertion and classification
     *  @{ */

    /** Integrates one scan. `points` are in the sensor frame, `sensor_to_world` places them in
     *  the world frame (the frame of the grid). Every pillar that receives at least one point
     *  is updated (Eq. 8-18) or created; other pillars are untouched, except by the see-through
     *  misses when Params::see_through_range > 0. Invalid points (non-finite, or beyond the
     *  int32 index range) are skipped and counted. */
    InsertStats insertScan(const PointsView& points, const Eigen::Isometry3d& sensor_to_world =
                                                         Eigen::Isometry3d::Identity());

    /** Classifies every point (sensor frame, placed by `sensor_to_world`, computed exactly as
     *  insertScan() does): is_dynamic[i] = 1 unless point i is static (isStatic() at its world
     *  position). Non-finite points are dynamic; finite points beyond the index range lie in
     *  unknown space. `is_dynamic` is resized to points.size. With `free_space` and
     *  Params::free_space_window > 0, the free-space test follows: of the points found static,
     *  those of a pillar that the test's scans showed gone are dynamic too (see FreeSpaceTest
     *  for which scans judge). */
    ClassifyStats classify(const PointsView& points, std::vector<uint8_t>& is_dynamic,
                           const Eigen::Isometry3d& sensor_to_world = Eigen::Isometry3d::Identity(),
                           const FreeSpaceTest* free_space = nullptr) const;
    /** @} */

    /** @name Point queries (world frame)
     *  @{ */

    /** P(static) at a world point: that of the interval containing it; else the pillar's
     *  p_empty when the pillar exists; else Params::p_empty_init (nothing known). */
    [[nodiscard]] double staticProbability(double x, double y, double z) const;
    /** True when the log-odds of staticProbability(x, y, z) is at least
     *  logit(Params::static_threshold) (that is, the probability is at least the threshold). */
    [[nodiscard]] bool isStatic(double x, double y, double z) const;
    /** The one rule of what is static: a log-odds (an interval's, or a pillar's p_empty) of at
     *  least logit(Params::static_threshold). */
    [[nodiscard]] bool isStaticLogOdds(double logodds) const { return logodds >= static_logodds_; }
    /** @} */

    /** @name Settings
     *  @{ */
    [[nodiscard]] const GridGeometry& geometry() const { return geometry_; }
    [[nodiscard]] const Params& params() const { return params_; }
    /** Replaces the parameters (the geometry and the pillars stay). Throws
     *  std::invalid_argument if `params` is invalid (see Params::validateWith()). */
    void setParams(const Params& params);

    /** The model of the LiDAR in effect (estimated from the first scan with
     *  Params::sensor_from_scans, or set); none before. */
    [[nodiscard]] const std::optional<SensorModel>& sensorModel() const { return sensor_; }
    /** Sets the model in effect (or none), given rather than estimated: with
     *  Params::sensor_from_scans, the next scan inserted is checked against it (and every 50th
     *  after). Throws std::invalid_argument if it is invalid. */
    void setSensorModel(std::optional<SensorModel> model);
    /** Range images' layout for the model in effect (RangeImageLayout::forSensor()). */
    [[nodiscard]] const RangeImageLayout& imageLayout() const { return layout_; }
    /** The range-adaptive intervals' vertical gap between neighbouring beams, per metre of
     *  horizontal distance, in the direction tan_el (elevation from the sensor): with a model
     *  of rings, that of the two beams around it (SensorModel::beamGapSlope()); without a
     *  model, tan(Params::beam_spacing_deg); 0 when off (beam_spacing_deg 0). */
    [[nodiscard]] double beamGapSlope(double tan_el) const;
    /** p_empty of a new pillar in effect (Eq. 14's prior where nothing is known yet):
     *  Params::p_empty_init, but not under 0.5 with a sensor model without rings (a
     *  non-repetitive pattern, a Livox-style rosette). Under 0.5, a height seen once is
     *  dynamic until a second sighting; a spinning LiDAR samples a static surface at the same
     *  heights scan after scan, but a non-repetitive one samples it at new heights in every
     *  scan, so there a height seen once is no sign that something moved (doc/sensors.md). */
    [[nodiscard]] double pEmptyInit() const;
    /** Scans between two checks of a scan against the sensor model. */
    static constexpr std::size_t kSensorCheckInterval = 50;
    /** Scans after the one a model was estimated from that are estimated too when they hold
     *  more points (by a tenth), the model replaced by theirs where they saw more of the sensor
     *  (SensorModel::seesLessThan()): a first scan that is part of a sweep does not set the
     *  model for the run. */
    static constexpr std::size_t kSensorSettleScans = 2;

    /** Threads used by insertion and classification (default 1; more than the machine's
     *  cores run as that many). Work is split by pillar, and pillars are independent, so every
     *  thread count gives the same map bit for bit. Throws std::invalid_argument for 0. */
    void setThreads(std::size_t threads);
    [[nodiscard]] std::size_t threads() const { return threads_; }
    /** @} */

    /** @name Contents
     *  @{ */
    [[nodiscard]] bool empty() const;
    [[nodiscard]] std::size_t pillarCount() const;
    [[nodiscard]] std::size_t intervalCount() const;
    [[nodiscard]] std::size_t maxIntervalsInAPillar() const;
    /** Intervals the map keeps (isStaticLogOdds()): the boxes getVisualizationInto() draws. */
    [[nodiscard]] std::size_t staticIntervalCount() const;
    /** Heap memory held by the map's content: the hash table's slots and control bytes, and
     *  every pillar's interval storage (capacity). Excludes the reusable scan buffers. */
    [[nodiscard]] std::size_t memoryBytes() const;
    /** Removes every pillar and the sensor model. */
    void clear();
    /** Frees the buffers that insertion and classification keep from one scan to the next
     *  (about 80 bytes a point of the largest scan): for a map that is done with insertion,
     *  or idle. The map is unchanged; the next call allocates them again. */
    void releaseScanBuffers();

    [[nodiscard]] const Pillar* findPillar(PillarIndex idx) const;
    /** All pillars sorted by (m, n): a deterministic order for saving and drawing. */
    [[nodiscard]] std::vector<std::pair<PillarIndex, const Pillar*>> sortedPillars() const;
    /** Sets a pillar (used when loading a saved map). Throws std::invalid_argument if the
     *  pillar breaks the invariant documented on Pillar or exceeds the interval bound. */
    void setPillar(PillarIndex idx, Pillar pillar);

    /** Same geometry, parameters, sensor model and pillars (the thread count is not part of
     *  the map). */
    friend bool operator==(const PillarGrid& a, const PillarGrid& b);
    /** @} */

private:
    friend struct detail::GridAccess;  // the insertion steps (detail/InsertSteps.h)

    GridGeometry geometry_;
    Params params_;
    double static_logodds_ = 0.0;  ///< logit(static_threshold)
    std::size_t threads_ = 1;
    /** The pillars' table, the threads and the buffers insertion and classification reuse
     *  (GridAccess.h). */
    struct State;
    /** Owns the State: a copy holds a copy of the table (and the same threads) with buffers of
     *  its own; one moved from may only be assigned to or destroyed. */
    class StateHolder
    {
    public:
        StateHolder();
        ~StateHolder();
        StateHolder(const StateHolder& other);
        StateHolder& operator=(const StateHolder& other);
        StateHolder(StateHolder&& other) noexcept;
        StateHolder& operator=(StateHolder&& other) noexcept;
        State* operator->() const { return p_.get(); }

    private:
        std::unique_ptr<State> p_;
    };
    StateHolder state_;
    std::optional<SensorModel> sensor_;
    std::vector<double> beam_tangents_;  ///< sensor_->beamTangents()
    /** Where the sensor's next beam lies farther than 1.5 median spacings, per row of layout_
     *  (detail::nextBeamRowsTable()). */
    std::vector<uint16_t> next_beam_rows_;
    RangeImageLayout layout_ = RangeImageLayout::forSensor(std::nullopt);
    std::size_t scans_since_check_ = 0;  ///< a check is due when it reaches kSensorCheckInterval
    std::size_t settle_scans_left_ = 0;  ///< kSensorSettleScans after an estimate, counted down
    std::size_t estimated_from_points_ = 0;  ///< points of the scan the model was estimated from

    /** The model (valid or none), its image layout and beam tangents; setSensorModel() also
     *  resets the checks, as for a given model. */
    void useSensorModel(std::optional<SensorModel> model);

    /** Log-odds of P(static) at a world point (logit(p_empty_init) where nothing is known). */
    [[nodiscard]] double logOddsAt(double x, double y, double z) const;
};

}  // namespace hif
