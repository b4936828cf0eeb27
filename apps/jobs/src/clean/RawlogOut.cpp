// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RawlogOut.cpp
 * @brief  The cleaned rawlog.
 */
#include "RawlogOut.h"

#include <mrpt/maps/CPointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "hif/apps/FrameComment.h"
#include "hif/apps/WriteError.h"

namespace
{
/** The observation without its dynamic points, as a new object. */
mrpt::obs::CObservation::Ptr withoutDynamic(const mrpt::obs::CObservation& obs,
                                            const std::vector<uint8_t>& dyn)
{
    using namespace mrpt::obs;
    const auto sizeError = [&](std::size_t n)
    {
        return std::logic_error("--rawlog-out: " + std::to_string(dyn.size()) +
                                " classes for an observation of " + std::to_string(n) + " points");
    };
    if (const auto* pc = dynamic_cast<const CObservationPointCloud*>(&obs))
    {
        auto copy = CObservationPointCloud::Create(*pc);
        auto points = std::dynamic_pointer_cast<mrpt::maps::CPointsMap>(
            pc->pointcloud->duplicateGetSmartPtr());
        if (points->size() != dyn.size()) throw sizeError(points->size());
        points->applyDeletionMask(std::vector<bool>(dyn.begin(), dyn.end()));
        copy->pointcloud = points;
        // Its own points from here on (written inline), never the input's external file.
        copy->overrideExternalStorageFormatFlag(
            CObservationPointCloud::ExternalStorageFormat::None);
        return copy;
    }
    if (const auto* o3d = dynamic_cast<const CObservation3DRangeScan*>(&obs))
    {
        auto copy = CObservation3DRangeScan::Create(*o3d);
        if (!copy->hasPoints3D) copy->unprojectInto(*copy);  // the points the map classified
        if (copy->points3D_x.size() != dyn.size()) throw sizeError(copy->points3D_x.size());
        copy->resizePoints3DVectors(dyn.size());  // pixel indices too, if there were none
        std::size_t k = 0;
        for (std::size_t i = 0; i < dyn.size(); ++i)
            if (!dyn[i])
            {
                copy->points3D_x[k] = copy->points3D_x[i];
                copy->points3D_y[k] = copy->points3D_y[i];
                copy->points3D_z[k] = copy->points3D_z[i];
                copy->points3D_idxs_x[k] = copy->points3D_idxs_x[i];
                copy->points3D_idxs_y[k] = copy->points3D_idxs_y[i];
                ++k;
            }
        copy->resizePoints3DVectors(k);
        copy->hasPoints3D = true;
        copy->hasRangeImage = false;  // it would bring the dynamic points back
        return copy;
    }
    if (const auto* velo = dynamic_cast<const CObservationVelodyneScan*>(&obs))
    {
        auto copy = CObservationVelodyneScan::Create(*velo);
        if (copy->point_cloud.size() == 0) copy->generatePointCloud();  // as the map did
        auto& pc = copy->point_cloud;
        if (pc.size() != dyn.size()) throw sizeError(pc.size());
        const auto keep = [&dyn](auto& v)
        {
            if (v.size() != dyn.size()) return v.clear();  // not filled by this source
            std::size_t k = 0;
            for (std::size_t i = 0; i < dyn.size(); ++i)
                if (!dyn[i]) v[k++] = v[i];
            v.resize(k);
        };
        keep(pc.x);
        keep(pc.y);
        keep(pc.z);
        keep(pc.intensity);
        keep(pc.timestamp);
        keep(pc.azimuth);
        keep(pc.laser_id);
        pc.pointsForLaserID.clear();  // indices into the points as they were
        copy->scan_packets.clear();   // they would bring the dynamic points back
        return copy;
    }
    if (const auto* o2d = dynamic_cast<const CObservation2DRangeScan*>(&obs))
    {
        auto copy = CObservation2DRangeScan::Create(*o2d);
        std::size_t k = 0;  // the valid ranges are the points, in order
        for (std::size_t i = 0; i < copy->getScanSize(); ++i)
        {
            if (!copy->getScanRangeValidity(i)) continue;
            if (k >= dyn.size()) throw sizeError(k + 1);
            if (dyn[k++]) copy->setScanRangeValidity(i, false);
        }
        if (k != dyn.size()) throw sizeError(k);
        return copy;
    }
    throw std::logic_error(std::string("--rawlog-out: unsupported observation ") +
                           obs.GetRuntimeClass()->className);
}
}  // namespace

RawlogOut::RawlogOut(const std::string& file, int level, std::string name) : name_(std::move(name))
{
    if (!out_.open(file, level))
        throw std::runtime_error("--rawlog-out '" + name_ +
                                 "' cannot be created: " + std::strerror(errno));
}

void RawlogOut::write(const hif::apps::Scan& scan, const std::vector<uint8_t>& dynamic)
{
    auto arch = mrpt::serialization::archiveFrom(out_);
    auto stamp = scan.obs->timestamp;
    if (stamp == INVALID_TIMESTAMP)
    {
        stamp = mrpt::Clock::fromDouble(double(scan.frame.value_or(scans)));
        ++untimed;
    }
    if (scan.frame)
    {
        auto c = mrpt::obs::CObservationComment::Create();
        c->sensorLabel = "KITTI_FRAME";
        c->timestamp = stamp;
        c->text = hif::apps::kittiFrameComment(*scan.frame);
        hif::apps::writeOrThrow(what(), [&] { arch << *c; });
    }
    if (scan.has_pose)
    {
        auto p = mrpt::obs::CObservationRobotPose::Create();
        p->sensorLabel = "GROUND_TRUTH";
        p->timestamp = stamp;
        p->pose.mean = scan.robot_pose;
        p->pose.cov.setZero();
        hif::apps::writeOrThrow(what(), [&] { arch << *p; });
    }
    const auto clean = withoutDynamic(*scan.obs, dynamic);
    clean->timestamp = stamp;
    hif::apps::writeOrThrow(what(), [&] { arch << *clean; });
    for (const uint8_t d : dynamic) points_dropped += d;
    ++scans;
}

void RawlogOut::close()
{
    hif::apps::writeOrThrow(
        what(), [&] { out_.close(); }, /*closing=*/true);
}
