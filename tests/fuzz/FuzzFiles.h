// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FuzzFiles.h
 * @brief  What the fuzz targets share: the readers under test take file names, so a target
 *         writes its input to files in a private temporary folder, split into parts.
 */
#pragma once
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace hif::fuzz
{
inline const std::filesystem::path& workDir();

inline void removeWorkDir()
{
    std::error_code ec;
    std::filesystem::remove_all(workDir(), ec);
}

/** A temporary folder for this process, made on first use and removed when the fuzzer exits
 *  normally (a crash leaves it, beside the crashing input). */
inline const std::filesystem::path& workDir()
{
    static const std::filesystem::path dir = []
    {
        auto d = std::filesystem::temp_directory_path() /
                 ("hif-fuzz-" + std::to_string(static_cast<long>(::getpid())));
        std::filesystem::create_directories(d);
        return d;
    }();
    // Registered once `dir` is made, so it runs before `dir` is destroyed.
    static const bool removed_at_exit = std::atexit(removeWorkDir) == 0;
    (void)removed_at_exit;
    return dir;
}

inline void writeFile(const std::filesystem::path& file, std::string_view bytes)
{
    std::filesystem::create_directories(file.parent_path());
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/** Splits `data` at each occurrence of `sep`, giving exactly `parts` parts (the last takes the
 *  rest; missing ones are empty), so that a seed is readable: its files one after another. */
inline std::vector<std::string_view> splitParts(const uint8_t* data, std::size_t size,
                                                std::string_view sep, std::size_t parts)
{
    std::string_view rest(reinterpret_cast<const char*>(data), size);
    std::vector<std::string_view> out;
    while (out.size() + 1 < parts)
    {
        const auto at = rest.find(sep);
        if (at == std::string_view::npos) break;
        out.push_back(rest.substr(0, at));
        rest.remove_prefix(at + sep.size());
    }
    out.push_back(rest);
    out.resize(parts);
    return out;
}
}  // namespace hif::fuzz
