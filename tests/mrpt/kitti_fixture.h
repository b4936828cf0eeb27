// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   kitti_fixture.h
 * @brief  Test helper: locate ../shared/data/kitti, read a sequence's poses in the LiDAR frame,
 *         its scans (MRPT's KITTI loader) and labels, and score predictions.
 */
#pragma once

#include <gtest/gtest.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/system/filesystem.h>

#include <Eigen/Dense>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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
        if (!mrpt::system::directoryExists(seq_dir))                                          \
        {                                                                                     \
            if (hif::test::dataRequired())                                                    \
                FAIL() << "KITTI data missing at " << (seq_dir) << " and HIF_REQUIRE_DATA=1"; \
            GTEST_SKIP() << "KITTI data not found at " << (seq_dir)                           \
                         << " (set HIF_KITTI_DIR); skipping";                                 \
        }                                                                                     \
    } while (0)

inline Eigen::Matrix4d readRow34(std::istringstream& is)
{
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) is >> T(r, c);
    return T;
}

struct KittiSequence
{
    std::string dir;
    std::vector<Eigen::Matrix4d> poses;  ///< T_world_velo(i) = inv(Tr) * P(i) * Tr

    explicit KittiSequence(std::string d) : dir(std::move(d))
    {
        std::ifstream calib(dir + "/calib.txt");
        Eigen::Matrix4d Tr = Eigen::Matrix4d::Identity();
        for (std::string line; std::getline(calib, line);)
            if (line.rfind("Tr:", 0) == 0)
            {
                std::istringstream is(line.substr(3));
                Tr = readRow34(is);
            }
        std::ifstream pf(dir + "/poses.txt");
        for (std::string line; std::getline(pf, line);)
        {
            std::istringstream is(line);
            poses.push_back(Tr.inverse() * readRow34(is) * Tr);
        }
    }

    std::string scanFile(int i) const
    {
        return dir + "/velodyne/" + mrpt::format("%06d", i) + ".bin";
    }
    std::string labelFile(int i) const
    {
        return dir + "/labels/" + mrpt::format("%06d", i) + ".label";
    }

    std::vector<uint32_t> labels(int i) const
    {
        std::ifstream f(labelFile(i), std::ios::binary);
        std::vector<uint32_t> v;
        uint32_t x;
        while (f.read(reinterpret_cast<char*>(&x), sizeof(x))) v.push_back(x & 0xffffu);
        return v;
    }
};

/** Point-level scores of the dynamic-points-removal benchmark: labels 0, 1 excluded; 252-259
 *  dynamic. */
struct Scores
{
    std::size_t static_total = 0, static_kept = 0, dynamic_total = 0, dynamic_removed = 0;
    void add(uint32_t label, bool removed)
    {
        if (label <= 1) return;
        if (label >= 252 && label <= 259)
        {
            ++dynamic_total;
            dynamic_removed += removed;
        }
        else
        {
            ++static_total;
            static_kept += !removed;
        }
    }
    double sa() const { return 100.0 * double(static_kept) / double(static_total); }
    double da() const
    {
        return dynamic_total ? 100.0 * double(dynamic_removed) / double(dynamic_total) : 100.0;
    }
};

}  // namespace hif::test
