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
        storage[0].assign(pts.getPointsBufferRef_x().begin(), pts.getPointsBufferRef_x().end());
        storage[1].assign(pts.getPointsBufferRef_y().begin(), pts.getPointsBufferRef_y().end());
        storage[2].assign(pts.getPointsBufferRef_z().begin(), pts.getPointsBufferRef_z().end());
        fromStorage();
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
        const std::size_t n = o2d->getScanSize();
        for (auto& s : storage) s.clear();
        // MRPT's convention: beam i at -aperture/2 + i * aperture / (n-1), mirrored when
        // scanning right to left is false.
        double ang = -0.5 * o2d->aperture;
        double dA = n > 1 ? o2d->aperture / static_cast<double>(n - 1) : 0.0;
        if (!o2d->rightToLeft)
        {
            ang = -ang;
            dA = -dA;
        }
        for (std::size_t i = 0; i < n; ++i, ang += dA)
        {
            if (!o2d->getScanRangeValidity(i)) continue;
            const double r = o2d->getScanRange(i);
            storage[0].push_back(static_cast<float>(r * std::cos(ang)));
            storage[1].push_back(static_cast<float>(r * std::sin(ang)));
            storage[2].push_back(0.0f);
        }
        fromStorage();
        return true;
    }
    return false;
}

}  // namespace hif::mrpt_adapter
