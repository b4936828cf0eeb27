// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RawlogOut.h
 * @brief  hif-clean --rawlog-out: the scans again, as an MRPT rawlog, without their dynamic
 *         points, for MRPT's own tools (rawlog-edit, RawLogViewer, icp-slam).
 */
#pragma once

#include <mrpt/io/CFileGZOutputStream.h>

#include <cstdint>
#include <string>
#include <vector>

#include "hif/apps/ScanSource.h"

/** Writes, per scan (observations format): its "kitti frame N" comment when it has a number, a
 *  CObservationRobotPose (sensor label GROUND_TRUTH) when it has a pose, and a copy of the
 *  observation without the points classified dynamic: a point cloud loses them, a 3D range
 *  scan keeps only its static points (as points, without its range image), a 2D scan marks
 *  their ranges invalid. Each gets the scan's time; MRPT's tools need one, so a scan without
 *  (a DynamicMap folder, clouds whose poses have no times) gets its number in seconds (counted
 *  in `untimed`). */
class RawlogOut
{
public:
    /** Creates `file` (gzip level `level`, 0 for none), the rawlog the user named `name`;
     *  throws naming it on failure, here or when writing. */
    RawlogOut(const std::string& file, int level, std::string name);
    /** `dynamic` has one entry per point of the scan, as the map classified it. */
    void write(const hif::apps::Scan& scan, const std::vector<uint8_t>& dynamic);
    void close();

    std::size_t scans = 0, points_dropped = 0;
    std::size_t untimed = 0;  ///< scans written with their number for a time

private:
    /** How a failed write names the rawlog. */
    [[nodiscard]] std::string what() const { return "--rawlog-out '" + name_ + "'"; }

    std::string name_;
    mrpt::io::CFileGZOutputStream out_;
};
