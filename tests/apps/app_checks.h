// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   app_checks.h
 * @brief  Test helpers for what the apps write: a rawlog's objects, a PLY's points by colour or by
 *         class, a PLY's vertex count; and a synthetic clip made, cleaned and scored in process.
 */
#pragma once

#include <gtest/gtest.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/serialization/CArchive.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "app_runner.h"
#include "hif/apps/TopView.h"
#include "job_runner.h"

namespace hif::test
{
using json = nlohmann::json;
using Options = hif::jobs::CleanOptions;

/** Every object of a rawlog (gzip-compressed or not), in order. */
inline std::vector<mrpt::serialization::CSerializable::Ptr> rawlogObjects(const std::string& file)
{
    mrpt::io::CFileGZInputStream in(file);
    auto arch = mrpt::serialization::archiveFrom(in);
    std::vector<mrpt::serialization::CSerializable::Ptr> objects;
    for (;;)
    {
        try
        {
            objects.push_back(arch.ReadObject());
        }
        catch (const mrpt::serialization::CExceptionEOF&)
        {
            return objects;
        }
    }
}

/** How many points of each colour (red, green, blue packed) a coloured PLY holds. */
inline std::map<uint32_t, std::size_t> coloursOf(const std::string& file)
{
    std::ifstream f(file, std::ios::binary);
    EXPECT_TRUE(f.good()) << file;
    for (std::string line; std::getline(f, line) && line != "end_header";)
    {
    }
    std::map<uint32_t, std::size_t> n;
    for (char rec[15]; f.read(rec, 15);)
        ++n[(uint32_t(uint8_t(rec[12])) << 16) | (uint32_t(uint8_t(rec[13])) << 8) |
            uint8_t(rec[14])];
    return n;
}

/** classes.ply's points (x y z intensity, float32; red green blue class, uchar) counted by
 *  (colour, class), and the sum of their intensities. */
inline std::map<std::pair<uint32_t, int>, std::size_t> classesOf(const std::string& file,
                                                                 double& intensity_sum)
{
    std::ifstream f(file, std::ios::binary);
    EXPECT_TRUE(f.good()) << file;
    std::string header;
    for (std::string line; std::getline(f, line) && line != "end_header";) header += line + "\n";
    EXPECT_NE(header.find("property float intensity\nproperty uchar red\nproperty uchar green\n"
                          "property uchar blue\nproperty uchar class\n"),
              std::string::npos)
        << header;
    std::map<std::pair<uint32_t, int>, std::size_t> n;
    intensity_sum = 0;
    for (char rec[20]; f.read(rec, 20);)
    {
        float i = 0;
        std::memcpy(&i, rec + 12, 4);
        intensity_sum += i;
        ++n[{(uint32_t(uint8_t(rec[16])) << 16) | (uint32_t(uint8_t(rec[17])) << 8) |
                 uint8_t(rec[18]),
             int(rec[19])}];
    }
    return n;
}

inline uint32_t packed(hif::apps::TopView::Outcome o)
{
    const uint8_t* c = hif::apps::TopView::kRgb[o];
    return (uint32_t(c[0]) << 16) | (uint32_t(c[1]) << 8) | c[2];
}

/** The vertex count a PLY header states. */
inline std::size_t plyVertexCount(const std::string& file)
{
    std::ifstream ply(file);
    EXPECT_TRUE(ply.good()) << file;
    for (std::string line; std::getline(ply, line) && line != "end_header";)
        if (line.rfind("element vertex ", 0) == 0) return std::stoul(line.substr(15));
    ADD_FAILURE() << file << " has no element vertex line";
    return 0;
}

/** A synthetic clip of `scene` (10 scans), converted to a rawlog in `seq`. */
inline void makeClip(const std::string& seq, const std::string& scene, double speed, long long seed,
                     bool foliage = false)
{
    auto r = synthesize(seq, 10,
                        [&](hif::jobs::SyntheticKittiOptions& o)
                        {
                            o.scene = scene;
                            o.ego_speed = speed;
                            o.seed = seed;
                            o.foliage = foliage;
                        });
    ASSERT_EQ(r.code, 0) << r.output;
    r = toRawlog(seq, seq + "/scans.rawlog");
    ASSERT_EQ(r.code, 0) << r.output;
}

/** The cleaning (in process) of `input` into `out` with what `set` changes, scored by hif-eval
 *  against `labels`: the scores' JSON. */
inline json cleanAndScoreInput(const std::string& input, const std::string& labels,
                               const std::string& out,
                               const std::function<void(Options&)>& set = {})
{
    const auto c = clean(input, out, set);
    EXPECT_EQ(c.code, 0) << c.output;
    const auto e = evaluate(labels, out + "/predictions",
                            [&](hif::jobs::EvaluateOptions& o) { o.json = out + "/scores.json"; });
    EXPECT_EQ(e.code, 0) << e.output;
    return readJson(out + "/scores.json");
}

/** cleanAndScoreInput() on the rawlog of the clip in `seq` (into seq/name). */
inline json cleanAndScore(const std::string& seq, const std::string& name,
                          const std::function<void(Options&)>& set = {})
{
    return cleanAndScoreInput(seq + "/scans.rawlog", seq + "/labels", seq + "/" + name, set);
}

/** What the options become for the paper's method, online, or without a picture. */
inline void paperConfig(Options& o) { o.config = HIF_SHARE_DIR "/config/kitti-paper.ini"; }
inline void onlineMode(Options& o) { o.online = true; }
inline void noPicture(Options& o) { o.picture = false; }

}  // namespace hif::test
