// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Summary.h
 * @brief  hif-clean's summary.json and its closing report on the console.
 */
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "Outputs.h"
#include "PoseCheck.h"

/** Where the map's sensor model came from and which later scans contradicted it. */
struct SensorReport
{
    std::optional<std::size_t> estimated_from_scan;  ///< none: given, or never estimated
    std::size_t checks = 0;                          ///< scans checked against it
    std::vector<std::string> contradictions;         ///< "scan k: why"
};

struct SummaryInfo
{
    std::string input, config;
    /** The trajectory file of a folder of clouds or a rawlog without poses (empty for other
     *  inputs), the LiDAR's extrinsic in it (--extrinsic) and whether the clouds were in the
     *  world frame (--world-frame). */
    std::string trajectory;
    std::optional<Eigen::Isometry3d> extrinsic;
    bool world_frame = false;
    bool online = false;
    bool held_scans = false;
    std::size_t skipped_objects = 0;
    /** Scans left out for want of a pose (a rawlog's, outside its trajectory). */
    std::size_t scans_left_out = 0;
    std::optional<hif::apps::TopView::Picture> picture;  ///< map.png, if drawn
    SensorReport sensor;
    const hif::apps::PoseCheck* poses = nullptr;  ///< the check of the poses, if run
    bool poses_doubted = false;                   ///< it warned
};

/** summary.json: counts, map size, timings and every parameter of the map. */
void writeSummary(const std::string& file, const SummaryInfo& info,
                  const hif::CHeightIntervalMap& map, const Outputs& out, const Timings& t);

/** The run's last lines: counts, map, times, and what was written (`extra`: the files asked
 *  for besides the usual ones, such as classes.ply). */
void printReport(std::ostream& log, const std::string& tag, const std::string& out_dir,
                 const std::string& format, const std::string& dm_output, bool online,
                 const hif::CHeightIntervalMap& map, const Outputs& out, const Timings& t,
                 const std::vector<std::string>& extra);
