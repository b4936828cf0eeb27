// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ObservationPoints.h
 * @brief  The one place where MRPT observations and poses become the core's points and
 *         transform: insertion and classification both go through it.
 */
#pragma once

#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Geometry>
#include <vector>

#include "hif/PillarGrid.h"

namespace hif::mrpt_adapter
{
/** The points of an observation in its sensor frame, and where the sensor sits on the robot. */
struct SensorPoints
{
    PointsView view;  ///< into the observation where possible, else into `storage`
    mrpt::poses::CPose3D sensor_pose;
    std::vector<float> storage[3];

    SensorPoints() = default;
    SensorPoints(const SensorPoints&) = delete;  // `view` may point into `storage`
    SensorPoints& operator=(const SensorPoints&) = delete;
};

/** Fills `out` from a CObservationPointCloud (any CPointsMap inside; loaded if stored
 *  externally), a CObservation3DRangeScan (its 3D points, or its range image unprojected) or a
 *  CObservation2DRangeScan (its valid ranges, at z = 0). False for other types, and for a
 *  point cloud or 3D scan without points. */
bool sensorPoints(const mrpt::obs::CObservation& obs, SensorPoints& out);

/** True for the observation types sensorPoints() reads. */
bool isSupported(const mrpt::obs::CObservation& obs);

/** The pose as the core's transform. */
Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& pose);

}  // namespace hif::mrpt_adapter
