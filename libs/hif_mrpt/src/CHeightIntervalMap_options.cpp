// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap_options.cpp
 * @brief  .ini load and save of the map's options and map definition, field by field from the
 *         core's field tables.
 */
#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>

#include <ostream>
#include <stdexcept>

#include "IniSection.h"
#include "hif/CHeightIntervalMap.h"

using namespace hif;
using hif::mrpt_adapter::IniSection;

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

void CHeightIntervalMap::TInsertionOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& c, const std::string& s)
{
    const IniSection section(c, s);
    std::vector<std::string> known = keysOf<Params>();
    known.emplace_back("threads");
    section.requireKnownKeys(known);
    loadFields<Params>(*this, section);
    section.read("threads", threads);
    if (threads == 0) section.fail("threads = 0: must be >= 1");
    // Validate now, so that a bad value is reported with where it came from.
    validateIn(section, [&] { Params::validate(); });
}

void CHeightIntervalMap::TInsertionOptions::saveToConfigFile(mrpt::config::CConfigFileBase& c,
                                                             const std::string& s) const
{
    saveFields<Params>(*this, c, s);
    c.write(s, "threads", threads, -1, -1,
            "Threads for insertion and classification (same map for any count)");
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
