// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SensorModel.h
 * @brief  What a LiDAR can see: its beams' elevations (or, for a non-repetitive pattern, how
 *         densely it samples), its field of view and its horizontal resolution, estimated from
 *         a scan. The sensor-dependent settings of the map (the range-adaptive intervals, the
 *         range images of the see-through and free-space tests) come from it.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace hif
{
struct PointsView;

/** A LiDAR's sampling pattern, as seen from its own frame (x forward, z up). Angles in
 *  degrees; elevation = atan2(z, sqrt(x^2 + y^2)). */
struct SensorModel
{
    /** The beams' elevations, ascending: one per ring of a spinning LiDAR. Empty for a
     *  non-repetitive pattern (a Livox rosette), which has no rings. */
    std::vector<double> beam_elevations_deg;
    /** The vertical field of view: the lowest and highest elevation sampled. */
    double elevation_min_deg = 0.0;
    double elevation_max_deg = 0.0;
    /** Median angle between neighbouring beams; non-repetitive: the mean angular distance
     *  between the points of one scan (sqrt(solid angle covered / points)). */
    double vertical_spacing_deg = 0.0;
    /** Median azimuth step between consecutive points of one beam; non-repetitive: as
     *  vertical_spacing_deg. */
    double horizontal_resolution_deg = 0.0;
    /** Degrees of azimuth the scan covers (360 for a spinning LiDAR). */
    double azimuth_coverage_deg = 0.0;

    /** A spinning LiDAR given by its beams' elevations (any order), its horizontal step and
     *  the azimuth it covers: the field of view from the lowest to the highest beam, the
     *  vertical spacing the median gap between neighbours. Throws std::invalid_argument if it
     *  makes no sense (fewer than 2 beams, two at one elevation, see validate()). */
    [[nodiscard]] static SensorModel fromBeams(std::vector<double> elevations_deg,
                                               double horizontal_resolution_deg,
                                               double azimuth_coverage_deg = 360.0);
    /** A non-repetitive pattern (a Livox rosette) given by its field of view and the mean
     *  angle between its points in one scan. Throws std::invalid_argument as validate(). */
    [[nodiscard]] static SensorModel fromPattern(double elevation_min_deg, double elevation_max_deg,
                                                 double spacing_deg, double azimuth_coverage_deg);

    [[nodiscard]] bool hasRings() const { return !beam_elevations_deg.empty(); }
    /** tan() of the beams' elevations (ascending), for beamGapSlope(). */
    [[nodiscard]] std::vector<double> beamTangents() const;
    /** The vertical gap between the two beams around elevation tan_el, per metre of horizontal
     *  distance: tan(e_k+1) - tan(e_k) for the beams e_k <= atan(tan_el) < e_k+1 (the nearest
     *  pair outside them); without rings, tan(vertical_spacing_deg). `tangents` is
     *  beamTangents(). */
    [[nodiscard]] double beamGapSlope(const std::vector<double>& tangents, double tan_el) const;
    /** One line for a log: "64 beams from -24.9 to 2.0 deg, 0.42 deg apart (median), 0.17 deg
     *  horizontally, 360 deg of azimuth"; for beams spaced unevenly, whose widest gap is more
     *  than one and a half median spacings, "(median; 9.361 at the widest)". */
    [[nodiscard]] std::string describe() const;

    /** Throws std::invalid_argument naming the first field that makes no sense (a spacing or
     *  resolution outside (0, 10] degrees, a field of view that is empty or beyond +-90
     *  degrees, beams not ascending or outside it). */
    void validate() const;

    /** The model of the LiDAR that took `points` (sensor frame), from the points farther than
     *  kMinEstimateRange horizontally: rings are the elevation bands that hold points, with
     *  empty bands between them; a scan whose elevations leave no empty bands (a rosette) has
     *  none. Nullopt when fewer than kMinEstimatePoints such points, or when what they give is
     *  no LiDAR (fails validate()): nothing to go on. */
    [[nodiscard]] static std::optional<SensorModel> estimate(const PointsView& points);

    /** Why `other` (estimated from a later scan) does not look like the same sensor, or
     *  nullopt when it does: a different number of rings (by more than a tenth, since a scan
     *  with much sky misses some), or a vertical spacing or horizontal resolution that differs
     *  by more than a quarter. */
    [[nodiscard]] std::optional<std::string> contradiction(const SensorModel& other) const;
    /** Whether `other` (estimated from a later scan) saw more of the same kind of sensor than
     *  this model did: more rings, a wider vertical field of view or more azimuth, each by
     *  more than a tenth. A scan that is part of a sweep (a driver's first message, cut short)
     *  gives a model that the next whole sweep shows more of. */
    [[nodiscard]] bool seesLessThan(const SensorModel& other) const;

    /** Points nearer the sensor than this (horizontally, metres) are not used by estimate():
     *  a LiDAR's lasers sit a few centimetres apart, which blurs the elevations of near
     *  returns by more than the gap between rings. */
    static constexpr double kMinEstimateRange = 2.0;
    static constexpr std::size_t kMinEstimatePoints = 200;

    friend bool operator==(const SensorModel& a, const SensorModel& b);

private:
    /** estimate() before validation. */
    [[nodiscard]] static std::optional<SensorModel> estimateAny(const PointsView& points);

public:
    friend bool operator!=(const SensorModel& a, const SensorModel& b) { return !(a == b); }
};

/** How a range image (the nearest return in each cell of directions around the sensor, as the
 *  see-through and free-space tests use it) is laid out: columns uniform in a pseudo-azimuth
 *  in [0, 4) (one division instead of an atan2), rows uniform in tan(elevation). */
struct RangeImageLayout
{
    int cols = 1800;
    int rows = 0;
    double tan_min = 0.0;  ///< the bottom row's lower edge
    double tan_max = 0.0;  ///< the top row's upper edge (excluded)
    double tan_res = 0.0;  ///< a row's height

    /** The layout for `model`: a column per half horizontal step and a row per half vertical
     *  spacing (so that neighbouring beams and neighbouring points of a beam fall in different
     *  cells), over the field of view and
     *  two spacings beyond it. Without a model, rows of 0.2 degrees from -30 to +15 degrees and
     *  1800 columns (a 64-beam layout; what hif used before it had sensor models). */
    [[nodiscard]] static RangeImageLayout forSensor(const std::optional<SensorModel>& model);

    [[nodiscard]] std::size_t cells() const
    {
        return static_cast<std::size_t>(cols) * static_cast<std::size_t>(rows);
    }
    friend bool operator==(const RangeImageLayout& a, const RangeImageLayout& b)
    {
        return a.cols == b.cols && a.rows == b.rows && a.tan_min == b.tan_min &&
               a.tan_max == b.tan_max && a.tan_res == b.tan_res;
    }
};

}  // namespace hif
