// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ShippedConfig.cpp
 * @brief  The shipped configurations, installed or in the source tree.
 */
#include "hif/apps/ShippedConfig.h"

#include <filesystem>
#include <stdexcept>
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

}  // namespace hif::apps
