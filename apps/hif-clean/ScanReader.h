// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanReader.h
 * @brief  hif-clean's inputs, read one scan at a time: an MRPT rawlog (observations with a
 *         CObservationRobotPose before each scan, as kitti2rawlog writes), a .simplemap, or a
 *         DynamicMap benchmark folder (pcd/NNNNNN.pcd in the world frame, sensor pose in
 *         VIEWPOINT).
 */
#pragma once

#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/poses/CPose3D.h>

#include <memory>
#include <string>
#include <vector>

namespace mrpt::io
{
class CFileGZInputStream;
}

namespace hif::apps
{
/** One scan: the observation and the robot pose it was taken at. */
struct Scan
{
    mrpt::obs::CObservation::Ptr obs;
    mrpt::poses::CPose3D robot_pose;
};

class ScanReader
{
public:
    enum class Kind
    {
        Rawlog,
        SimpleMap,
        DynamicMapFolder
    };

    /** Opens `path`: a folder with pcd/ is a DynamicMap folder, a *.simplemap file a simple
     *  map, anything else a rawlog (plain or gzip). Throws std::runtime_error naming it. */
    explicit ScanReader(const std::string& path);
    ~ScanReader();

    [[nodiscard]] Kind kind() const { return kind_; }
    /** Number of scans when known before reading (simplemap, DynamicMap), else 0. */
    [[nodiscard]] std::size_t knownSize() const;
    /** Next scan; false at the end. Throws std::runtime_error on a scan without a pose or on
     *  a corrupt file, naming the file and the scan. */
    bool next(Scan& out);
    /** Starts again from the first scan. */
    void rewind();
    /** Objects of the rawlog that were neither poses nor scans (skipped). */
    [[nodiscard]] std::size_t skippedObjects() const { return skipped_; }

private:
    void openRawlog();
    std::string path_;
    Kind kind_;
    std::unique_ptr<mrpt::io::CFileGZInputStream> in_;
    mrpt::maps::CSimpleMap simplemap_;
    std::vector<std::string> pcd_files_;
    std::size_t pos_ = 0;                                // next simplemap entry / pcd file
    std::vector<mrpt::obs::CObservation::Ptr> pending_;  // rest of a sensory frame
    mrpt::poses::CPose3D pending_pose_;
    bool have_pose_ = false;
    mrpt::poses::CPose3D pose_;
    std::size_t scans_read_ = 0;
    std::size_t skipped_ = 0;
};

/** Whether hif-clean can insert and classify this observation type. */
[[nodiscard]] bool isScan(const mrpt::obs::CObservation& obs);

}  // namespace hif::apps
