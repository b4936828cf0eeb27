// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Clean.h
 * @brief  hif-clean's work as a job: the maps of an .ini (a hif::CHeightIntervalMap among them)
 *         built from a sequence (rawlog, simple map, KITTI folder, DynamicMap folder, or a
 *         folder of clouds with their poses), every point classified, and the cleaned static
 *         map, the removed points, per-scan predictions, the serialized map and summary.json
 *         written. The app is its command line; the tests run the job in process.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <utility>

namespace hif::jobs
{
/** What to clean and what to write; the flags of hif-clean, which the job's messages name. */
struct CleanOptions
{
    std::string input;  ///< -i: rawlog, .simplemap or folder
    std::string poses;  ///< --poses: a folder of clouds' trajectory (default: its poses.txt)
    /** --extrinsic: the LiDAR's pose in the frame of a folder of clouds' trajectory (7 or 12
     *  numbers, hif::io::parseExtrinsic()); empty: the trajectory is the LiDAR's. */
    std::string extrinsic;
    bool world_frame = false;  ///< --world-frame: a folder of clouds registered in the world
    std::string output;        ///< -o: the output folder
    std::optional<std::string>
        config;  ///< -c: the .ini (default: the shipped one for the mode and input)
    std::string section = "map";               ///< --section with the map list
    std::string format = "ply";                ///< --format: ply, pcd or both
    bool picture = true;                       ///< map.png (--no-png: false)
    std::optional<std::string> rawlog_out;     ///< --rawlog-out
    std::optional<long long> rawlog_compress;  ///< --rawlog-compress 0-9
    std::optional<double> voxel;               ///< --voxel: static_map at this resolution, m
    std::optional<long long> voxel_memory;     ///< --voxel-memory, MiB (default 64)
    bool classes_ply = false;                  ///< --classes-ply
    bool scan_numbers = false;                 ///< --scan-numbers
    bool scene = false;                        ///< --scene: map.3Dscene
    bool online = false;                       ///< --online
    std::optional<long long> first_frame;      ///< --first-frame
    bool overwrite = false;                    ///< --overwrite
    std::optional<long long> threads;          ///< --threads (default: .ini's, else all cores)
    bool hold_scans = false;                   ///< --hold-scans
    bool show_progress = true;                 ///< no --quiet
};

/** What a cleaning read and decided. */
struct CleanResult
{
    std::string out_dir;  ///< where the results are
    std::size_t scans = 0;
    std::size_t points_in = 0, points_kept = 0, points_removed = 0, points_invalid = 0;
};

/** Checks the options, the input and the config before anything is written, writes the
 *  results aside and puts them in place once complete (earlier results are replaced only with
 *  `overwrite`); says what it does on `log`. Throws std::runtime_error naming the flag or the
 *  file and the problem. */
class Clean
{
public:
    /** What the job's lines and its app's errors start with. */
    static constexpr const char* kTag = "[hif-clean]";

    explicit Clean(CleanOptions options) : options_(std::move(options)) {}
    CleanResult run(std::ostream& log) const;

private:
    CleanOptions options_;
};

}  // namespace hif::jobs
