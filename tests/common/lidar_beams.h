// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   lidar_beams.h
 * @brief  Beam tables of real LiDARs for the tests: the references the sensor model, the
 *         simulated sensors and the rules that look for a sensor's next beam are checked
 *         against.
 */
#pragma once

#include <vector>

namespace hif::test
{
/** A Velodyne VLP-32C's beam elevations, degrees, top first, as its manual lists them: a third
 *  of a degree apart from +1.67 to -4, then 0.67 to 9.4 apart down to -25, and 0.67 to 4.7
 *  apart up to +15. */
inline std::vector<double> vlp32cBeams()
{
    return {15.0,   10.333, 7.0,    4.667,  3.333,  2.333,  1.667,  1.333,  1.0,     0.667, 0.333,
            0.0,    -0.333, -0.667, -1.0,   -1.333, -1.667, -2.0,   -2.333, -2.667,  -3.0,  -3.333,
            -3.667, -4.0,   -4.667, -5.333, -6.148, -7.254, -8.843, -11.31, -15.639, -25.0};
}
}  // namespace hif::test
