// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Sensor.h
 * @brief  The LiDARs hif-synthetic-kitti can simulate: spinning sensors with a fixed set of beams
 *         (Velodyne HDL-64E, HDL-32E, VLP-16, Ouster OS1-128, evenly spaced; a Velodyne VLP-32C,
 *         crowded near the horizon) and a non-repetitive rosette with a limited field of view
 *         (Livox Mid-70 style).
 */
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace synth
{
struct Sensor
{
    std::string name;
    std::string description;
    /** Spinning: the beams' elevations, degrees, top first; one ring each, fired over
     *  `columns` azimuth steps per turn (one turn a scan). Empty for a rosette. */
    std::vector<double> elevations_deg;
    int columns = 0;
    /** Spinning: how far, in columns, the firing azimuths move on from one turn to the next.
     *  A Velodyne fires on its own clock while its motor turns, and a turn is not a whole
     *  number of firings, so each scan samples the azimuths a fraction of a column away from
     *  the last one's; an Ouster fires at fixed encoder positions, the same every turn (0). */
    double column_drift = 0.0;
    /** Rosette (two counter-rotating prisms, as Livox sensors scan): points per scan and the
     *  field of view's full angle, degrees, around the forward axis (+x). */
    std::size_t rosette_points = 0;
    double rosette_fov_deg = 0;
    double max_range = 80.0;  ///< metres

    /** The beam directions (unit, sensor frame) of the scan that starts at `t` seconds, in the
     *  order the sensor fires them: ring after ring for a spinning sensor (as KITTI stores its
     *  points), in time for a rosette, whose pattern never repeats from one scan to the next. */
    void directions(double t, double scan_period, std::vector<Eigen::Vector3d>& out) const;
};

/** The sensor called `name` (see sensorNames()); throws std::runtime_error naming the known
 *  ones otherwise. */
[[nodiscard]] const Sensor& sensorNamed(const std::string& name);
/** "hdl-64e, hdl-32e, vlp-16, os1-128, vlp-32c, mid-70". */
[[nodiscard]] std::string sensorNames();

}  // namespace synth
