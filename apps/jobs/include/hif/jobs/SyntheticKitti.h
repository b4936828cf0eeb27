// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SyntheticKitti.h
 * @brief  hif-synthetic-kitti's work as a job: a synthetic LiDAR sequence in the SemanticKITTI
 *         layout with exact labels (a street with sloping ground, buildings, trees and parked
 *         cars; cars, people or cyclists that move), seen by a LiDAR model with ray casting. The
 *         app is its command line; the tests run the job in process.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <utility>

namespace hif::jobs
{
/** What to render; the flags of hif-synthetic-kitti, which the job's messages name. */
struct SyntheticKittiOptions
{
    std::string output;            ///< -o: the sequence folder
    long long scans = 30;          ///< -n
    long long seed = 1;            ///< --seed
    std::string scene = "street";  ///< --scene: street, walkers, radial, cyclists or traffic
    std::optional<double>
        ego_speed;         ///< --ego-speed, m/s (default: 8 street, 12 traffic, 3 the others)
    long long groups = 6;  ///< --groups (walkers, radial, cyclists, traffic)
    std::string sensor = "hdl-64e";  ///< --sensor
    bool foliage = false;    ///< --foliage: canopies, bushes and hedges that beams enter and pass
    bool roadside = false;   ///< --roadside: traffic signs, street lights and railings
    bool overwrite = false;  ///< --overwrite
    bool show_progress = true;
};

/** What was written. */
struct SyntheticKittiResult
{
    std::size_t scans = 0, points = 0, moving_points = 0;
};

/** Writes the sequence aside and puts it in place when complete; says what it wrote on `log`.
 *  Throws std::runtime_error naming the flag or the file and the problem. */
class SyntheticKitti
{
public:
    /** What the job's lines and its app's errors start with. */
    static constexpr const char* kTag = "[hif-synthetic-kitti]";

    explicit SyntheticKitti(SyntheticKittiOptions options) : options_(std::move(options)) {}
    SyntheticKittiResult run(std::ostream& log) const;

private:
    SyntheticKittiOptions options_;
};

}  // namespace hif::jobs
