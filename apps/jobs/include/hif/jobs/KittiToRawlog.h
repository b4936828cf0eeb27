// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KittiToRawlog.h
 * @brief  kitti2rawlog's work as a job: a KITTI sequence (SemanticKITTI layout) into an MRPT
 *         rawlog (per scan: a frame comment, optionally the pose as odometry, the pose, the
 *         point cloud) or into the DynamicMap benchmark layout. The app is its command line;
 *         the tests run the job in process.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <utility>

namespace hif::jobs
{
/** What to convert and how; the flags of kitti2rawlog. */
struct KittiToRawlogOptions
{
    std::string input;                        ///< the sequence folder
    std::string output;                       ///< the rawlog, or with `dynamicmap` the folder
    std::optional<long long> first, last;     ///< scans first..last (default: all)
    bool external = false;                    ///< points left in the .bin files (lazy load)
    std::optional<long long> compress_level;  ///< gzip level 1-9, 0 uncompressed
    bool odometry = false;                    ///< each pose also as CObservationOdometry
    std::optional<double> start_time;         ///< seconds since 1970 added to times.txt's
    bool dynamicmap = false;                  ///< the DynamicMap layout instead of a rawlog
    bool overwrite = false;
    bool show_progress = true;
};

/** What a conversion wrote. */
struct KittiToRawlogResult
{
    std::size_t scans = 0;
    std::size_t points = 0;    ///< in the scans converted (rawlog only)
    std::size_t labelled = 0;  ///< scans whose label file was present and checked (rawlog only)
};

/** Checks everything (the flags, the sequence, every scan and label file) before writing, then
 *  writes the output aside and moves it into place when complete; says what it does on `log`.
 *  Throws std::runtime_error naming the flag or the file and the problem. */
class KittiToRawlog
{
public:
    /** What the job's lines and its app's errors start with. */
    static constexpr const char* kTag = "[kitti2rawlog]";

    explicit KittiToRawlog(KittiToRawlogOptions options) : options_(std::move(options)) {}
    KittiToRawlogResult run(std::ostream& log) const;

private:
    KittiToRawlogOptions options_;
};

}  // namespace hif::jobs
