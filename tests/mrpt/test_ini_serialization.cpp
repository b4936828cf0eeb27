// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_ini_serialization.cpp
 * @brief  Creation from .ini through CMultiMetricMap, options round trip, serialization round
 *         trip through MRPT's class factory, and rejection of bad input.
 */
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/rtti/CObject.h>
#include <mrpt/serialization/CArchive.h>
#include <sys/resource.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "field_helpers.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/IniSection.h"
#include "map_bytes.h"
#include "work_dir.h"

using hif::CHeightIntervalMap;

namespace
{
const char* kIni = R"(
[map]
CHeightIntervalMap_count=1

[map_CHeightIntervalMap_00_creationOpts]
pillar_size=0.75
origin_x=-3.5
origin_y=2.25
height_resolution=0.04

[map_CHeightIntervalMap_00_insertOpts]
merge_gap=0.3
interval_padding=0.08
alpha=0.7
beta=0.35
p_min=0.12
p_max=0.88
p_empty_init=0.45
low_height_preservation=false
high_height_preservation=false
unseen_height_prior=false
beam_spacing_deg=0.3
static_threshold=0.55
max_intervals_per_pillar=17
threads=2
)";

mrpt::maps::TSetOfMetricMapInitializers initializersFrom(const std::string& ini)
{
    mrpt::config::CConfigFileMemory cfg(ini);
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, "map");
    return inits;
}

void insertRandomScans(CHeightIntervalMap& map, int scans)
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> xy(-6, 6), z(-0.5, 3);
    for (int s = 0; s < scans; ++s)
    {
        auto obs = mrpt::obs::CObservationPointCloud::Create();
        auto pts = mrpt::maps::CSimplePointsMap::Create();
        for (int i = 0; i < 500; ++i) pts->insertPoint(xy(rng), xy(rng), z(rng));
        obs->pointcloud = pts;
        ASSERT_TRUE(
            map.insertObservation(*obs, mrpt::poses::CPose3D(0.3 * s, 0, 0, 0.1 * s, 0, 0)));
    }
}
}  // namespace

TEST(CHeightIntervalMapIni, CreatedThroughCMultiMetricMapWithEveryOption)
{
    mrpt::maps::CMultiMetricMap multi(initializersFrom(kIni));
    ASSERT_EQ(multi.maps.size(), 1u);
    ASSERT_TRUE(IS_CLASS(*multi.maps[0], CHeightIntervalMap));
    const auto map = multi.mapByClass<CHeightIntervalMap>();
    ASSERT_TRUE(map);
    const hif::GridGeometry& g = map->geometry();
    EXPECT_DOUBLE_EQ(g.pillar_size, 0.75);
    EXPECT_DOUBLE_EQ(g.origin_x, -3.5);
    EXPECT_DOUBLE_EQ(g.origin_y, 2.25);
    EXPECT_DOUBLE_EQ(g.height_resolution, 0.04);
    const hif::Params p = map->params();
    EXPECT_DOUBLE_EQ(p.merge_gap, 0.3);
    EXPECT_DOUBLE_EQ(p.interval_padding, 0.08);
    EXPECT_DOUBLE_EQ(p.alpha, 0.7);
    EXPECT_DOUBLE_EQ(p.beta, 0.35);
    EXPECT_DOUBLE_EQ(p.p_min, 0.12);
    EXPECT_DOUBLE_EQ(p.p_max, 0.88);
    EXPECT_DOUBLE_EQ(p.p_empty_init, 0.45);
    EXPECT_FALSE(p.low_height_preservation);
    EXPECT_FALSE(p.high_height_preservation);
    EXPECT_FALSE(p.unseen_height_prior);
    EXPECT_DOUBLE_EQ(p.beam_spacing_deg, 0.3);
    EXPECT_DOUBLE_EQ(p.static_threshold, 0.55);
    EXPECT_EQ(p.max_intervals_per_pillar, 17u);
    EXPECT_EQ(map->grid().threads(), 2u);

    // The multi-map forwards observations to it.
    auto obs = mrpt::obs::CObservationPointCloud::Create();
    auto pts = mrpt::maps::CSimplePointsMap::Create();
    pts->insertPoint(1.0f, 1.0f, 0.0f);
    obs->pointcloud = pts;
    EXPECT_TRUE(multi.insertObservation(*obs));
    EXPECT_EQ(map->pillarCount(), 1u);
}

// Every option, set away from its default through the field table (so an option added later
// is covered without editing this test), survives save then load, in memory and as text.
TEST(CHeightIntervalMapIni, OptionsSaveLoadRoundTrip)
{
    CHeightIntervalMap::TInsertionOptions a;
    static_cast<hif::Params&>(a) = hif::test::everyFieldChanged<hif::Params>();
    a.merge_gap = 0.1234567890123;  // more digits than "%f" keeps
    a.beam_spacing_deg = 0.123456789012345;
    a.threads = 3;
    const hif::Params defaults;
    hif::forEachField<hif::Params>([&](const hif::Field<hif::Params>& f, auto member)
                                   { ASSERT_NE(a.*member, defaults.*member) << f.name; });
    mrpt::config::CConfigFileMemory cfg;
    a.saveToConfigFile(cfg, "opts");
    CHeightIntervalMap::TInsertionOptions b;
    b.loadFromConfigFile(cfg, "opts");
    // Through text too, as when the .ini is written to disk and read again.
    CHeightIntervalMap::TInsertionOptions b_text;
    b_text.loadFromConfigFile(mrpt::config::CConfigFileMemory(cfg.getContent()), "opts");
    const hif::Params& pa = a;
    EXPECT_EQ(hif::test::differingFields<hif::Params>(pa, b), "");
    EXPECT_EQ(hif::test::differingFields<hif::Params>(pa, b_text), "");
    EXPECT_EQ(b.threads, a.threads);
    EXPECT_EQ(b_text.threads, a.threads);
}

namespace
{
/** kIni with `from` replaced by `to` must be rejected, naming `field` and `section`. */
void expectRejected(const std::string& from, const std::string& to, const std::string& field,
                    const std::string& section)
{
    std::string ini = kIni;
    ini.replace(ini.find(from), from.size(), to);
    try
    {
        initializersFrom(ini);
        ADD_FAILURE() << to << " accepted";
    }
    catch (const std::exception& e)
    {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(field), std::string::npos) << msg;
        EXPECT_NE(msg.find(section), std::string::npos) << msg;
    }
}
}  // namespace

TEST(CHeightIntervalMapIni, BadValuesAreRejectedWithSectionAndField)
{
    expectRejected("alpha=0.7", "alpha=0.3", "alpha", "map_CHeightIntervalMap_00_insertOpts");
    expectRejected("pillar_size=0.75", "pillar_size=-1.0", "pillar_size", "creationOpts");
    expectRejected("threads=2", "threads=0", "threads", "insertOpts");
}

// Geometry and every option away from their defaults (through the field tables, so that an
// option added later is covered too): all of them come back.
TEST(CHeightIntervalMapSerialization, RoundTripThroughClassFactoryIsExact)
{
    CHeightIntervalMap map(hif::test::everyFieldChanged<hif::GridGeometry>());
    static_cast<hif::Params&>(map.insertionOptions) = hif::test::everyFieldChanged<hif::Params>();
    map.insertionOptions.see_through_range = 12.0;  // so that the misses run
    map.genericMapParams.enableSaveAs3DObject = false;
    insertRandomScans(map, 25);
    ASSERT_GT(map.intervalCount(), 100u);

    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << map;
    buf.Seek(0);
    auto in = mrpt::serialization::archiveFrom(buf);
    const mrpt::serialization::CSerializable::Ptr obj = in.ReadObject();
    const auto copy = std::dynamic_pointer_cast<CHeightIntervalMap>(obj);
    ASSERT_TRUE(copy) << "the class factory did not produce a hif::CHeightIntervalMap";
    EXPECT_TRUE(copy->grid() == map.grid());
    EXPECT_EQ(hif::test::differingFields<hif::Params>(copy->params(), map.params()), "");
    EXPECT_EQ(hif::test::differingFields<hif::Params>(copy->insertionOptions, map.params()), "");
    EXPECT_EQ(copy->geometry(), map.geometry());
    EXPECT_FALSE(copy->genericMapParams.enableSaveAs3DObject);

    // Serializing the copy gives the same bytes (deterministic order).
    mrpt::io::CMemoryStream buf2;
    auto out2 = mrpt::serialization::archiveFrom(buf2);
    out2 << *copy;
    ASSERT_EQ(buf2.getTotalBytesCount(), buf.getTotalBytesCount());
    EXPECT_EQ(
        0, std::memcmp(buf.getRawBufferData(), buf2.getRawBufferData(), buf.getTotalBytesCount()));

    // Mapping continues identically from the copy.
    insertRandomScans(map, 3);
    insertRandomScans(*copy, 3);
    EXPECT_TRUE(copy->grid() == map.grid());
}

// Maps saved before the see-through options (serialization version 0) still load: the
// options take their defaults (off), everything else is read as saved.
TEST(CHeightIntervalMapSerialization, Version0MapsStillLoad)
{
    CHeightIntervalMap map(hif::GridGeometry{0.5, 0.1, -0.2, 0.02});
    map.insertionOptions.alpha = 0.65;
    map.insertionOptions.max_intervals_per_pillar = 12;
    insertRandomScans(map, 10);
    ASSERT_GT(map.intervalCount(), 100u);

    // The version-0 layout, field by field: geometry, insertion options without the two
    // see-through ones, generic map parameters, then the pillars.
    const hif::GridGeometry& p = map.geometry();
    const auto& o = map.insertionOptions;
    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << p.pillar_size << p.origin_x << p.origin_y << p.height_resolution;
    out << o.merge_gap << o.interval_padding << o.alpha << o.beta << o.p_min << o.p_max
        << o.p_empty_init << o.low_height_preservation << o.high_height_preservation
        << o.unseen_height_prior << o.beam_spacing_deg << o.static_threshold
        << o.max_intervals_per_pillar;
    out << map.genericMapParams;
    const auto pillars = map.grid().sortedPillars();
    out << static_cast<uint64_t>(pillars.size());
    for (const auto& [idx, pillar] : pillars)
    {
        out << idx.m << idx.n << pillar->logodds_empty << pillar->seen_top
            << static_cast<uint32_t>(pillar->intervals.size());
        for (const hif::Interval& iv : pillar->intervals) out << iv.lo << iv.hi << iv.logodds;
    }

    struct Version0Reader : CHeightIntervalMap
    {
        void read(mrpt::serialization::CArchive& in) { serializeFrom(in, 0); }
    };
    Version0Reader loaded;
    loaded.insertionOptions.see_through_range = 20.0;  // must be reset to the default
    buf.Seek(0);
    auto in = mrpt::serialization::archiveFrom(buf);
    loaded.read(in);
    hif::PillarGrid expected = map.grid();  // a version-0 map has no sensor model
    expected.setSensorModel(std::nullopt);
    for (const auto& [idx, pillar] : map.grid().sortedPillars())  // nor passed cells
    {
        hif::Pillar without = *pillar;
        without.passed = {};
        without.object_u = without.object_v = 0;  // nor where objects stood in them
        without.object_weight = 0;
        expected.setPillar(idx, std::move(without));
    }
    EXPECT_FALSE(loaded.grid().sensorModel());
    EXPECT_TRUE(loaded.grid() == expected);
    EXPECT_EQ(loaded.params(), map.params());
    EXPECT_EQ(loaded.insertionOptions.see_through_range, 0.0);
    EXPECT_EQ(loaded.insertionOptions.see_through_margin, hif::Params().see_through_margin);
}

TEST(CHeightIntervalMapSerialization, TruncatedDataThrows)
{
    CHeightIntervalMap map;
    insertRandomScans(map, 3);
    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << map;
    const auto n = static_cast<size_t>(buf.getTotalBytesCount());
    mrpt::io::CMemoryStream cut;
    cut.Write(buf.getRawBufferData(), n / 2);
    cut.Seek(0);
    auto in = mrpt::serialization::archiveFrom(cut);
    CHeightIntervalMap loaded;
    EXPECT_THROW(in >> loaded, std::exception);
}

// Found by fuzz_map (tests/fuzz): a byte other than 0 or 1 where a bool option is stored was
// loaded into the bool (undefined behaviour); it is a corrupt file.
TEST(CHeightIntervalMapSerialization, ABoolOptionThatIsNeither0Nor1IsCorrupt)
{
    auto bytes = [](bool lhp)
    {
        CHeightIntervalMap map;
        map.insertionOptions.low_height_preservation = lhp;
        mrpt::io::CMemoryStream buf;
        auto out = mrpt::serialization::archiveFrom(buf);
        out << map;
        const auto* p = static_cast<const uint8_t*>(buf.getRawBufferData());
        return std::vector<uint8_t>(p, p + buf.getTotalBytesCount());
    };
    const auto on = bytes(true), off = bytes(false);
    ASSERT_EQ(on.size(), off.size());
    std::vector<std::size_t> differ;
    for (std::size_t k = 0; k < on.size(); ++k)
        if (on[k] != off[k]) differ.push_back(k);
    ASSERT_EQ(differ.size(), 1u);  // the option's one byte
    auto corrupt = on;
    corrupt[differ[0]] = 2;
    mrpt::io::CMemoryStream in_buf;
    in_buf.Write(corrupt.data(), corrupt.size());
    in_buf.Seek(0);
    auto in = mrpt::serialization::archiveFrom(in_buf);
    CHeightIntervalMap loaded;
    try
    {
        in >> loaded;
        FAIL() << "a corrupt bool loaded";
    }
    catch (const std::exception& e)
    {
        EXPECT_NE(std::string(e.what()).find("option low_height_preservation is 2, not a bool"),
                  std::string::npos)
            << e.what();
    }
}

namespace
{
/** Inserts one point into `map` (one pillar, no sensor model); returns its interval count. */
std::size_t insertOnePoint(CHeightIntervalMap& map)
{
    auto cloud = mrpt::maps::CSimplePointsMap::Create();
    cloud->insertPoint(1.f, 1.f, 0.5f);
    mrpt::obs::CObservationPointCloud obs;
    obs.pointcloud = cloud;
    map.insertObservation(obs, mrpt::poses::CPose3D());
    EXPECT_EQ(map.grid().pillarCount(), 1u);
    return map.grid().sortedPillars().at(0).second->intervals.size();
}

/** The bytes after a one-pillar map's interval count: its intervals (12 bytes each), the
 *  sensor model's flag (0: one point gives no model), the free-space test's scan count
 *  (uint32, 0: the test is off) and MRPT's end-of-object byte. */
std::size_t onePillarTail(std::size_t intervals) { return 12 * intervals + 6; }
}  // namespace

// A pillar's passed cells (version 6) with bits but no base is corrupt: an error, not a record
// that says beams passed somewhere unknown.
TEST(CHeightIntervalMapSerialization, PassedCellsWithoutABaseAreCorrupt)
{
    CHeightIntervalMap map;
    const std::size_t intervals = insertOnePoint(map);
    std::vector<uint8_t> bytes = hif::test::mapBytes(map);
    // The one pillar's passed cells (base int32, two uint64) come before its interval count
    // and what onePillarTail() says follows it.
    const std::size_t at = bytes.size() - onePillarTail(intervals) - 4 - 20;
    const int32_t none = hif::PassedCells::kNone;
    const uint64_t one = 1;
    std::memcpy(&bytes[at], &none, 4);
    std::memcpy(&bytes[at + 4], &one, 8);
    EXPECT_NE(hif::test::loadError(bytes).find("passed cells without a base"), std::string::npos)
        << hif::test::loadError(bytes);
}

// Found by fuzz_map (tests/fuzz): a pillar's interval count, bounded only by the file's own
// max_intervals_per_pillar, was allocated before its intervals were read: a short file could
// ask for gigabytes. The intervals are read one at a time; the file ends first.
TEST(CHeightIntervalMapSerialization, AHugeIntervalCountInAShortFileIsNotAllocated)
{
    CHeightIntervalMap map;
    map.insertionOptions.max_intervals_per_pillar = std::size_t{1} << 40;
    const std::size_t intervals = insertOnePoint(map);
    ASSERT_GE(intervals, 1u);
    std::vector<uint8_t> bytes = hif::test::mapBytes(map);
    ASSERT_EQ(bytes[bytes.size() - 6], 0u) << "no sensor model";
    // The one pillar's interval count (uint32) comes before what onePillarTail() says.
    const std::size_t at = bytes.size() - onePillarTail(intervals) - 4;
    uint32_t count = 0;
    std::memcpy(&count, &bytes[at], 4);
    ASSERT_EQ(count, intervals);
    count = 1u << 25;  // 384 MiB of intervals (far more fails to allocate at all)
    std::memcpy(&bytes[at], &count, 4);
    mrpt::io::CMemoryStream in_buf;
    in_buf.Write(bytes.data(), bytes.size());
    in_buf.Seek(0);
    auto in = mrpt::serialization::archiveFrom(in_buf);
    struct rusage before
    {
    };
    getrusage(RUSAGE_SELF, &before);
    CHeightIntervalMap loaded;
    EXPECT_THROW(in >> loaded, std::exception);
    struct rusage after
    {
    };
    getrusage(RUSAGE_SELF, &after);
    EXPECT_LT(after.ru_maxrss - before.ru_maxrss, 256 * 1024) << "kB of peak memory added";
}

TEST(CHeightIntervalMapIni, ShippedKittiConfigsLoadTheDocumentedDefaults)
{
    for (const std::string name : {"kitti.ini", "kitti-online.ini", "dynamicmap.ini"})
    {
        mrpt::config::CConfigFile cfg(std::string(HIF_SHARE_DIR "/config/") + name);
        mrpt::maps::TSetOfMetricMapInitializers inits;
        inits.loadFromConfigFile(cfg, "map");
        mrpt::maps::CMultiMetricMap multi(inits);
        const auto map = multi.mapByClass<CHeightIntervalMap>();
        ASSERT_TRUE(map) << name;
        // They differ from hif::Params() in what doc/algorithm.md measures: the see-through
        // misses, the surfaces at pillars' edges and the free-space test; offline, the mode,
        // p_empty_init, ground seen once and a higher share for the test; online, a lower one;
        // the DynamicMap layout, a minimum range too.
        hif::Params expected;
        expected.pillar_edge_margin = 0.1;
        expected.free_space_window = 10;
        expected.free_space_fraction = 0.4;
        expected.see_through_range = 35.0;
        expected.see_through_margin = 2.5;
        if (name != "kitti-online.ini")
        {
            expected.online = false;
            expected.p_empty_init = 0.42;
            expected.ground_max_slope_deg = 5.0;
            expected.free_space_fraction = 0.7;
        }
        if (name == "dynamicmap.ini") expected.min_range = 3.0;
        EXPECT_EQ(hif::test::differingFields<hif::Params>(map->params(), expected), "") << name;
    }
}

TEST(CHeightIntervalMapIni, ShippedPaperConfigLoadsThePaperSettings)
{
    mrpt::config::CConfigFile cfg(HIF_SHARE_DIR "/config/kitti-paper.ini");
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, "map");
    mrpt::maps::CMultiMetricMap multi(inits);
    const auto map = multi.mapByClass<CHeightIntervalMap>();
    ASSERT_TRUE(map);
    EXPECT_EQ(map->params(), hif::Params::paper());
}

// The LiDAR given in the .ini instead of estimated (doc/sensors.md): a spinning one by its
// beams, a non-repetitive one by its field of view; the map uses it from the start, it is
// saved with the options, and a wrong or incomplete one is an error naming the key.
TEST(CHeightIntervalMapIni, ASensorGivenInTheIniIsTheMapsModel)
{
    const std::string vlp16 = std::string(kIni) +
                              "sensor_beams_deg=15, 13, 11, 9, 7, 5, 3, 1, -1, -3, -5, -7, -9, "
                              "-11, -13, -15\nsensor_horizontal_resolution_deg=0.2\n";
    mrpt::maps::CMultiMetricMap multi(initializersFrom(vlp16));
    const auto map = multi.mapByClass<CHeightIntervalMap>();
    ASSERT_TRUE(map);
    const auto& m = map->grid().sensorModel();
    ASSERT_TRUE(m);
    EXPECT_EQ(m->beam_elevations_deg.size(), 16u);
    EXPECT_EQ(m->beam_elevations_deg.front(), -15.0);  // sorted
    EXPECT_DOUBLE_EQ(m->vertical_spacing_deg, 2.0);
    EXPECT_EQ(m->azimuth_coverage_deg, 360.0);
    // Its range images are laid out for it: a row per degree (half the spacing).
    EXPECT_NEAR(map->grid().imageLayout().tan_res, M_PI / 180.0, 1e-12);

    // Saved and read back with the options.
    mrpt::config::CConfigFileMemory cfg;
    map->insertionOptions.saveToConfigFile(cfg, "opts");
    CHeightIntervalMap::TInsertionOptions back;
    back.loadFromConfigFile(mrpt::config::CConfigFileMemory(cfg.getContent()), "opts");
    ASSERT_TRUE(back.sensor);
    EXPECT_TRUE(*back.sensor == *m);

    // A Livox-style pattern: its field of view and spacing.
    mrpt::maps::CMultiMetricMap livox(initializersFrom(
        std::string(kIni) +
        "sensor_fov_deg=-35 21\nsensor_spacing_deg=0.27\nsensor_azimuth_deg=70\n"));
    const auto& l = livox.mapByClass<CHeightIntervalMap>()->grid().sensorModel();
    ASSERT_TRUE(l);
    EXPECT_FALSE(l->hasRings());
    EXPECT_EQ(l->elevation_min_deg, -35.0);
    EXPECT_EQ(l->azimuth_coverage_deg, 70.0);

    // Mistakes, each named.
    const std::string insert = "map_CHeightIntervalMap_00_insertOpts";
    for (const auto& [keys, says] : std::vector<std::pair<std::string, std::string>>{
             {"sensor_beams_deg=-15 -13\n", "sensor_horizontal_resolution_deg missing"},
             {"sensor_beams_deg=-15 x 15\nsensor_horizontal_resolution_deg=0.2\n",
              "'x' is not a number"},
             {"sensor_beams_deg=3\nsensor_horizontal_resolution_deg=0.2\n", "1 beam elevations"},
             {"sensor_beams_deg=-1 -1 2\nsensor_horizontal_resolution_deg=0.2\n",
              "is not ascending"},
             {"sensor_fov_deg=-30 20\nsensor_beams_deg=1 2\n", "give one"},
             {"sensor_fov_deg=-30\nsensor_spacing_deg=0.3\n", "give the lowest and the highest"},
             {"sensor_spacing_deg=0.3\n", "without sensor_beams_deg"},
             {"sensor_fov_deg=-30 20\nsensor_spacing_deg=0\n", "vertical_spacing_deg 0"}})
    {
        try
        {
            initializersFrom(std::string(kIni) + keys);
            ADD_FAILURE() << keys << " accepted";
        }
        catch (const std::exception& e)
        {
            EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
            EXPECT_NE(std::string(e.what()).find(insert), std::string::npos) << e.what();
        }
    }
}

// A ConfigText is read once: the map's strict checks read its text from memory (the file may be
// gone), and still name the file in what they report.
TEST(CHeightIntervalMapIni, AConfigTextIsReadOnceAndNamedInErrors)
{
    const hif::test::WorkDir dir("config_text");
    std::stringstream shipped;
    shipped << std::ifstream(HIF_SHARE_DIR "/config/kitti.ini").rdbuf();
    const std::string good = dir.path() + "/good.ini", bad = dir.path() + "/bad.ini";
    std::ofstream(good) << shipped.str();
    std::string text = shipped.str();
    const std::string from = "alpha=0.6";
    text.replace(text.find(from), from.size(), "alpha 0.6");
    std::ofstream(bad) << text;
    const hif::ConfigText good_cfg(good), bad_cfg(bad);
    std::filesystem::remove(good);
    std::filesystem::remove(bad);

    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(good_cfg, "map");
    mrpt::maps::CMultiMetricMap maps;
    maps.setListOfMaps(inits);
    const auto map = maps.mapByClass<hif::CHeightIntervalMap>();
    ASSERT_TRUE(map);
    EXPECT_DOUBLE_EQ(map->params().alpha, 0.6);
    const hif::IniSection section(good_cfg, "map_CHeightIntervalMap_00_insertOpts");
    EXPECT_TRUE(section.linesChecked());

    try
    {
        mrpt::maps::TSetOfMetricMapInitializers bad_inits;
        bad_inits.loadFromConfigFile(bad_cfg, "map");
        ADD_FAILURE() << "a line that is not key = value was read";
    }
    catch (const std::exception& e)
    {
        EXPECT_NE(std::string(e.what()).find("'" + bad + "', line "), std::string::npos)
            << e.what();
        // MRPT wraps what passes through its loader (the apps print the innermost message).
        EXPECT_NE(
            std::string(e.what()).find("'alpha 0.6' in [map_CHeightIntervalMap_00_insertOpts"),
            std::string::npos)
            << e.what();
        EXPECT_NE(std::string(e.what()).find("is not key = value"), std::string::npos) << e.what();
    }
    EXPECT_THROW(hif::ConfigText(dir.path() + "/missing.ini"), std::runtime_error);
}
