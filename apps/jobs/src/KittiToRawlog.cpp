// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KittiToRawlog.cpp
 * @brief  A KITTI sequence into an MRPT rawlog or the DynamicMap layout.
 */
#include "hif/jobs/KittiToRawlog.h"

#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRobotPose.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>

#include "hif/apps/Cli.h"
#include "hif/apps/FrameComment.h"
#include "hif/apps/RunFiles.h"
#include "hif/apps/Staged.h"
#include "hif/apps/WriteError.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"

namespace hif::jobs
{
namespace
{
/** The scans first..last as <dir>/pcd/NNNNNN.pcd, points in the world frame. */
void writeDynamicMap(const hif::io::KittiSequence& seq, std::size_t first, std::size_t last,
                     const std::string& dir, bool overwrite, bool show_progress)
{
    hif::apps::StagedFolder staged(hif::apps::cleanDir(dir), {"pcd"}, overwrite, "--overwrite");
    const std::string pcd_dir = staged.path() + "/pcd";
    hif::apps::makeDirs(pcd_dir);
    hif::apps::Progress progress(KittiToRawlog::kTag, "converting", last - first + 1,
                                 show_progress);
    for (std::size_t i = first; i <= last; ++i)
    {
        const hif::io::Cloud scan = seq.readScan(i);
        const Eigen::Isometry3d& T = seq.pose(i);
        hif::io::CloudWriter pcd({pcd_dir + "/" + hif::io::frameName(i) + ".pcd"});
        pcd.setViewpoint(T);
        // World points in double: a sequence in UTM coordinates keeps its millimetres (the
        // writer stores float64 where float32 would lose them).
        for (std::size_t k = 0; k < scan.size(); ++k)
        {
            const Eigen::Vector3d p = T * Eigen::Vector3d(scan.x[k], scan.y[k], scan.z[k]);
            pcd.add(p.x(), p.y(), p.z(), scan.intensity[k]);
        }
        pcd.close();
        progress.update(i - first + 1);
    }
    progress.finish();
    staged.commit();
}

}  // namespace

KittiToRawlogResult KittiToRawlog::run(std::ostream& log) const
{
    const KittiToRawlogOptions& o = options_;
    const hif::io::KittiSequence seq(o.input);
    const std::size_t n = seq.size();
    const auto max_scan = static_cast<long long>(n) - 1;
    const auto first = static_cast<std::size_t>(
        hif::apps::flagInRange(o.first.value_or(0), "--first", 0, max_scan));
    const auto last =
        o.last ? static_cast<std::size_t>(hif::apps::flagInRange(*o.last, "--last", 0, max_scan))
               : n - 1;
    if (last >= n)
        throw std::runtime_error("--last " + std::to_string(last) + " is past the last scan (" +
                                 std::to_string(n - 1) + ") of '" + seq.dir() + "'");
    if (first > last)
        throw std::runtime_error("--first " + std::to_string(first) + " is after --last " +
                                 std::to_string(last));
    const double start = o.start_time.value_or(0.0);
    if (!std::isfinite(start) || start < 0 || start > 4e9)
        throw std::runtime_error("--start-time " + std::to_string(start) +
                                 ": give seconds since 1970-01-01 UTC (0 to 4e9)");
    const long long level = o.compress_level.value_or(0);
    if (level < 0 || level > 9)
        throw std::runtime_error("--compress-level " + std::to_string(level) + " is not in 0-9");
    const std::string& out_file = o.output;
    if (o.dynamicmap)
    {
        if (o.external || o.compress_level || o.odometry || o.start_time)
            throw std::runtime_error(
                "--external, --compress-level, --odometry and --start-time apply to rawlogs, "
                "not to --dynamicmap");
        log << kTag << " sequence '" << seq.dir() << "': scans " << first << ".." << last << " of "
            << n << " into the DynamicMap layout '" << out_file << "/pcd'\n";
        hif::apps::RunFiles files;
        files.inputKittiSequence(seq.dir(), "-i");
        files.output(hif::apps::cleanDir(out_file) + "/pcd", "the pcd/ of -o", true);
        writeDynamicMap(seq, first, last, out_file, o.overwrite, o.show_progress);
        log << kTag << " done: " << (last - first + 1) << " scans\n";
        return {last - first + 1, 0, 0};
    }
    // Never over an input; written aside and renamed when complete: a failed conversion leaves
    // no partial rawlog.
    hif::apps::RunFiles files;
    files.inputKittiSequence(seq.dir(), "-i");
    files.output(out_file, "-o");
    hif::apps::StagedFile staged(out_file, o.overwrite, "-o");

    // Check every scan (and label file) before writing anything.
    std::size_t total_points = 0, labelled = 0;
    for (std::size_t i = first; i <= last; ++i)
    {
        const std::size_t pts = seq.pointCount(i);
        total_points += pts;
        // SemanticKITTI may label only part of a sequence: check the label files present.
        if (seq.hasLabels() && std::filesystem::exists(seq.labelFile(i)))
        {
            ++labelled;
            const std::size_t nl = hif::io::readLabels(seq.labelFile(i)).size();
            if (nl != pts)
                throw std::runtime_error("'" + seq.labelFile(i) + "' has " + std::to_string(nl) +
                                         " labels for " + std::to_string(pts) + " points in '" +
                                         seq.scanFile(i) + "'");
        }
    }
    log << kTag << " sequence '" << seq.dir() << "': scans " << first << ".." << last << " of " << n
        << ", " << total_points << " points"
        << ", labels present and checked for " << labelled << " of them\n"
        << kTag << " writing '" << out_file << "' ("
        << (o.external ? "points in the KITTI files" : "points inline")
        << (level > 0 ? ", gzip level " + std::to_string(level) : ", uncompressed") << ")\n";

    std::unique_ptr<mrpt::io::CStream> stream;
    if (level > 0)
    {
        auto gz = std::make_unique<mrpt::io::CFileGZOutputStream>();
        if (!gz->open(staged.path(), static_cast<int>(level)))
            throw std::runtime_error("cannot create '" + out_file + "'");
        stream = std::move(gz);
    }
    else
    {
        auto plain = std::make_unique<mrpt::io::CFileOutputStream>();
        if (!plain->open(staged.path()))
            throw std::runtime_error("cannot create '" + out_file + "'");
        stream = std::move(plain);
    }
    auto arch = mrpt::serialization::archiveFrom(*stream);
    const std::string written = "'" + out_file + "'";  // for a failed write

    hif::apps::Progress progress(kTag, "converting", last - first + 1, o.show_progress);
    for (std::size_t i = first; i <= last; ++i)
    {
        // KITTI times are seconds from the start of the sequence.
        const auto stamp = mrpt::Clock::fromDouble(start + seq.time(i));
        // The scan's number in the sequence, so that hif-clean names its predictions after it.
        auto frame = mrpt::obs::CObservationComment::Create();
        frame->sensorLabel = "KITTI_FRAME";
        frame->timestamp = stamp;
        frame->text = hif::apps::kittiFrameComment(i);
        auto pose_obs = mrpt::obs::CObservationRobotPose::Create();
        pose_obs->sensorLabel = "GROUND_TRUTH";
        pose_obs->timestamp = stamp;
        pose_obs->pose.mean = mrpt::poses::CPose3D::FromHomogeneousMatrix(seq.pose(i).matrix());
        pose_obs->pose.cov.setZero();

        auto scan = mrpt::obs::CObservationPointCloud::Create();
        scan->sensorLabel = "LIDAR";
        scan->timestamp = stamp;
        scan->sensorPose = mrpt::poses::CPose3D();  // points are in the LiDAR frame
        if (o.external)
        {
            scan->setAsExternalStorage(
                std::filesystem::absolute(seq.scanFile(i)).string(),
                mrpt::obs::CObservationPointCloud::ExternalStorageFormat::KittiBinFile);
        }
        else
        {
            auto cloud = mrpt::maps::CPointsMapXYZI::Create();
            if (!cloud->loadFromKittiVelodyneFile(seq.scanFile(i)) ||
                cloud->size() != seq.pointCount(i))
                throw std::runtime_error("error reading '" + seq.scanFile(i) + "'");
            scan->pointcloud = cloud;
        }
        hif::apps::writeOrThrow(written, [&] { arch << *frame; });
        if (o.odometry)
        {
            auto odo = mrpt::obs::CObservationOdometry::Create();
            odo->sensorLabel = "GROUND_TRUTH_ODOMETRY";
            odo->timestamp = stamp;
            odo->odometry = mrpt::poses::CPose2D(pose_obs->pose.mean);
            hif::apps::writeOrThrow(written, [&] { arch << *odo; });
        }
        hif::apps::writeOrThrow(written, [&] { arch << *pose_obs << *scan; });
        progress.update(i - first + 1);
    }
    progress.finish();
    hif::apps::writeOrThrow(
        written, [&] { stream.reset(); }, /*closing=*/true);
    staged.commit();
    log << kTag << " done: " << (last - first + 1) << " scans\n";
    return {last - first + 1, total_points, labelled};
}

}  // namespace hif::jobs
