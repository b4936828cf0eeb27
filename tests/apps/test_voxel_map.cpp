// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_voxel_map.cpp
 * @brief  hif-clean --voxel: static_map at a resolution holds one point per voxel of the kept
 *         points (checked against classes.ply's kept points), the same with a small memory
 *         (run files) as with a large one, and within the memory it was given.
 */
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app_runner.h"
#include "hif/io/VoxelMerger.h"
#include "job_runner.h"

namespace fs = std::filesystem;
using hif::test::expectError;
using hif::test::readJson;
using Options = hif::jobs::CleanOptions;
using hif::test::workDir;
using json = nlohmann::json;

namespace
{
/** Not a round number: the synthetic scene's walls and ground lie at round coordinates, and a
 *  voxel face there would split a plane of points by float rounding. */
constexpr double kVoxel = 0.237;

/** A binary little-endian PLY's vertices, every property as a double, by name. */
struct Ply
{
    std::vector<std::string> names;
    std::vector<std::vector<double>> rows;

    [[nodiscard]] std::size_t column(const std::string& name) const
    {
        for (std::size_t k = 0; k < names.size(); ++k)
            if (names[k] == name) return k;
        ADD_FAILURE() << "no property " << name;
        return 0;
    }
};

template <typename T>
double scalar(const char* bytes)
{
    T v;
    std::memcpy(&v, bytes, sizeof v);
    return static_cast<double>(v);
}

Ply readPly(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    EXPECT_TRUE(in.good()) << file;
    Ply ply;
    std::vector<std::string> types;
    std::size_t count = 0;
    for (std::string line; std::getline(in, line) && line != "end_header";)
    {
        std::istringstream s(line);
        std::string word, type, name;
        s >> word;
        if (word == "element") s >> name >> count;
        if (word == "property")
        {
            s >> type >> name;
            types.push_back(type);
            ply.names.push_back(name);
        }
    }
    for (std::size_t i = 0; i < count && in; ++i)
    {
        std::vector<double> row;
        for (const std::string& t : types)
        {
            char b[8];
            const std::size_t n = t == "double" ? 8 : (t == "uchar" ? 1 : 4);
            in.read(b, static_cast<std::streamsize>(n));
            row.push_back(t == "double"  ? scalar<double>(b)
                          : t == "float" ? scalar<float>(b)
                          : t == "uint"  ? scalar<uint32_t>(b)
                                         : scalar<uint8_t>(b));
        }
        ply.rows.push_back(std::move(row));
    }
    EXPECT_EQ(ply.rows.size(), count) << file << " is truncated";
    return ply;
}
}  // namespace

TEST(VoxelMap, HoldsOnePointPerVoxelOfTheKeptPointsWithinItsMemory)
{
    const auto dir = workDir("voxel_map");
    const std::string d = dir.path();
    auto r = hif::test::synthesize(d + "/seq", 16);
    ASSERT_EQ(r.code, 0) << r.output;
    // 1 MiB for the voxels: most of the map waits in run files.
    r = hif::test::clean(d + "/seq", d + "/small",
                         [](Options& o)
                         {
                             o.picture = false;
                             o.classes_ply = true;
                             o.voxel = 0.237;
                             o.voxel_memory = 1;
                         });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_NE(r.output.find("voxels of 0.237 m from the"), std::string::npos) << r.output;
    const json s = readJson(d + "/small/summary.json");
    const json& v = s["voxel_map"];
    EXPECT_EQ(v["voxel_m"], kVoxel);
    EXPECT_EQ(v["points_merged"], s["points_kept"]);
    EXPECT_LE(v["voxels_in_memory_max"].get<std::size_t>(),
              hif::io::VoxelMerger::voxelsWithin(std::size_t{1} << 20));
    EXPECT_GT(v["run_files"].get<std::size_t>(), 0u);
    // The run files are gone.
    for (const auto& e : fs::directory_iterator(d + "/small"))
        EXPECT_EQ(e.path().string().find(".part"), std::string::npos) << e.path();

    // static_map: x y z intensity points, one point per voxel, every kept point merged.
    const Ply map = readPly(d + "/small/static_map.ply");
    ASSERT_EQ(map.names, (std::vector<std::string>{"x", "y", "z", "intensity", "points"}));
    EXPECT_EQ(map.rows.size(), v["points"].get<std::size_t>());
    std::size_t merged = 0, shared = 0;
    std::map<std::array<int64_t, 3>, std::array<double, 4>> got;
    for (const auto& p : map.rows)
    {
        merged += static_cast<std::size_t>(p[4]);
        const std::array<int64_t, 3> key{static_cast<int64_t>(std::floor(p[0] / kVoxel)),
                                         static_cast<int64_t>(std::floor(p[1] / kVoxel)),
                                         static_cast<int64_t>(std::floor(p[2] / kVoxel))};
        // A centroid written as float32 may round across its voxel's face: rarely.
        shared += !got.emplace(key, std::array<double, 4>{p[0], p[1], p[2], p[4]}).second;
    }
    EXPECT_LE(double(shared), 1e-4 * double(map.rows.size()));
    EXPECT_EQ(merged, s["points_kept"].get<std::size_t>());
    EXPECT_GT(merged, 10 * map.rows.size());

    // The reference: classes.ply's kept points, merged in a std::map. Its coordinates are
    // float32, so a point a rounding away from a voxel's face may fall on the other side: a
    // handful of points in a million.
    const Ply classes = readPly(d + "/small/classes.ply");
    const std::size_t cls = classes.column("class");
    std::map<std::array<int64_t, 3>, std::array<double, 4>> want;
    for (const auto& p : classes.rows)
        if (p[cls] == 0)
        {
            auto& w = want[{static_cast<int64_t>(std::floor(p[0] / kVoxel)),
                            static_cast<int64_t>(std::floor(p[1] / kVoxel)),
                            static_cast<int64_t>(std::floor(p[2] / kVoxel))}];
            for (int a = 0; a < 3; ++a) w[a] += p[a];
            w[3] += 1;
        }
    std::size_t differ = 0;
    for (const auto& [key, w] : want)
    {
        const auto it = got.find(key);
        if (it == got.end() || it->second[3] != w[3])
        {
            ++differ;
            continue;
        }
        for (int a = 0; a < 3; ++a) ASSERT_NEAR(it->second[a], w[a] / w[3], 1e-4);
    }
    EXPECT_LE(double(differ), 1e-4 * double(want.size())) << differ << " of " << want.size();
    EXPECT_LE(std::abs(double(want.size()) - double(got.size())), 1e-4 * double(want.size()));

    // With the default memory: no run file, the same map.
    r = hif::test::clean(d + "/seq", d + "/large",
                         [](Options& o)
                         {
                             o.picture = false;
                             o.voxel = 0.237;
                         });
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(readJson(d + "/large/summary.json")["voxel_map"]["run_files"], 0);
    const Ply large = readPly(d + "/large/static_map.ply");
    ASSERT_EQ(large.rows.size(), map.rows.size());
    for (std::size_t k = 0; k < large.rows.size(); ++k)
        for (std::size_t c = 0; c < 5; ++c)
            ASSERT_NEAR(large.rows[k][c], map.rows[k][c], 1e-4) << "point " << k;

    expectError(hif::test::clean(d + "/seq", d + "/bad", [](Options& o) { o.voxel = 0; }),
                "--voxel 0");
    expectError(hif::test::clean(d + "/seq", d + "/bad", [](Options& o) { o.voxel_memory = 8; }),
                "--voxel-memory goes with --voxel");
}
