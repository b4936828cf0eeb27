// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   IcpSlam.h
 * @brief  hif-icp-slam's work as a job: 3D LiDAR ICP-SLAM on MRPT (mrpt::slam::CICP, point to
 *         point, 6 DoF) whose map HIF keeps clean: each scan is aligned against a voxel map of
 *         the earlier scans' points that HIF classified static, then inserted into the HIF map
 *         at its estimated pose. The app is its command line; the tests run the job in process.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <utility>

namespace hif::jobs
{
/** What to track and what to write; the flags of hif-icp-slam, which the job's messages name. */
struct IcpSlamOptions
{
    std::string input;                  ///< -i: rawlog (poses optional), .simplemap, KITTI folder
    std::string output;                 ///< -o: the output folder
    std::optional<std::string> config;  ///< -c (default: the shipped icp-slam-3d.ini)
    std::string labels;                 ///< --labels (default: <input>/labels if it exists)
    bool use_hif = true;                ///< --no-hif: false
    bool overwrite = false;             ///< --overwrite
    bool show_progress = true;          ///< no --quiet
};

/** What a run tracked. */
struct IcpSlamResult
{
    std::size_t scans = 0;
    std::size_t not_aligned = 0;   ///< scans ICP could not align (kept at the guess)
    std::optional<double> rmse_m;  ///< against the input's poses, when it has them
};

/** Checks the options, the input and the config before anything is written, writes the results
 *  aside and puts them in place once complete; says what it does on `log`. Throws
 *  std::runtime_error naming the flag or the file and the problem. */
class IcpSlam
{
public:
    /** What the job's lines and its app's errors start with. */
    static constexpr const char* kTag = "[hif-icp-slam]";

    explicit IcpSlam(IcpSlamOptions options) : options_(std::move(options)) {}
    IcpSlamResult run(std::ostream& log) const;

private:
    IcpSlamOptions options_;
};

}  // namespace hif::jobs
