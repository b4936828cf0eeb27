// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap_options.cpp
 * @brief  .ini load and save of the map's options and map definition, field by field from the
 *         core's field tables.
 */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>

#include <ostream>
#include <sstream>
#include <stdexcept>

#include "hif/CHeightIntervalMap.h"
#include "hif/IniSection.h"

using namespace hif;

namespace
{
/** The keys of S's fields. */
template <typename S>
std::vector<std::string> keysOf()
{
    std::vector<std::string> keys;
    forEachField<S>([&](const Field<S>& f, auto) { keys.emplace_back(f.name); });
    return keys;
}

/** Reads every field of `s` present in `section` (absent keys keep their value), strictly. */
template <typename S>
void loadFields(S& s, const IniSection& section)
{
    forEachField<S>(
        [&](const Field<S>& f, auto member)
        {
            auto& v = s.*member;
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, std::size_t>)
            {
                uint64_t u = v;
                section.read(f.name, u);
                v = static_cast<T>(u);
            }
            else
                section.read(f.name, v);
        });
}

/** Writes every field of `s` to `section`, with its doc as comment. Doubles are written so
 *  that they read back exactly; keys are unpadded (MRPT 2.5.8's CConfigFileMemory keeps the
 *  padding in the key, so a padded key cannot be read back from the same object). */
template <typename S>
void saveFields(const S& s, mrpt::config::CConfigFileBase& c, const std::string& section)
{
    forEachField<S>(
        [&](const Field<S>& f, auto member)
        {
            const auto v = s.*member;
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, double>)
            {
                std::string txt = mrpt::format("%.15g", v);
                if (std::stod(txt) != v) txt = mrpt::format("%.17g", v);
                c.write(section, f.name, txt, -1, -1, f.doc);
            }
            else if constexpr (std::is_same_v<T, bool>)
                c.write(section, f.name, v, -1, -1, f.doc);
            else
                c.write(section, f.name, static_cast<uint64_t>(v), -1, -1, f.doc);
        });
}

/** Runs `validate`, adding where the values come from to its message. */
template <typename F>
void validateIn(const IniSection& section, F&& validate)
{
    try
    {
        validate();
    }
    catch (const std::invalid_argument& e)
    {
        section.fail(e.what());
    }
}
}  // namespace

namespace
{
/** The LiDAR given by the section's sensor_* keys, or none when it has none of them. */
std::optional<SensorModel> readSensor(const IniSection& section)
{
    const bool beams = section.has("sensor_beams_deg"), fov = section.has("sensor_fov_deg");
    if (!beams && !fov)
    {
        for (const char* k :
             {"sensor_spacing_deg", "sensor_horizontal_resolution_deg", "sensor_azimuth_deg"})
            if (section.has(k))
                section.fail(std::string(k) +
                             " without sensor_beams_deg (a spinning LiDAR) or sensor_fov_deg (a "
                             "non-repetitive one)");
        return std::nullopt;
    }
    if (beams && fov)
        section.fail(
            "sensor_beams_deg and sensor_fov_deg: give one (a spinning LiDAR's beams, or "
            "a non-repetitive one's field of view)");
    auto need = [&](const char* k)
    {
        if (!section.has(k))
            section.fail(std::string(k) + " missing (needed with " +
                         (beams ? "sensor_beams_deg)" : "sensor_fov_deg)"));
    };
    double azimuth = 360.0, spacing = 0.0, horizontal = 0.0;
    section.read("sensor_azimuth_deg", azimuth);
    try
    {
        if (beams)
        {
            need("sensor_horizontal_resolution_deg");
            if (section.has("sensor_spacing_deg"))
                section.fail(
                    "sensor_spacing_deg with sensor_beams_deg: the spacing follows from "
                    "the beams");
            std::vector<double> el;
            section.read("sensor_beams_deg", el);
            section.read("sensor_horizontal_resolution_deg", horizontal);
            return SensorModel::fromBeams(el, horizontal, azimuth);
        }
        need("sensor_spacing_deg");
        if (section.has("sensor_horizontal_resolution_deg"))
            section.fail(
                "sensor_horizontal_resolution_deg with sensor_fov_deg: a non-repetitive "
                "pattern has one spacing (sensor_spacing_deg)");
        std::vector<double> v;
        section.read("sensor_fov_deg", v);
        if (v.size() != 2)
            section.fail("sensor_fov_deg has " + std::to_string(v.size()) +
                         " numbers: give the lowest and the highest elevation");
        section.read("sensor_spacing_deg", spacing);
        return SensorModel::fromPattern(v[0], v[1], spacing, azimuth);
    }
    catch (const std::invalid_argument& e)
    {
        if (std::string(e.what()).rfind("hif::SensorModel", 0) != 0) throw;  // already placed
        section.fail(std::string("the sensor_* keys: ") + e.what());
    }
}
}  // namespace

void CHeightIntervalMap::TInsertionOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
    const IniSection section(c, s);
    std::vector<std::string> known = keysOf<Params>();
    known.insert(known.end(),
                 {"threads", "sensor_beams_deg", "sensor_fov_deg", "sensor_spacing_deg",
                  "sensor_horizontal_resolution_deg", "sensor_azimuth_deg"});
    section.requireKnownKeys(known);
    loadFields<Params>(*this, section);
    section.read("threads", threads);
    if (threads == 0) section.fail("threads = 0: must be >= 1");
    sensor = readSensor(section);
    // Validate now, so that a bad value is reported with where it came from.
    validateIn(section, [&] { Params::validate(); });
}

void CHeightIntervalMap::TInsertionOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                             const std::string& s) const
{
    saveFields<Params>(*this, c, s);
    c.write(s, "threads", threads, -1, -1,
            "Threads for insertion and classification (same map for any count)");
    if (!sensor) return;
    auto list = [](const std::vector<double>& v)
    {
        std::ostringstream os;
        os.precision(17);
        for (std::size_t k = 0; k < v.size(); ++k) os << (k ? " " : "") << v[k];
        return os.str();
    };
    if (sensor->hasRings())
    {
        c.write(s, "sensor_beams_deg", list(sensor->beam_elevations_deg), -1, -1,
                "The LiDAR's beams, degrees of elevation");
        c.write(s, "sensor_horizontal_resolution_deg", sensor->horizontal_resolution_deg, -1, -1,
                "Azimuth step of a beam, degrees");
    }
    else
    {
        c.write(s, "sensor_fov_deg", list({sensor->elevation_min_deg, sensor->elevation_max_deg}),
                -1, -1, "Lowest and highest elevation of a non-repetitive LiDAR, degrees");
        c.write(s, "sensor_spacing_deg", sensor->vertical_spacing_deg, -1, -1,
                "Mean angle between its points in one scan, degrees");
    }
    c.write(s, "sensor_azimuth_deg", sensor->azimuth_coverage_deg, -1, -1,
            "Azimuth the LiDAR covers, degrees");
}

CHeightIntervalMap::TMapDefinition::TMapDefinition() = default;

void CHeightIntervalMap::TMapDefinition::loadFromConfigFile_map_specific(
    const mrpt::config::CConfigFileBase& source, const std::string& sectionNamePrefix)
{
    const IniSection creation(source, sectionNamePrefix + "_creationOpts");
    creation.requireKnownKeys(keysOf<GridGeometry>());
    loadFields<GridGeometry>(geometry, creation);
    validateIn(creation, [&] { geometry.validate(); });
    insertionOpts.loadFromConfigFile(source, sectionNamePrefix + "_insertOpts");
    validateIn(IniSection(source, sectionNamePrefix + "_insertOpts"),
               [&] { insertionOpts.validateWith(geometry); });
}

void CHeightIntervalMap::TMapDefinition::dumpToTextStream_map_specific(std::ostream& out) const
{
    forEachField<GridGeometry>(
        [&](const Field<GridGeometry>& f, auto member)
        { dumpVar_double(out, f.name, static_cast<double>(geometry.*member)); });
    insertionOpts.dumpToTextStream(out);
}
