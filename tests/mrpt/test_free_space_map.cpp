// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_free_space_map.cpp
 * @brief  The map's free-space test as a user of the API meets it, on real KITTI scans: online
 *         (each scan classified right after its insertion) and offline (every scan inserted,
 *         then each classified with the scans on both sides) give what their configs promise;
 *         an offline map classifying as scans come says so; and a map saved and loaded back
 *         classifies as the saved one did.
 */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/serialization/CArchive.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "hif/CHeightIntervalMap.h"
#include "hif/io/KittiSequence.h"
#include "kitti_fixture.h"
#include "map_bytes.h"

using hif::CHeightIntervalMap;

namespace
{
/** The first `n` scans of a KITTI sequence as observations, with their poses. */
struct Clip
{
    std::vector<mrpt::obs::CObservationPointCloud::Ptr> scans;
    std::vector<mrpt::poses::CPose3D> poses;

    Clip(const std::string& dir, std::size_t n)
    {
        const hif::io::KittiSequence seq(dir);
        for (std::size_t i = 0; i < n && i < seq.size(); ++i)
        {
            auto points = mrpt::maps::CPointsMapXYZI::Create();
            EXPECT_TRUE(points->loadFromKittiVelodyneFile(seq.scanFile(i))) << seq.scanFile(i);
            scans.push_back(mrpt::obs::CObservationPointCloud::Create());
            scans.back()->pointcloud = points;
            poses.push_back(mrpt::poses::CPose3D::FromHomogeneousMatrix(seq.pose(i).matrix()));
        }
    }
    [[nodiscard]] std::size_t size() const { return scans.size(); }
};

/** A CMultiMetricMap from a shipped .ini, and its HIF map. */
struct Maps
{
    mrpt::maps::CMultiMetricMap multi;
    CHeightIntervalMap::Ptr map;

    explicit Maps(const std::string& ini)
    {
        mrpt::config::CConfigFile cfg(std::string(HIF_SHARE_DIR "/config/") + ini);
        mrpt::maps::TSetOfMetricMapInitializers inits;
        inits.loadFromConfigFile(cfg, "map");
        multi.setListOfMaps(inits);
        map = multi.mapByClass<CHeightIntervalMap>();
        map->logging_enable_keep_record = true;
    }
    [[nodiscard]] std::string log() const
    {
        std::string s;
        map->getLogAsString(s);
        return s;
    }
};

std::size_t dynamicCount(const std::vector<uint8_t>& dyn)
{
    std::size_t n = 0;
    for (uint8_t d : dyn) n += d;
    return n;
}

/** Offline, from code: every scan inserted, then the scans given to the free-space test
 *  again in their order, scan k classified once scan k + w is in. */
std::vector<std::vector<uint8_t>> offlineClasses(Maps& m, const Clip& clip)
{
    for (std::size_t i = 0; i < clip.size(); ++i)
        m.multi.insertObservation(*clip.scans[i], clip.poses[i]);
    const std::size_t w = m.map->params().free_space_window;
    std::vector<std::vector<uint8_t>> classes(clip.size());
    for (std::size_t i = 0; i < clip.size() + w; ++i)
    {
        if (i < clip.size())
        {
            EXPECT_TRUE(m.map->addToFreeSpaceTest(*clip.scans[i], clip.poses[i]));
        }
        if (i >= w && i - w < clip.size())
        {
            const std::size_t k = i - w;
            const hif::ClassifyStats st =
                m.map->classify(*clip.scans[k], clip.poses[k], classes[k]);
            // Judged by the scans within w of it, itself left out.
            EXPECT_EQ(st.free_space_scans, std::min(clip.size() - 1, k + w) - (k > w ? k - w : 0));
        }
    }
    return classes;
}

/** A map serialized and read back (as map.hifmap is). */
CHeightIntervalMap reloaded(const CHeightIntervalMap& map)
{
    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << map;
    buf.Seek(0);
    auto in = mrpt::serialization::archiveFrom(buf);
    CHeightIntervalMap loaded;
    in >> loaded;
    return loaded;
}
}  // namespace

// What a SLAM system does: insert a scan, classify it. With the online config, the first scan
// is mostly kept (measured 99.7 % of KITTI 04's scan 0; it has no past to show its movers
// gone) and later ones are judged by the scans before them.
TEST(FreeSpaceMap, OnlineEachScanIsClassifiedRightAfterItsInsertion)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const Clip clip(dir, 4);
    Maps m("kitti-online.ini");
    ASSERT_TRUE(m.map->params().online);
    for (std::size_t i = 0; i < clip.size(); ++i)
    {
        m.multi.insertObservation(*clip.scans[i], clip.poses[i]);
        std::vector<uint8_t> dyn;
        const hif::ClassifyStats st = m.map->classify(*clip.scans[i], clip.poses[i], dyn);
        EXPECT_EQ(st.free_space_scans, i) << "scan " << i << ": judged by the scans before it";
        if (i == 0)
        {
            EXPECT_LT(dynamicCount(dyn), dyn.size() / 50);
        }
    }
    EXPECT_EQ(m.map->freeSpaceTest().size(), 4u);
    EXPECT_EQ(m.log(), "") << "nothing to warn of";
}

// The same with the offline config: kitti.ini's first sighting of a height is dynamic until a
// later scan confirms it (but for ground that runs on both ways along its beams), so scan 0
// classified right after its insertion comes out mostly dynamic. The map knows it is offline
// and says what to do instead.
TEST(FreeSpaceMap, AnOfflineMapClassifyingAsScansComeSaysSo)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const Clip clip(dir, 2);
    Maps m("kitti.ini");
    ASSERT_FALSE(m.map->params().online);
    m.multi.insertObservation(*clip.scans[0], clip.poses[0]);
    std::vector<uint8_t> dyn;
    m.map->classify(*clip.scans[0], clip.poses[0], dyn);
    EXPECT_GT(dynamicCount(dyn), dyn.size() * 3 / 4);
    EXPECT_NE(m.log().find("offline map (online=false) classified a scan without the scans "
                           "around it"),
              std::string::npos)
        << m.log();
    EXPECT_NE(m.log().find("kitti-online.ini"), std::string::npos);
    m.multi.insertObservation(*clip.scans[1], clip.poses[1]);
    EXPECT_NE(m.log().find("A scan was inserted after scans were classified"), std::string::npos)
        << m.log();
}

// Offline from code, and the round trip: the map saved and loaded back holds the scans its
// free-space test held, and classifies every scan as the saved one did (before, the test's
// scans were not saved, and scan 5 of 04 came out different in 90 points).
TEST(FreeSpaceMap, ASavedMapClassifiesAsTheSavedOneDid)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const Clip clip(dir, 10);
    for (const std::string ini : {"kitti.ini", "kitti-online.ini"})
    {
        SCOPED_TRACE(ini);
        Maps m(ini);
        std::vector<std::vector<uint8_t>> before;
        if (ini == "kitti.ini")
            before = offlineClasses(m, clip);
        else
            for (std::size_t i = 0; i < clip.size(); ++i)
            {
                m.multi.insertObservation(*clip.scans[i], clip.poses[i]);
                before.emplace_back();
                m.map->classify(*clip.scans[i], clip.poses[i], before.back());
            }
        EXPECT_EQ(m.log(), "");
        const CHeightIntervalMap loaded = reloaded(*m.map);
        // And through a file, as hif-clean's map.hifmap.
        const std::string file =
            ::testing::TempDir() + "/hif_" + std::to_string(getpid()) + ".hifmap";
        m.map->saveToFile(file);
        CHeightIntervalMap from_file;
        from_file.loadFromFile(file);
        std::remove(file.c_str());
        EXPECT_TRUE(from_file.grid() == m.map->grid());
        EXPECT_TRUE(from_file.freeSpaceTest() == m.map->freeSpaceTest());
        EXPECT_TRUE(loaded.freeSpaceTest() == m.map->freeSpaceTest());
        EXPECT_TRUE(loaded.grid() == m.map->grid());
        EXPECT_FALSE(loaded.freeSpaceTest().empty());
        // Offline, the test holds the whole clip (10 scans, within its 21); online, the last
        // 10 (scan 9 and the 10 before it, of which there are 9): every scan is judged again
        // as it was (online, scan 9 the last one, the others as the map judges any scan it
        // holds).
        const std::size_t k = ini == "kitti.ini" ? 5 : 9;
        std::vector<uint8_t> saved, again;
        const hif::ClassifyStats a = m.map->classify(*clip.scans[k], clip.poses[k], saved);
        const hif::ClassifyStats b = loaded.classify(*clip.scans[k], clip.poses[k], again);
        EXPECT_EQ(saved, before[k]);
        EXPECT_EQ(again, saved);
        EXPECT_EQ(a.free_space_scans, b.free_space_scans);
        EXPECT_GT(a.seen_through_points, 0u);
        EXPECT_EQ(a.seen_through_points, b.seen_through_points);
    }
}

// The second pass in two steps, as hif-clean runs it: each scan for the test made on another
// thread while the map classifies, then added in order. The classes are those of the scans
// added by their observations; a scan made for another sensor model's layout is refused.
TEST(FreeSpaceMap, ScansMadeOnAnotherThreadJudgeAsTheObservationsDo)
{
    const std::string dir = hif::test::kittiRoot() + "/sequences/04";
    HIF_REQUIRE_KITTI_SEQUENCE(dir);
    const Clip clip(dir, 10);
    Maps by_obs("kitti.ini");
    const std::vector<std::vector<uint8_t>> expected = offlineClasses(by_obs, clip);
    Maps m("kitti.ini");
    for (std::size_t i = 0; i < clip.size(); ++i)
        m.multi.insertObservation(*clip.scans[i], clip.poses[i]);
    const std::size_t w = m.map->params().free_space_window;
    hif::FreeSpaceTest::ScanMaker maker;
    std::vector<std::vector<uint8_t>> classes(clip.size());
    std::size_t next = 0;
    for (std::size_t k = 0; k < clip.size(); ++k)
    {
        for (; next < clip.size() && next <= k + w; ++next)
        {
            std::optional<hif::FreeSpaceTest::Scan> made;
            std::thread(
                [&]
                { made = m.map->makeFreeSpaceScan(*clip.scans[next], clip.poses[next], maker); })
                .join();
            ASSERT_TRUE(made);
            m.map->addToFreeSpaceTest(std::move(*made));
        }
        m.map->classify(*clip.scans[k], clip.poses[k], classes[k]);
    }
    EXPECT_EQ(classes, expected);
    EXPECT_GT(dynamicCount(classes[5]), 0u);
    EXPECT_TRUE(m.map->freeSpaceTest() == by_obs.map->freeSpaceTest());

    std::optional<hif::FreeSpaceTest::Scan> other =
        m.map->makeFreeSpaceScan(*clip.scans[0], clip.poses[0], maker);
    ASSERT_TRUE(other);
    other->layout.rows += 2;
    other->image.assign(other->layout.rows, other->layout.cols,
                        std::vector<uint16_t>(static_cast<std::size_t>(other->layout.rows) *
                                                  static_cast<std::size_t>(other->layout.cols),
                                              hif::FreeSpaceTest::kNoReturn));
    EXPECT_THROW(m.map->addToFreeSpaceTest(std::move(*other)), std::invalid_argument);
}

// The images in a saved map are read only when laid out as the map's own (which bounds what a
// corrupt file can make the reader allocate), and a file with more scans than the map's
// options keep, or an image's cells past its end, is refused with what is wrong.
TEST(FreeSpaceMap, ACorruptImageInASavedMapIsRefused)
{
    hif::Params prm;
    prm.free_space_window = 2;
    prm.sensor_from_scans = false;  // the default layout: 1800 columns
    CHeightIntervalMap map(hif::GridGeometry(), prm);
    auto points = mrpt::maps::CSimplePointsMap::Create();
    for (float a = 0; a < 6.28f; a += 0.01f)
        points->insertPoint(10 * std::cos(a), 10 * std::sin(a), -1.5f);
    mrpt::obs::CObservationPointCloud obs;
    obs.pointcloud = points;
    map.insertObservation(obs, mrpt::poses::CPose3D());
    ASSERT_EQ(map.freeSpaceTest().size(), 1u);
    const std::vector<uint8_t> bytes = hif::test::mapBytes(map);
    const hif::RangeImageLayout& l = map.grid().imageLayout();
    const int32_t layout[2] = {l.cols, l.rows};
    const auto at =
        std::search(bytes.begin(), bytes.end(), reinterpret_cast<const uint8_t*>(layout),
                    reinterpret_cast<const uint8_t*>(layout) + 8);
    ASSERT_NE(at, bytes.end());
    const auto load = hif::test::loadError;
    EXPECT_EQ(load(bytes), "");
    std::vector<uint8_t> bad = bytes;
    const int32_t huge = 7200 * 3600;
    std::memcpy(&bad[std::size_t(at - bytes.begin())], &huge, 4);
    EXPECT_NE(load(bad).find("not laid out for the map's sensor"), std::string::npos) << load(bad);
    // The scan count is the uint32 before the scan's fingerprint (8 bytes) and pose (96).
    bad = bytes;
    const std::size_t count_at = std::size_t(at - bytes.begin()) - 96 - 8 - 4;
    uint32_t count = 0;
    std::memcpy(&count, &bad[count_at], 4);
    ASSERT_EQ(count, 1u);
    count = 1000;
    std::memcpy(&bad[count_at], &count, 4);
    EXPECT_NE(load(bad).find("more than its options keep"), std::string::npos) << load(bad);
}

TEST(FreeSpaceMap, LoadFromFileNamesAFileItCannotRead)
{
    CHeightIntervalMap map;
    const std::string missing = ::testing::TempDir() + "/no_such_map.hifmap";
    try
    {
        map.loadFromFile(missing);
        ADD_FAILURE() << "a missing file loaded";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
    }
    const std::string junk = ::testing::TempDir() + "/junk_" + std::to_string(getpid()) + ".hifmap";
    std::ofstream(junk) << "not a map";
    try
    {
        map.loadFromFile(junk);
        ADD_FAILURE() << "junk loaded";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find("is not a hif map that can be read"),
                  std::string::npos)
            << e.what();
    }
    std::remove(junk.c_str());
}
