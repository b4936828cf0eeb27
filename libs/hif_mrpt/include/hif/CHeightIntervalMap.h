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
#include <mrpt/system/COutputLogger.h>

#include <cstdint>
#include <functional>
#include <optional>
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
 *  The algorithm lives in hif::PillarGrid (no MRPT types); this class adapts it. Warnings
 *  (an offline map classifying scans as they come) go to its COutputLogger.
 */
class CHeightIntervalMap : public mrpt::maps::CMetricMap, public mrpt::system::COutputLogger
{
    DEFINE_SERIALIZABLE(CHeightIntervalMap, hif)

public:
    /** @name User API
     * @{ */

    /** The grid geometry is fixed at construction (Eq. 1). Throws std::invalid_argument if
     *  `geometry` or `params` is invalid. */
    explicit CHeightIntervalMap(const GridGeometry& geometry = GridGeometry(),
                                const Params& params = Params());

    /** P(static) at a world point (see hif::PillarGrid::staticProbability()). */
    [[nodiscard]] double staticProbability(const mrpt::math::TPoint3D& p) const;
    /** staticProbability(p) >= the static_threshold in effect. */
    [[nodiscard]] bool isStatic(const mrpt::math::TPoint3D& p) const;
    /** Classifies points given in the world frame: isDynamic[i] = 1 unless point i is static.
     *  Returns the counts. A CPointsMap holds float32 coordinates, which keep millimetres only
     *  below about 8 km from the origin: for world coordinates in the millions of metres (UTM),
     *  classify the observation at its pose instead (computed in double). */
    ClassifyStats classify(const mrpt::maps::CPointsMap& worldPoints,
                           std::vector<uint8_t>& isDynamic) const;
    /** Classifies the points of an observation taken at `robotPose`, placed in the world
     *  exactly as insertObservation() places them (robotPose (+) sensor pose): isDynamic[i] =
     *  1 unless point i is static, in the observation's point order. With the free-space test
     *  on (free_space_window > 0), the map's freeSpaceTest() judges it too: online (the
     *  `online` option), the scans inserted before it; offline, the scans on both sides of it
     *  that addToFreeSpaceTest() was given (see FreeSpaceTest). Throws std::invalid_argument
     *  for an observation type the map cannot insert. */
    ClassifyStats classify(const mrpt::obs::CObservation& obs,
                           const mrpt::poses::CPose3D& robotPose,
                           std::vector<uint8_t>& isDynamic) const;
    /** Offline (the `online` option false), the second pass: once every scan is inserted, give
     *  the free-space test the scans again in their order, and classify scan k once scan k +
     *  free_space_window is given (or the last one is). Online, insertion gives it each scan,
     *  and this is not needed. Returns false for an observation type the map cannot insert. */
    bool addToFreeSpaceTest(const mrpt::obs::CObservation& obs,
                            const mrpt::poses::CPose3D& robotPose);
    /** addToFreeSpaceTest() in two steps, so that the second pass can build a scan's range
     *  image (most of the cost) on another thread while this map classifies: the scan for the
     *  test, made by `maker` (one per thread; this map is only read), laid out for the map's
     *  sensor model; nullopt for an observation type the map cannot insert. */
    [[nodiscard]] std::optional<FreeSpaceTest::Scan> makeFreeSpaceScan(
        const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& robotPose,
        FreeSpaceTest::ScanMaker& maker) const;
    /** Adds a scan that makeFreeSpaceScan() made, in the scans' order. Throws
     *  std::invalid_argument if it was made for another sensor model's layout. */
    void addToFreeSpaceTest(FreeSpaceTest::Scan scan);
    /** The scans that judge a classified one (see FreeSpaceTest); serialized with the map. */
    [[nodiscard]] const FreeSpaceTest& freeSpaceTest() const { return free_space_; }
    /** Frees the buffers kept from one scan to the next (PillarGrid::releaseScanBuffers()):
     *  offline, once every scan is inserted. */
    void releaseScanBuffers() { grid_.releaseScanBuffers(); }

    [[nodiscard]] std::size_t pillarCount() const { return grid_.pillarCount(); }
    [[nodiscard]] std::size_t intervalCount() const { return grid_.intervalCount(); }
    /** What the last successful insertion did (points used/invalid, pillars updated/created). */
    [[nodiscard]] const InsertStats& lastInsertStats() const { return last_insert_; }

    /** The core map, for read access (pillars, intervals, statistics). */
    [[nodiscard]] const PillarGrid& grid() const { return grid_; }
    [[nodiscard]] const GridGeometry& geometry() const { return grid_.geometry(); }
    /** The parameters in effect: insertionOptions as of the last insertion or applyOptions(). */
    [[nodiscard]] const Params& params() const { return grid_.params(); }

    /** Makes changes to insertionOptions take effect now, instead of at the next insertion.
     *  Throws std::invalid_argument naming the first invalid option. */
    void applyOptions();

    /** Observation points in the world frame, for an observation taken at `robotPose`
     *  (robotPose (+) the observation's sensor pose). Returns false for unsupported types. */
    static bool observationToWorldPoints(const mrpt::obs::CObservation& obs,
                                         const mrpt::poses::CPose3D& robotPose,
                                         std::vector<float>& xs, std::vector<float>& ys,
                                         std::vector<float>& zs);
    /** observationToWorldPoints() in double: world coordinates in the millions of metres (UTM,
     *  ENU with a large offset) keep their millimetres, which float32 does not. */
    static bool observationToWorldPoints(const mrpt::obs::CObservation& obs,
                                         const mrpt::poses::CPose3D& robotPose,
                                         std::vector<double>& xs, std::vector<double>& ys,
                                         std::vector<double>& zs);
    /** Points `first` to `first + size - 1` of an observation's `total`, in the world frame. */
    struct WorldPointsChunk
    {
        std::size_t first = 0, size = 0, total = 0;
        const double *xs = nullptr, *ys = nullptr, *zs = nullptr;
    };
    /** observationToWorldPoints() in double, given to `fn` a chunk of at most `chunk` points
     *  at a time, in order (the same coordinates, without holding a whole scan of them).
     *  Returns false for unsupported types, without calling `fn`. */
    static bool forEachWorldPointsChunk(const mrpt::obs::CObservation& obs,
                                        const mrpt::poses::CPose3D& robotPose, std::size_t chunk,
                                        const std::function<void(const WorldPointsChunk&)>& fn);
    /** @} */

    /** @name Options
     * @{ */

    /** Insertion and classification parameters: hif::Params (see doc/algorithm.md), with the
     *  same names in .ini files, plus the thread count. Changes take effect at the next
     *  insertion (or applyOptions()); queries use the parameters in effect (params()). */
    class TInsertionOptions : public mrpt::config::CLoadableOptions, public Params
    {
    public:
        /** Threads for insertion and classification, >= 1; any count gives the same map. A
         *  property of the machine, not of the map: read from and written to .ini files but
         *  not serialized with the map (Default: 1) */
        uint64_t threads = 1;
        /** The LiDAR, when given instead of estimated from the scans (see doc/sensors.md):
         *  `sensor_beams_deg` (every beam's elevation) and `sensor_horizontal_resolution_deg`
         *  for a spinning LiDAR, or `sensor_fov_deg` (lowest and highest elevation) and
         *  `sensor_spacing_deg` for a non-repetitive one, and `sensor_azimuth_deg` (Default:
         *  360). With sensor_from_scans, the first scan and every 50th after are checked
         *  against it. The model itself is serialized with the map, these keys are not
         *  (Default: none) */
        std::optional<SensorModel> sensor;

        /** Loads every field; throws std::invalid_argument if the result is invalid, naming
         *  the section and the field. */
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& source,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& target,
                              const std::string& section) const override;
        /** The parameters (not the thread count), in the layout of serialization version
         *  `version` (see Field::since_version). */
        void writeToStream(mrpt::serialization::CArchive& out) const;
        /** Reads what writeToStream() wrote in serialization version `version`; parameters
         *  newer than it take their defaults. */
        void readFromStream(mrpt::serialization::CArchive& in, uint8_t version);
    };
    TInsertionOptions insertionOptions;

    /** @} */

    /** @name CMetricMap interface
     * @{ */
    [[nodiscard]] bool isEmpty() const override;
    [[nodiscard]] std::string asString() const override;
    /** What the map keeps: every static interval (P(static) at least the static_threshold) as a
     *  box over its pillar (its top and sides), coloured by the height of its top from blue
     *  (low) through green to yellow (high). Intervals below the threshold (seen through, or
     *  never confirmed) are not drawn: the points in them are the ones classified dynamic. */
    void getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const override;
    /** Writes `<prefix>_intervals.txt` (one interval per line: x_min y_min x_max y_max z_bottom
     *  z_top p_static) and `<prefix>_3D.3Dscene` (the visualization). */
    void saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const override;
    /** Writes the map MRPT-serialized, in a gzip file of stored blocks (not compressed: most
     *  of it is range images, which compress poorly and slowly; hif-clean's map.hifmap); read
     *  it back with loadFromFile(). Throws
     *  std::runtime_error naming the file if it cannot be written. */
    void saveToFile(const std::string& file) const;
    /** Reads a map that saveToFile() wrote (or any MRPT-serialized hif::CHeightIntervalMap,
     *  gzip-compressed or not) into this one: its grid, options, sensor model and free-space
     *  test, as saved. Throws std::runtime_error naming the file if it cannot be read, is
     *  corrupt or holds something else. */
    void loadFromFile(const std::string& file);
    /** Writes getVisualizationInto()'s boxes as a scene that MRPT's SceneViewer3D opens. Throws
     *  std::runtime_error naming the file if it cannot be written. */
    void saveSceneToFile(const std::string& file) const;
    /** Fraction of the other map's points (a CPointsMap, placed at otherMapPose) that lie in a
     *  static interval of this map, within params.maxDistForCorr vertically. 0 for other maps. */
    float compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                 const mrpt::poses::CPose3D& otherMapPose,
                                 const mrpt::maps::TMatchingRatioParams& params) const override;
    /** @} */

    MAP_DEFINITION_START(CHeightIntervalMap)
    /** Pillar size, origin and height resolution (section `_creationOpts`). */
    hif::GridGeometry geometry;
    /** Section `_insertOpts`. */
    CHeightIntervalMap::TInsertionOptions insertionOpts;
    MAP_DEFINITION_END(CHeightIntervalMap)

private:
    PillarGrid grid_;
    InsertStats last_insert_;
    /** The free-space test's scans: online, the last ones inserted; offline, those given by
     *  addToFreeSpaceTest(). */
    FreeSpaceTest free_space_;
    /** An offline map classified a scan: what it warns of, once each (see classify()). */
    mutable bool classified_ = false;
    mutable bool warned_no_neighbours_ = false;
    bool warned_inserted_after_ = false;

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
