// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   NumberedFiles.h
 * @brief  The scans of a folder: the files named by their number (NNNNNN.pcd, 42.ply), as the
 *         DynamicMap benchmark and LiDAR SLAM systems write them.
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
 *  is one of `extensions`; anything else there (a gt_cloud.pcd, results written into the
 *  folder) is listed in `other`, never read as a scan. Throws std::runtime_error naming the
 *  folder when two files have one number (000001.pcd and 1.pcd). */
[[nodiscard]] NumberedFiles numberedFiles(const std::string& folder,
                                          const std::vector<std::string>& extensions);

/** Up to five names, and how many more: "a, b, c, d, e and 3 more". */
[[nodiscard]] std::string listNames(const std::vector<std::string>& names);

}  // namespace hif::apps
