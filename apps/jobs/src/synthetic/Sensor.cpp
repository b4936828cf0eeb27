// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Sensor.cpp
 * @brief  The simulated sensors and their beam patterns.
 */
#include "Sensor.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace synth
{
namespace
{
/** `n` elevations from `top` down to `bottom`, evenly spaced (degrees). */
std::vector<double> evenly(int n, double top, double bottom)
{
    std::vector<double> e;
    for (int b = 0; b < n; ++b) e.push_back(top - (top - bottom) * b / (n - 1));
    return e;
}

/** How far a Velodyne's firings drift against its turns (Sensor::column_drift), in columns; by
 *  how much depends on its motor's speed. 0.382 (1 - 1 / golden ratio) spreads the phases of a
 *  short clip evenly over the column, never the same twice. */
constexpr double kVelodyneDrift = 0.381966;

/** A spinning sensor whose beams lie at the elevations `table` (degrees, any order),
 *  `columns` a turn, its firings drifting by `column_drift` a turn. */
Sensor spinningAt(const char* name, const char* description, std::vector<double> table, int columns,
                  double max_range, double column_drift)
{
    Sensor s;
    s.name = name;
    s.description = description;
    std::sort(table.begin(), table.end(), std::greater<>());
    s.elevations_deg = std::move(table);
    s.columns = columns;
    s.max_range = max_range;
    s.column_drift = column_drift;
    return s;
}

/** A spinning sensor: `beams` evenly from `top` to `bottom` degrees, `columns` a turn. */
Sensor spinning(const char* name, const char* description, int beams, double top, double bottom,
                int columns, double max_range, double column_drift)
{
    return spinningAt(name, description, evenly(beams, top, bottom), columns, max_range,
                      column_drift);
}

std::vector<Sensor> makeSensors()
{
    std::vector<Sensor> s{
        spinning("hdl-64e", "64 beams, +2 to -24.8 degrees, 1024 columns, 80 m (KITTI's)", 64, 2.0,
                 -24.8, 1024, 80.0, kVelodyneDrift),
        spinning("hdl-32e", "32 beams, +10.67 to -30.67 degrees (1.33 apart), 1800 columns, 100 m",
                 32, 10.67, -30.67, 1800, 100.0, kVelodyneDrift),
        spinning("vlp-16", "16 beams, +15 to -15 degrees (2 apart), 1800 columns, 100 m", 16, 15.0,
                 -15.0, 1800, 100.0, kVelodyneDrift),
        spinning("os1-128", "128 beams, +22.5 to -22.5 degrees (0.35 apart), 1024 columns, 120 m",
                 128, 22.5, -22.5, 1024, 120.0, 0.0),  // fires at fixed encoder counts
        // The VLP-32C's beams as its manual lists them: a third of a degree apart around the
        // horizon, up to 9 degrees apart at the bottom and top of its view.
        spinningAt("vlp-32c",
                   "32 beams, +15 to -25 degrees, unevenly: 0.33 apart from +1.67 to -4, up to 9 "
                   "apart at the ends (Velodyne VLP-32C), 1800 columns, 200 m",
                   {-25.0,  -1.0,  -1.667, -15.639, -11.31, 0.0,   -0.667, -8.843,
                    -7.254, 0.333, -0.333, -6.148,  -5.333, 1.333, 0.667,  -4.0,
                    -4.667, 1.667, 1.0,    -3.667,  -3.333, 3.333, 2.333,  -2.667,
                    -3.0,   7.0,   4.667,  -2.333,  -2.0,   15.0,  10.333, -1.333},
                   1800, 200.0, kVelodyneDrift)};
    Sensor livox;
    livox.name = "mid-70";
    livox.description =
        "non-repetitive rosette, 70.4 degrees circular field of view ahead, 10,000 points a "
        "scan, 90 m (Livox Mid-70 style)";
    livox.rosette_points = 10000;
    livox.rosette_fov_deg = 70.4;
    livox.max_range = 90.0;
    s.push_back(livox);
    return s;
}

const std::vector<Sensor>& sensors()
{
    static const std::vector<Sensor> all = makeSensors();
    return all;
}
}  // namespace

void Sensor::directions(double t, double scan_period, std::vector<Eigen::Vector3d>& out) const
{
    out.clear();
    if (rosette_points == 0)
    {
        // The turn's firing phase: its drift from the first turn, within one column.
        const double turn = std::round(t / scan_period);
        const double phase = turn * column_drift - std::floor(turn * column_drift);
        for (const double el_deg : elevations_deg)
        {
            const double el = el_deg * M_PI / 180.0;
            for (int c = 0; c < columns; ++c)
            {
                const double az = 2.0 * M_PI * (c + phase) / columns;
                out.emplace_back(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                 std::sin(el));
            }
        }
        return;
    }
    // Two prisms turning the opposite ways at rates whose ratio is far from any small
    // fraction: the deflection traces petals that fill the field of view, a little further
    // with every scan, never the same path twice.
    constexpr double kRate1 = 2.0 * M_PI * 73.3, kRate2 = -2.0 * M_PI * 49.1;  // rad/s
    const double half = 0.5 * rosette_fov_deg * M_PI / 180.0;
    for (std::size_t k = 0; k < rosette_points; ++k)
    {
        const double tk = t + scan_period * double(k) / double(rosette_points);
        const double u = 0.5 * half * (std::cos(kRate1 * tk) + std::cos(kRate2 * tk));
        const double v = 0.5 * half * (std::sin(kRate1 * tk) + std::sin(kRate2 * tk));
        // (u, v): angles off the forward axis, to the left and up.
        out.push_back(Eigen::Vector3d(1.0, std::tan(u), std::tan(v)).normalized());
    }
}

const Sensor& sensorNamed(const std::string& name)
{
    for (const Sensor& s : sensors())
        if (s.name == name) return s;
    throw std::runtime_error("--sensor '" + name + "' is not one of " + sensorNames());
}

std::string sensorNames()
{
    std::string names;
    for (const Sensor& s : sensors()) names += (names.empty() ? "" : ", ") + s.name;
    return names;
}

}  // namespace synth
