// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   NumberedFiles.h
 * @brief  The scans of a folder: the files named by their number (NNNNNN.pcd, 42.ply), as the
 *         DynamicMap benchmark and LiDAR SLAM systems write them, or by their time.
 */
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace hif::apps
{
struct NumberedFiles
{
    /** (number, path), by number. */
    std::vector<std::pair<std::size_t, std::string>> files;
    /** The names of everything else in the folder, sorted. */
    std::vector<std::string> other;
};

/** The regular files of `folder` whose stem is a number of up to 8 digits and whose extension
 *  is one of `extensions`; without any, those whose stem is such a number after one prefix
 *  (without digits or dots) that they all share (FAST-LIO's scans_12.pcd). Anything else there
 *  (a gt_cloud.pcd, results written into the folder, files of another prefix) is listed in
 *  `other`, never read as a scan. Throws std::runtime_error naming the folder when two files
 *  have one number (000001.pcd and 1.pcd). */
[[nodiscard]] NumberedFiles numberedFiles(const std::string& folder,
                                          const std::vector<std::string>& extensions);

/** A folder's clouds named by their time: (seconds, path), in time order. */
struct TimedFiles
{
    std::vector<std::pair<double, std::string>> files;
    /** The fractions were read as nanoseconds written without their leading zeros (ROS 2's
     *  pointcloud_to_pcd), not as decimals. */
    bool nanoseconds_unpadded = false;
};

/** The regular files of `folder` with one of `extensions` whose stem is a time, after a prefix
 *  (no digits, no dots) that they all share: seconds with a fraction (1317022176.580342102.pcd,
 *  as pcl_ros's bag_to_pcd names them; ROS 2's pointcloud_to_pcd writes the nanoseconds without
 *  their leading zeros, told by fractions of different lengths, the longest of 9 digits) or
 *  nanoseconds, 19 digits (1317022176580342102.pcd). None when their prefixes differ. Throws
 *  std::runtime_error naming the folder when two files have one time. */
[[nodiscard]] TimedFiles timedFiles(const std::string& folder,
                                    const std::vector<std::string>& extensions);

/** Up to five names, and how many more: "a, b, c, d, e and 3 more". */
[[nodiscard]] std::string listNames(const std::vector<std::string>& names);

}  // namespace hif::apps
