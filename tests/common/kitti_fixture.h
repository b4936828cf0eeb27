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
#include <string>

namespace hif::test
{
/** The KITTI folder: $HIF_KITTI_DIR, else the one beside the repository. */
inline std::string kittiRoot()
{
    if (const char* env = std::getenv("HIF_KITTI_DIR")) return env;
    return HIF_DEFAULT_KITTI_DIR;
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
