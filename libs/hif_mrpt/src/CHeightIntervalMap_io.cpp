// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap_io.cpp
 * @brief  Serialization of the map (versioned; every version still read), and its text and
 *         .3Dscene representation.
 */
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/serialization/CArchive.h>
#include <algorithm>

#include <filesystem>
#include <fstream>

#include "hif/CHeightIntervalMap.h"

using namespace hif;

IMPLEMENTS_SERIALIZABLE(CHeightIntervalMap, CMetricMap, hif)

namespace
{
/** Version 1 added the see-through options, version 2 the free-space test and the minimum
 *  range (Field::since_version), version 3 the sensor model (its option, and the model after
 *  the pillars), version 4 the `online` option and the free-space test's scans (after the
 *  model), version 5 the ground options, version 6 each pillar's cells beams passed through
 *  (Pillar::passed, after seen_top), version 7 the pillar edge margin, version 8 where in
 *  each pillar what stands above its ground was seen (Pillar::object_u, object_v,
 *  object_weight, after the passed cells); every older version is still read (its pillars
 *  with no such cells: what later scans insert there starts from p_empty_init until beams
 *  pass; nothing seen yet above the ground: judged by the beams toward the pillar's centre
 *  until it is). */
constexpr uint8_t kSerializationVersion = 8;
/** More beams than any LiDAR has: a larger count in a file is corruption. */
constexpr uint32_t kMaxBeams = 4096;
/** A free-space image in a file has the layout of the map's sensor model, and at most this
 *  many cells (a 128-beam LiDAR's: 7200 columns of 0.05 degrees by 260 rows): more is a corrupt
 *  file, which must not make the reader allocate what it says. */
constexpr std::size_t kMaxImageCells = std::size_t{8} << 20;

/** A free-space test's scan. Its image is mostly "no return": it is written as the cells that
 *  hold one, each as the number of cells skipped since the last (a varint) and its value (two
 *  bytes, little-endian), in one buffer. */
void writeTestScan(mrpt::serialization::CArchive& out, const FreeSpaceTest::Scan& s)
{
    out << s.fingerprint;
    const Eigen::Matrix4d& m = s.sensor_to_world.matrix();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) out << m(r, c);
    out << static_cast<int32_t>(s.layout.cols) << static_cast<int32_t>(s.layout.rows)
        << s.layout.tan_min << s.layout.tan_max << s.layout.tan_res;
    std::vector<uint8_t> bytes;
    bytes.reserve(s.image.cells() / 2);
    std::size_t next = 0;  // the cell after the last return written
    s.image.forEachReturn(
        [&](std::size_t cell, uint16_t v)
        {
            std::size_t skipped = cell - next;
            for (; skipped >= 0x80; skipped >>= 7)
                bytes.push_back(uint8_t(0x80 | (skipped & 0x7F)));
            bytes.push_back(uint8_t(skipped));
            next = cell + 1;
            bytes.push_back(uint8_t(v & 0xFF));
            bytes.push_back(uint8_t(v >> 8));
        });
    out << static_cast<uint32_t>(bytes.size());
    out.WriteBuffer(bytes.data(), bytes.size());
}

FreeSpaceTest::Scan readTestScan(mrpt::serialization::CArchive& in,
                                 const RangeImageLayout& expected)
{
    FreeSpaceTest::Scan s;
    in >> s.fingerprint;
    Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) in >> m(r, c);
    s.sensor_to_world.matrix() = m;
    int32_t cols = 0, rows = 0;
    in >> cols >> rows >> s.layout.tan_min >> s.layout.tan_max >> s.layout.tan_res;
    s.layout.cols = cols;
    s.layout.rows = rows;
    if (!(s.layout == expected) || expected.cells() > kMaxImageCells)
        THROW_EXCEPTION_FMT(
            "Corrupt hif map: a free-space image of %d x %d cells, not laid out "
            "for the map's sensor (%d x %d)",
            cols, rows, expected.cols, expected.rows);
    std::vector<uint16_t> image(s.layout.cells(), FreeSpaceTest::kNoReturn);
    uint32_t n = 0;
    in >> n;
    // At most 4 bytes a cell (a varint of up to 2 bytes and the value): more is corruption.
    if (n > 4 * image.size())
        THROW_EXCEPTION_FMT("Corrupt hif map: %u bytes for an image of %zu cells", n, image.size());
    std::vector<uint8_t> bytes(n);
    if (in.ReadBuffer(bytes.data(), n) != n)
        THROW_EXCEPTION("Corrupt hif map: a free-space image ends early");
    std::size_t cell = 0, k = 0;
    while (k < n)
    {
        std::size_t skip = 0;
        for (int shift = 0;; shift += 7)
        {
            if (k >= n || shift > 28)
                THROW_EXCEPTION("Corrupt hif map: a free-space image's cells");
            const uint8_t b = bytes[k++];
            skip |= std::size_t(b & 0x7F) << shift;
            if (!(b & 0x80)) break;
        }
        cell += skip;
        if (cell >= image.size() || k + 2 > n)
            THROW_EXCEPTION("Corrupt hif map: a free-space image's cells");
        image[cell++] = uint16_t(bytes[k] | bytes[k + 1] << 8);
        k += 2;
    }
    s.image.assign(s.layout.rows, s.layout.cols, image);
    return s;
}
}  // namespace

void CHeightIntervalMap::TInsertionOptions::writeToStream(mrpt::serialization::CArchive& out) const
{
    // Grouped by the version that added each field, so that every older layout is a prefix.
    for (uint8_t v = 0; v <= kSerializationVersion; ++v)
        forEachField<Params>(
            [&](const Field<Params>& f, auto member)
            {
                if (f.since_version != v) return;
                const auto value = this->*member;
                if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::size_t>)
                    out << static_cast<uint64_t>(value);
                else
                    out << value;
            });
}

void CHeightIntervalMap::TInsertionOptions::readFromStream(mrpt::serialization::CArchive& in,
                                                           uint8_t version)
{
    static_cast<Params&>(*this) = Params();  // fields newer than `version` keep the default
    for (uint8_t v = 0; v <= version && v <= kSerializationVersion; ++v)
        forEachField<Params>(
            [&](const Field<Params>& f, auto member)
            {
                if (f.since_version != v) return;
                auto& value = this->*member;
                if constexpr (std::is_same_v<std::decay_t<decltype(value)>, std::size_t>)
                {
                    uint64_t u = 0;
                    in >> u;
                    value = static_cast<std::size_t>(u);
                }
                else if constexpr (std::is_same_v<std::decay_t<decltype(value)>, bool>)
                {
                    // One byte, 0 or 1 (read as a byte: any other value in a bool is undefined).
                    uint8_t b = 0;
                    in >> b;
                    if (b > 1)
                        THROW_EXCEPTION_FMT("Corrupt hif map: option %s is %u, not a bool", f.name,
                                            static_cast<unsigned>(b));
                    value = b == 1;
                }
                else
                    in >> value;
            });
}

uint8_t CHeightIntervalMap::serializeGetVersion() const { return kSerializationVersion; }

void CHeightIntervalMap::serializeTo(mrpt::serialization::CArchive& out) const
{
    const GridGeometry& g = geometry();
    forEachField<GridGeometry>([&](const Field<GridGeometry>&, auto member) { out << g.*member; });
    insertionOptions.writeToStream(out);
    out << genericMapParams;
    const auto pillars = grid_.sortedPillars();
    out << static_cast<uint64_t>(pillars.size());
    for (const auto& [idx, pillar] : pillars)
    {
        out << idx.m << idx.n << pillar->logodds_empty << pillar->seen_top << pillar->passed.base
            << pillar->passed.bits[0] << pillar->passed.bits[1] << pillar->object_u
            << pillar->object_v << pillar->object_weight
            << static_cast<uint32_t>(pillar->intervals.size());
        for (const Interval& iv : pillar->intervals) out << iv.lo << iv.hi << iv.logodds;
    }
    const std::optional<SensorModel>& m = grid_.sensorModel();
    out << static_cast<uint8_t>(m ? 1 : 0);
    if (m)
    {
        out << static_cast<uint32_t>(m->beam_elevations_deg.size());
        for (double e : m->beam_elevations_deg) out << e;
        out << m->elevation_min_deg << m->elevation_max_deg << m->vertical_spacing_deg
            << m->horizontal_resolution_deg << m->azimuth_coverage_deg;
    }
    out << static_cast<uint32_t>(free_space_.size());
    for (const FreeSpaceTest::Scan& s : free_space_.scans()) writeTestScan(out, s);
}

void CHeightIntervalMap::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
    if (version > kSerializationVersion) MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    GridGeometry g;
    forEachField<GridGeometry>([&](const Field<GridGeometry>&, auto member) { in >> g.*member; });
    insertionOptions.readFromStream(in, version);
    in >> genericMapParams;
    grid_ = PillarGrid(g, insertionOptions);  // validates the geometry and the options
    applyOptions();                           // the thread count
    uint64_t n = 0;
    in >> n;
    for (uint64_t k = 0; k < n; ++k)
    {
        PillarIndex idx;
        Pillar pillar;
        uint32_t count = 0;
        in >> idx.m >> idx.n >> pillar.logodds_empty >> pillar.seen_top;
        if (version >= 6)
        {
            PassedCells& p = pillar.passed;
            in >> p.base >> p.bits[0] >> p.bits[1];
            if (p.base == PassedCells::kNone && (p.bits[0] != 0 || p.bits[1] != 0))
                THROW_EXCEPTION("Corrupt hif map: a pillar's passed cells without a base");
        }
        if (version >= 8)
        {
            in >> pillar.object_u >> pillar.object_v >> pillar.object_weight;
            if (pillar.object_weight > Pillar::kObjectSightings)
                THROW_EXCEPTION_FMT("Corrupt hif map: a pillar's object weight %u, above %u",
                                    unsigned{pillar.object_weight},
                                    unsigned{Pillar::kObjectSightings});
        }
        in >> count;
        if (count > params().max_intervals_per_pillar)
            THROW_EXCEPTION_FMT("Corrupt hif map: pillar with %u intervals, above the bound",
                                count);
        // One at a time: a corrupt count in a short file ends in an end-of-file error, not in
        // allocating what the count says.
        pillar.intervals.reserve(std::min<uint32_t>(count, 64));
        for (uint32_t j = 0; j < count; ++j)
        {
            Interval iv;
            in >> iv.lo >> iv.hi >> iv.logodds;
            pillar.intervals.push_back(iv);
        }
        grid_.setPillar(idx, std::move(pillar));
    }
    if (version >= 3)
    {
        uint8_t has = 0;
        in >> has;
        if (has > 1) THROW_EXCEPTION_FMT("Corrupt hif map: sensor model flag %u", unsigned{has});
        if (has == 1)
        {
            SensorModel m;
            uint32_t beams = 0;
            in >> beams;
            if (beams > kMaxBeams)
                THROW_EXCEPTION_FMT("Corrupt hif map: a sensor model of %u beams", beams);
            m.beam_elevations_deg.resize(beams);
            for (double& e : m.beam_elevations_deg) in >> e;
            in >> m.elevation_min_deg >> m.elevation_max_deg >> m.vertical_spacing_deg >>
                m.horizontal_resolution_deg >> m.azimuth_coverage_deg;
            try
            {
                grid_.setSensorModel(std::move(m));
            }
            catch (const std::invalid_argument& e)
            {
                THROW_EXCEPTION_FMT("Corrupt hif map: %s", e.what());
            }
        }
    }
    free_space_ = FreeSpaceTest(FreeSpaceTest::capacityFor(params()));
    if (version >= 4)
    {
        uint32_t scans = 0;
        in >> scans;
        if (scans > free_space_.capacity())
            THROW_EXCEPTION_FMT(
                "Corrupt hif map: a free-space test of %u scans, more than its "
                "options keep (%zu)",
                scans, free_space_.capacity());
        for (uint32_t k = 0; k < scans; ++k) free_space_.add(readTestScan(in, grid_.imageLayout()));
    }
    last_insert_ = {};
    classified_ = warned_no_neighbours_ = warned_inserted_after_ = false;
}

void CHeightIntervalMap::saveMetricMapRepresentationToFile(const std::string& prefix) const
{
    const GridGeometry& g = geometry();
    const std::string txt = prefix + "_intervals.txt";
    std::ofstream f(txt);
    if (!f) THROW_EXCEPTION_FMT("Error writing to target file '%s'", txt.c_str());
    f << "# x_min y_min x_max y_max z_bottom z_top p_static\n";
    f.precision(12);  // world coordinates in the millions of metres (UTM) keep their millimetres
    for (const auto& [idx, pillar] : grid_.sortedPillars())
    {
        const double x0 = g.origin_x + idx.m * g.pillar_size;
        const double y0 = g.origin_y + idx.n * g.pillar_size;
        for (const Interval& iv : pillar->intervals)
            f << x0 << ' ' << y0 << ' ' << x0 + g.pillar_size << ' ' << y0 + g.pillar_size << ' '
              << g.cellBottom(iv.lo) << ' ' << g.cellBottom(iv.hi) << ' ' << logistic(iv.logodds)
              << '\n';
    }
    if (!f) THROW_EXCEPTION_FMT("Error writing to target file '%s'", txt.c_str());

    saveSceneToFile(prefix + "_3D.3Dscene");
}

void CHeightIntervalMap::saveSceneToFile(const std::string& file) const
{
    mrpt::opengl::COpenGLScene scene;
    auto objs = mrpt::opengl::CSetOfObjects::Create();
    getVisualizationInto(*objs);
    scene.insert(objs);
    if (!scene.saveToFile(file))
        throw std::runtime_error("Error writing to target file '" + file + "'");
}

void CHeightIntervalMap::saveToFile(const std::string& file) const
{
    // A gzip file whose blocks are stored, not deflated: the same bytes inside, readable as any
    // gzip file, in a tenth of the time. Most of a map file is its free-space test's range
    // images, which deflate only to about half (KITTI 08's map: 9.0 MB, 4.9 MB at level 1), and
    // deflating them took 0.13 s of hif-clean's 0.9 s on that clip, at the end of the run.
    constexpr int kStored = 0;
    mrpt::io::CFileGZOutputStream f;
    if (!f.open(file, kStored))
        throw std::runtime_error("Error writing to target file '" + file + "'");
    auto arch = mrpt::serialization::archiveFrom(f);
    arch << *this;
}

void CHeightIntervalMap::loadFromFile(const std::string& file)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec))
        throw std::runtime_error("the hif map file '" + file + "' does not exist or is not a file");
    try
    {
        mrpt::io::CFileGZInputStream f;
        if (!f.open(file)) throw std::runtime_error("cannot open it");
        auto arch = mrpt::serialization::archiveFrom(f);
        arch.ReadObject(this);
    }
    catch (const std::exception& e)
    {
        throw std::runtime_error(
            "'" + file + "' is not a hif map that can be read: " + mrpt::exception_to_str(e));
    }
}
