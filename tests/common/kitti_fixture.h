// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   kitti_fixture.h
 * @brief  Test helper: locate ../shared/data/kitti, and skip (or fail when HIF_REQUIRE_DATA=1)
 *         when it is missing. Reading sequences and scoring use hif_io (KittiSequence.h,
 *         Labels.h), the code the apps run.
 */
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "hif/io/KittiSequence.h"

namespace hif::test
{
/** The KITTI folder: $HIF_KITTI_DIR, else the one beside the repository. */
inline std::string kittiRoot()
{
    if (const char* env = std::getenv("HIF_KITTI_DIR")) return env;
    return HIF_DEFAULT_KITTI_DIR;
}

/** Makes `to` a KITTI sequence folder of the first `n` scans of the one at `from` (its scans
 *  and labels linked, calib.txt copied, poses.txt and times.txt cut to `n` lines) and returns
 *  `to`: a real clip for the tests that compare runs of the apps on it, at a fraction of the
 *  time (the sanitizer build runs them several times slower). */
inline std::string firstScans(const std::string& from, std::size_t n, const std::string& to)
{
    namespace fs = std::filesystem;
    for (const char* sub : {"velodyne", "labels"})
    {
        if (!fs::is_directory(from + "/" + sub)) continue;
        fs::create_directories(to + "/" + sub);
        for (std::size_t i = 0; i < n; ++i)
        {
            const std::string name =
                "/" + hif::io::frameName(i) + (std::string(sub) == "labels" ? ".label" : ".bin");
            fs::create_symlink(fs::absolute(from + "/" + sub + name), to + "/" + sub + name);
        }
    }
    fs::copy_file(from + "/calib.txt", to + "/calib.txt");
    for (const char* file : {"/poses.txt", "/times.txt"})
    {
        std::ifstream in(from + file);
        std::ofstream out(to + file);
        std::string line;
        for (std::size_t i = 0; i < n && std::getline(in, line); ++i) out << line << '\n';
    }
    return to;
}

inline bool dataRequired()
{
    const char* v = std::getenv("HIF_REQUIRE_DATA");
    return v && std::string(v) == "1";
}

/** Skips the test (or fails it when HIF_REQUIRE_DATA=1) when the sequence is missing. */
#define HIF_REQUIRE_KITTI_SEQUENCE(seq_dir)                                                   \
    do                                                                                        \
    {                                                                                         \
        if (!std::filesystem::is_directory(seq_dir))                                          \
        {                                                                                     \
            if (hif::test::dataRequired())                                                    \
                FAIL() << "KITTI data missing at " << (seq_dir) << " and HIF_REQUIRE_DATA=1"; \
            GTEST_SKIP() << "KITTI data not found at " << (seq_dir)                           \
                         << " (set HIF_KITTI_DIR); skipping";                                 \
        }                                                                                     \
    } while (0)

}  // namespace hif::test
