// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanReader.cpp
 * @brief  Rawlog / simplemap / DynamicMap folder reading for hif-clean.
 */
#include "ScanReader.h"

#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "hif/apps/CloudFiles.h"

namespace fs = std::filesystem;

namespace hif::apps
{
bool isScan(const mrpt::obs::CObservation& obs)
{
    using namespace mrpt::obs;
    return IS_CLASS(obs, CObservationPointCloud) || IS_CLASS(obs, CObservation3DRangeScan) ||
           IS_CLASS(obs, CObservation2DRangeScan);
}

ScanReader::ScanReader(const std::string& path) : path_(path)
{
    if (fs::is_directory(path))
    {
        kind_ = Kind::DynamicMapFolder;
        const fs::path pcd = fs::path(path) / "pcd";
        if (!fs::is_directory(pcd))
            throw std::runtime_error("'" + path +
                                     "' is a folder without pcd/: not a DynamicMap benchmark "
                                     "folder (hif-clean reads a rawlog, a .simplemap, or a "
                                     "folder with pcd/NNNNNN.pcd)");
        for (const auto& e : fs::directory_iterator(pcd))
            if (e.path().extension() == ".pcd") pcd_files_.push_back(e.path().string());
        std::sort(pcd_files_.begin(), pcd_files_.end());
        if (pcd_files_.empty()) throw std::runtime_error("'" + pcd.string() + "' has no .pcd");
        return;
    }
    if (!fs::exists(path)) throw std::runtime_error("input '" + path + "' does not exist");
    if (fs::path(path).extension() == ".simplemap")
    {
        kind_ = Kind::SimpleMap;
        if (!simplemap_.loadFromFile(path))
            throw std::runtime_error("cannot read the simple map '" + path + "'");
        return;
    }
    kind_ = Kind::Rawlog;
    openRawlog();
}

ScanReader::~ScanReader() = default;

void ScanReader::openRawlog()
{
    in_ = std::make_unique<mrpt::io::CFileGZInputStream>();
    if (!in_->open(path_)) throw std::runtime_error("cannot open rawlog '" + path_ + "'");
}

std::size_t ScanReader::knownSize() const
{
    switch (kind_)
    {
        case Kind::SimpleMap:
            return simplemap_.size();
        case Kind::DynamicMapFolder:
            return pcd_files_.size();
        default:
            return 0;
    }
}

void ScanReader::rewind()
{
    pos_ = 0;
    pending_.clear();
    have_pose_ = false;
    scans_read_ = 0;
    skipped_ = 0;
    if (kind_ == Kind::Rawlog) openRawlog();
}

bool ScanReader::next(Scan& out)
{
    using namespace mrpt::obs;
    // Rest of a sensory frame (simplemap entry or rawlog CSensoryFrame) first.
    while (!pending_.empty())
    {
        auto obs = pending_.front();
        pending_.erase(pending_.begin());
        if (obs && isScan(*obs))
        {
            out = {obs, pending_pose_};
            ++scans_read_;
            return true;
        }
        if (obs && IS_CLASS(*obs, CObservationRobotPose))
        {
            pose_ = dynamic_cast<const CObservationRobotPose&>(*obs).pose.mean;
            have_pose_ = true;
            pending_pose_ = pose_;
        }
    }
    switch (kind_)
    {
        case Kind::SimpleMap:
        {
            if (pos_ >= simplemap_.size()) return false;
            const auto& [pose_pdf, sf] = simplemap_.get(pos_++);
            if (!pose_pdf || !sf)
                throw std::runtime_error("simple map '" + path_ + "': entry " +
                                         std::to_string(pos_ - 1) + " has no pose or no frame");
            pending_pose_ = pose_pdf->getMeanVal();
            pending_.assign(sf->begin(), sf->end());
            return next(out);
        }
        case Kind::DynamicMapFolder:
        {
            if (pos_ >= pcd_files_.size()) return false;
            const PcdCloud pcd = readPcd(pcd_files_[pos_++]);
            // The benchmark's clouds are in the world frame; the map takes sensor-frame points
            // and the sensor pose (VIEWPOINT), so bring them back to the sensor frame.
            const Eigen::Isometry3d inv = pcd.viewpoint.inverse();
            auto cloud = mrpt::maps::CPointsMapXYZI::Create();
            cloud->resize(pcd.x.size());
            for (std::size_t i = 0; i < pcd.x.size(); ++i)
            {
                const Eigen::Vector3d p = inv * Eigen::Vector3d(pcd.x[i], pcd.y[i], pcd.z[i]);
                cloud->setPointFast(i, static_cast<float>(p.x()), static_cast<float>(p.y()),
                                    static_cast<float>(p.z()));
                cloud->setPointIntensity(i, pcd.intensity[i]);
            }
            auto obs = CObservationPointCloud::Create();
            obs->sensorLabel = "LIDAR";
            obs->pointcloud = cloud;
            out.obs = obs;
            out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(pcd.viewpoint.matrix());
            ++scans_read_;
            return true;
        }
        case Kind::Rawlog:
        {
            auto arch = mrpt::serialization::archiveFrom(*in_);
            for (;;)
            {
                mrpt::serialization::CSerializable::Ptr obj;
                try
                {
                    obj = arch.ReadObject();
                }
                catch (const mrpt::serialization::CExceptionEOF&)
                {
                    return false;
                }
                catch (const std::exception& e)
                {
                    throw std::runtime_error("rawlog '" + path_ +
                                             "' is corrupt or truncated after " +
                                             std::to_string(scans_read_) +
                                             " scans: " + std::string(e.what()).substr(0, 300));
                }
                if (auto rp = std::dynamic_pointer_cast<CObservationRobotPose>(obj))
                {
                    pose_ = rp->pose.mean;
                    have_pose_ = true;
                    continue;
                }
                if (auto sf = std::dynamic_pointer_cast<CSensoryFrame>(obj))
                {
                    pending_pose_ = pose_;
                    pending_.assign(sf->begin(), sf->end());
                    // A pose inside the frame updates pending_pose_ as it is met.
                    const bool any_scan =
                        std::any_of(pending_.begin(), pending_.end(),
                                    [](const auto& o) { return o && isScan(*o); });
                    const bool any_pose = std::any_of(
                        pending_.begin(), pending_.end(),
                        [](const auto& o) { return o && IS_CLASS(*o, CObservationRobotPose); });
                    if (any_scan && !have_pose_ && !any_pose)
                        throw std::runtime_error(
                            "rawlog '" + path_ + "': scan " + std::to_string(scans_read_) +
                            " has no pose before it (hif-clean needs a CObservationRobotPose "
                            "before each scan, as kitti2rawlog writes, or a .simplemap)");
                    have_pose_ = false;
                    return next(out);
                }
                auto obs = std::dynamic_pointer_cast<CObservation>(obj);
                if (!obs || !isScan(*obs))
                {
                    ++skipped_;
                    continue;
                }
                if (!have_pose_)
                    throw std::runtime_error(
                        "rawlog '" + path_ + "': scan " + std::to_string(scans_read_) +
                        " has no pose before it (hif-clean needs a CObservationRobotPose before "
                        "each scan, as kitti2rawlog writes, or a .simplemap)");
                out = {obs, pose_};
                have_pose_ = false;  // every scan needs its own pose: never reuse a stale one
                ++scans_read_;
                return true;
            }
        }
    }
    return false;
}

}  // namespace hif::apps
