// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap.h
 * @brief  hif::CHeightIntervalMap: the HIF dynamic-points-removal map as a native MRPT metric map.
 */
#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/CMetricMap.h>
#include <mrpt/maps/CPointsMap.h>
#include <mrpt/math/TPoint3D.h>
#include <mrpt/obs/obs_frwds.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdint>
#include <vector>

#include "hif/PillarGrid.h"

namespace hif
{
/** A map of vertical pillars, each holding height intervals with a probability of being
 *  static: Height Interval Filtering (HIF). Insert scans at their poses; then ask which points
 *  are static (`isStatic()`, `classify()`), i.e. to remove moving objects from a point cloud map.
 *
 *  Created from an .ini like any MRPT map (see the .ini files in share/hif/config):
 *  \code
 *  [map]
 *  CHeightIntervalMap_count=1
 *  [map_CHeightIntervalMap_00_creationOpts]
 *  pillar_size=1.0
 *  [map_CHeightIntervalMap_00_insertOpts]
 *  alpha=0.6
 *  \endcode
 *
 *  Inserts `CObservationPointCloud` (any CPointsMap inside), `CObservation3DRangeScan` and
 *  `CObservation2DRangeScan`, at robot pose (+) sensor pose. Probabilities are P(static), the
 *  paper's "occupancy probability" (MRPT's occupancy grids store freeness instead).
 *
 *  Observation likelihood: the sum over the points of log P(static) at the point.
 *  The algorithm lives in hif::PillarGrid (no MRPT types); this class adapts it.
 */
class CHeightIntervalMap : public mrpt::maps::CMetricMap
{
    DEFINE_SERIALIZABLE(CHeightIntervalMap, hif)

public:
    /** @name User API
     * @{ */

    /** Grid geometry is fixed at construction (Eq. 1): pillar edge and origin in metres, and
     *  the vertical resolution of interval endpoints. */
    explicit CHeightIntervalMap(double pillar_size = Params().pillar_size,
                                double origin_x = Params().origin_x,
                                double origin_y = Params().origin_y,
                                double height_resolution = Params().height_resolution);

    /** P(static) at a world point (see hif::PillarGrid::staticProbability()). */
    [[nodiscard]] double staticProbability(const mrpt::math::TPoint3D& p) const;
    /** staticProbability(p) >= insertionOptions.static_threshold. */
    [[nodiscard]] bool isStatic(const mrpt::math::TPoint3D& p) const;
    /** Classifies points given in the world frame: isDynamic[i] = 1 unless point i is static.
     *  Returns the counts. */
    ClassifyStats classify(const mrpt::maps::CPointsMap& worldPoints,
                           std::vector<uint8_t>& isDynamic) const;

    [[nodiscard]] std::size_t pillarCount() const { return grid_.pillarCount(); }
    [[nodiscard]] std::size_t intervalCount() const { return grid_.intervalCount(); }
    /** What the last successful insertion did (points used/invalid, pillars updated/created). */
    [[nodiscard]] const InsertStats& lastInsertStats() const { return last_insert_; }

    /** The core map, for read access (pillars, intervals). */
    [[nodiscard]] const PillarGrid& grid() const;
    /** All parameters in effect: creation geometry plus insertionOptions. */
    [[nodiscard]] Params params() const;

    /** Observation points in the world frame, for an observation taken at `robotPose`
     *  (robotPose (+) the observation's sensor pose). Returns false for unsupported types. */
    static bool observationToWorldPoints(const mrpt::obs::CObservation& obs,
                                         const mrpt::poses::CPose3D& robotPose,
                                         std::vector<float>& xs, std::vector<float>& ys,
                                         std::vector<float>& zs);
    /** @} */

    /** @name Options
     * @{ */

    /** Insertion and classification parameters; same names and meaning as hif::Params (see
     *  doc/algorithm.md). Changes take effect at the next insertion or query. */
    class TInsertionOptions : public mrpt::config::CLoadableOptions
    {
    public:
        /** Heights merged into one interval when their gap is at most this, m (Default: 0.1) */
        double merge_gap = Params().merge_gap;
        /** Each scan interval widened by this below and above, m (Default: 0.05) */
        double interval_padding = Params().interval_padding;
        /** P_S when observed, Eq. 6, in (0.5, 1) (Default: 0.6) */
        double alpha = Params().alpha;
        /** P_D when observed, Eq. 6, in (0, 0.5) (Default: 0.45) */
        double beta = Params().beta;
        /** Lower clipping bound of probabilities, Eq. 17 (Default: 0.1) */
        double p_min = Params().p_min;
        /** Upper clipping bound of probabilities, Eq. 17 (Default: 0.9) */
        double p_max = Params().p_max;
        /** p_empty of a pillar seen for the first time (Default: 0.5) */
        double p_empty_init = Params().p_empty_init;
        /** Low-Height Preservation, Eq. 15-16 (Default: true) */
        bool low_height_preservation = Params().low_height_preservation;
        /** Keep intervals above the scan's field of view (ours; Default: true) */
        bool high_height_preservation = Params().high_height_preservation;
        /** New intervals above every height seen so far start at p_empty_init (ours;
         *  Default: true) */
        bool unseen_height_prior = Params().unseen_height_prior;
        /** Range-adaptive intervals: vertical beam spacing, degrees; 0 = the paper's fixed
         *  merge_gap/interval_padding (ours; Default: 0.44, for the HDL-64E) */
        double beam_spacing_deg = Params().beam_spacing_deg;
        /** See-through misses within this horizontal distance of the sensor, m; 0 = off, the
         *  paper (ours; Default: 0) */
        double see_through_range = Params().see_through_range;
        /** A return this far beyond a pillar passed through it; nearer ones veto, m (Default:
         *  2.5) */
        double see_through_margin = Params().see_through_margin;
        /** Static when P(static) >= this (Default: 0.5) */
        double static_threshold = Params().static_threshold;
        /** Bound on intervals per pillar (Default: 16) */
        uint64_t max_intervals_per_pillar = Params().max_intervals_per_pillar;
        /** Threads for insertion and classification, >= 1; any count gives the same map. A
         *  property of the machine, not of the map: read from and written to .ini files but
         *  not serialized with the map (Default: 1) */
        uint64_t threads = 1;

        /** Loads every field; throws if the result is invalid, naming the section and field. */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                              const std::string& section) const override;
        void writeToStream(mrpt::serialization::CArchive& out) const;
        /** Reads what writeToStream() wrote; `version` is the map's serialization version. */
        void readFromStream(mrpt::serialization::CArchive& in, uint8_t version);
    };
    TInsertionOptions insertionOptions;

    /** @} */

    /** @name CMetricMap interface
     * @{ */
    [[nodiscard]] bool isEmpty() const override;
    [[nodiscard]] std::string asString() const override;
    /** Every interval as a box over its pillar, coloured from red (p_min, dynamic) to green
     *  (p_max, static). */
    void getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const override;
    /** Writes `<prefix>_intervals.txt` (one interval per line: x_min y_min x_max y_max z_bottom
     *  z_top p_static) and `<prefix>_3D.3Dscene` (the visualization). */
    void saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const override;
    /** Fraction of the other map's points (a CPointsMap, placed at otherMapPose) that lie in a
     *  static interval of this map, within params.maxDistForCorr vertically. 0 for other maps. */
    float compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                 const mrpt::poses::CPose3D& otherMapPose,
                                 const mrpt::maps::TMatchingRatioParams& params) const override;
    /** @} */

    MAP_DEFINITION_START(CHeightIntervalMap)
    /** Pillar edge, m (Default: 1.0) */
    double pillar_size = Params().pillar_size;
    /** Grid origin, m (Default: 0, 0) */
    double origin_x = Params().origin_x;
    double origin_y = Params().origin_y;
    /** Vertical resolution of interval endpoints, m (Default: 0.05) */
    double height_resolution = Params().height_resolution;
    CHeightIntervalMap::TInsertionOptions insertionOpts;
    MAP_DEFINITION_END(CHeightIntervalMap)

private:
    /** Applies insertionOptions to the core if they changed (throws if they are invalid). */
    void syncParams() const;

    mutable PillarGrid grid_;
    InsertStats last_insert_;

    void internal_clear() override;
    bool internal_insertObservation(
        const mrpt::obs::CObservation& obs,
        const std::optional<const mrpt::poses::CPose3D>& robotPose = std::nullopt) override;
    double internal_computeObservationLikelihood(
        const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const override;
    bool internal_canComputeObservationLikelihood(
        const mrpt::obs::CObservation& obs) const override;
};

}  // namespace hif
