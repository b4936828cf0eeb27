// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Config.h
 * @brief  The apps' configuration files: where the shipped ones are, and the checks done before
 *         MRPT reads one.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <cstdint>
#include <optional>
#include <string>

namespace hif::apps
{
/** `name` (e.g. "kitti.ini") in the installed share/hif/config beside the running program (any
 *  install prefix), else in the source tree's (a build tree). Throws std::runtime_error naming
 *  both places if it is in neither. */
[[nodiscard]] std::string shippedConfig(const std::string& name);

/** Throws std::runtime_error naming `file` unless it is a readable regular file (not missing,
 *  not a folder). */
void checkConfigFile(const std::string& file);

/** The most maps of one class a map list may ask for: a handful is plenty. */
constexpr long kMaxMapsPerClass = 16;

/** Checks every `<class>_count` key of `section` (how many maps of a class MRPT creates, each
 *  with its memory) before MRPT reads them: a whole number in [0, kMaxMapsPerClass]. Throws
 *  std::runtime_error naming `file`, the section and the key otherwise. */
void checkMapCounts(const mrpt::config::CConfigFileBase& config, const std::string& section,
                    const std::string& file);

/** The thread count an app gives the first CHeightIntervalMap of map list `section`: `given`
 *  (a command-line option) where set, else none where its insertion options in `config` set
 *  `threads` (that count stands), else one per hardware thread of this machine: a batch run
 *  uses the cores it has, and the map is the same for any count. */
[[nodiscard]] std::optional<uint64_t> mapThreads(const mrpt::config::CConfigFileBase& config,
                                                 const std::string& section,
                                                 std::optional<long long> given);

}  // namespace hif::apps
