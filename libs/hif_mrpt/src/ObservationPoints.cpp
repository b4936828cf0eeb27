// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ObservationPoints.cpp
 * @brief  The points of the observations the map inserts, in their sensor frame.
 */
#include "ObservationPoints.h"

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cmath>

namespace hif::mrpt_adapter
{
Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& pose)
{
    mrpt::math::CMatrixDouble44 H;
    pose.getHomogeneousMatrix(H);
    Eigen::Isometry3d T;
    T.matrix() = H.asEigen();
    return T;
}

bool isSupported(const mrpt::obs::CObservation& obs)
{
    using namespace mrpt::obs;
    return dynamic_cast<const CObservationPointCloud*>(&obs) != nullptr ||
           dynamic_cast<const CObservation3DRangeScan*>(&obs) != nullptr ||
           dynamic_cast<const CObservation2DRangeScan*>(&obs) != nullptr ||
           dynamic_cast<const CObservationVelodyneScan*>(&obs) != nullptr;
}

bool sensorPoints(const mrpt::obs::CObservation& obs, SensorPoints& out)
{
    using namespace mrpt::obs;
    auto& storage = out.storage;
    auto fromStorage = [&]() {
        out.view = {storage[0].data(), storage[1].data(), storage[2].data(), storage[0].size()};
    };
    auto fromPoints = [&](const mrpt::maps::CPointsMap& pts)
    {
        storage[0].assign(pts.getPointsBufferRef_x().begin(), pts.getPointsBufferRef_x().end());
        storage[1].assign(pts.getPointsBufferRef_y().begin(), pts.getPointsBufferRef_y().end());
        storage[2].assign(pts.getPointsBufferRef_z().begin(), pts.getPointsBufferRef_z().end());
        fromStorage();
    };
    if (const auto* pc = dynamic_cast<const CObservationPointCloud*>(&obs))
    {
        pc->load();  // no-op unless stored externally (lazy-load)
        if (!pc->pointcloud) return false;
        const auto& m = *pc->pointcloud;
        out.view = {m.getPointsBufferRef_x().data(), m.getPointsBufferRef_y().data(),
                    m.getPointsBufferRef_z().data(), m.size()};
        out.sensor_pose = pc->sensorPose;
        return true;
    }
    if (const auto* o3d = dynamic_cast<const CObservation3DRangeScan*>(&obs))
    {
        o3d->load();
        out.sensor_pose = o3d->sensorPose;
        if (o3d->hasPoints3D)
        {
            out.view = {o3d->points3D_x.data(), o3d->points3D_y.data(), o3d->points3D_z.data(),
                        o3d->points3D_x.size()};
            return true;
        }
        if (!o3d->hasRangeImage) return false;
        CObservation3DRangeScan copy = *o3d;  // unprojectInto() is not const
        mrpt::maps::CSimplePointsMap pts;
        copy.unprojectInto(pts);  // sensor frame by default
        fromPoints(pts);
        return true;
    }
    if (const auto* velo = dynamic_cast<const CObservationVelodyneScan*>(&obs))
    {
        out.sensor_pose = velo->sensorPose;
        if (velo->point_cloud.size() == 0 && !velo->scan_packets.empty())
        {
            // Raw packets only: MRPT turns them into points (its default parameters).
            CObservationVelodyneScan copy = *velo;
            copy.generatePointCloud();
            storage[0] = std::move(copy.point_cloud.x);
            storage[1] = std::move(copy.point_cloud.y);
            storage[2] = std::move(copy.point_cloud.z);
            fromStorage();
            return true;
        }
        const auto& pc = velo->point_cloud;
        out.view = {pc.x.data(), pc.y.data(), pc.z.data(), pc.size()};
        return true;
    }
    if (const auto* o2d = dynamic_cast<const CObservation2DRangeScan*>(&obs))
    {
        out.sensor_pose = o2d->sensorPose;
        // MRPT's own conversion (its beam angles, its validity), in the sensor frame: a copy
        // at the identity, every valid range one point (and one class), none merged or added.
        CObservation2DRangeScan at_sensor = *o2d;
        at_sensor.sensorPose = mrpt::poses::CPose3D();
        mrpt::maps::CSimplePointsMap pts;
        pts.insertionOptions.minDistBetweenLaserPoints = 0;
        pts.insertionOptions.also_interpolate = false;
        pts.loadFromRangeScan(at_sensor);
        fromPoints(pts);
        return true;
    }
    return false;
}

}  // namespace hif::mrpt_adapter
