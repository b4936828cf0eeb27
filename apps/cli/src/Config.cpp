// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Config.cpp
 * @brief  The shipped configurations, installed or in the source tree; checks of a
 *         configuration before MRPT reads it.
 */
#include "hif/apps/Config.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

namespace hif::apps
{
std::string shippedConfig(const std::string& name)
{
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    std::vector<fs::path> dirs;
    if (!ec) dirs.push_back((exe.parent_path() / HIF_SHARE_FROM_BIN / "config").lexically_normal());
    dirs.push_back(fs::path(HIF_SOURCE_SHARE_DIR) / "config");
    for (const fs::path& dir : dirs)
        if (fs::exists(dir / name)) return (dir / name).string();
    std::string tried;
    for (const fs::path& dir : dirs) tried += (tried.empty() ? "'" : ", '") + dir.string() + "'";
    throw std::runtime_error("the shipped configuration " + name + " was not found in " + tried +
                             "; pass -c");
}

void checkConfigFile(const std::string& file)
{
    std::error_code ec;
    if (!fs::exists(file, ec)) throw std::runtime_error("config '" + file + "' not found");
    if (fs::is_directory(file, ec))
        throw std::runtime_error("config '" + file + "' is a folder, not an .ini file");
    if (!fs::is_regular_file(file, ec))
        throw std::runtime_error("config '" + file + "' is not a regular file (an .ini file)");
    if (!std::ifstream(file).good())
        throw std::runtime_error("config '" + file + "' cannot be read");
}

void checkMapCounts(const mrpt::config::CConfigFileBase& config, const std::string& section,
                    const std::string& file)
{
    std::vector<std::string> keys;
    config.getAllKeys(section, keys);
    const std::string suffix = "_count";
    for (const std::string& key : keys)
    {
        if (key.size() <= suffix.size() ||
            key.compare(key.size() - suffix.size(), suffix.size(), suffix) != 0)
            continue;
        const std::string text = config.read_string(section, key, "", false);
        std::size_t used = 0;
        long n = -1;
        try
        {
            n = std::stol(text, &used);
        }
        catch (const std::exception&)
        {
            used = 0;
        }
        const auto end = text.find_first_not_of(" \t", used);
        if (used == 0 || end != std::string::npos || n < 0 || n > kMaxMapsPerClass)
            throw std::runtime_error("'" + file + "', [" + section + "]: " + key + " = '" + text +
                                     "' is not a whole number in [0, " +
                                     std::to_string(kMaxMapsPerClass) + "] (how many maps of " +
                                     "that class to create)");
    }
}

std::optional<uint64_t> mapThreads(const mrpt::config::CConfigFileBase& config,
                                   const std::string& section, std::optional<long long> given)
{
    if (given) return static_cast<uint64_t>(*given);
    // MRPT reads a map's insertion options from the section named after the map list, the
    // class and the map's number among those of its class.
    if (config.keyExists(section + "_CHeightIntervalMap_00_insertOpts", "threads"))
        return std::nullopt;
    return std::max<uint64_t>(1, std::thread::hardware_concurrency());
}

}  // namespace hif::apps
