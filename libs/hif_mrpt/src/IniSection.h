// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   IniSection.h
 * @brief  Strict reading of one .ini section of the map's options: every line a key = value,
 *         every key known, every value read whole; a mistake is an error that names the file,
 *         the section, the key and what was written.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <cstdint>
#include <string>
#include <vector>

namespace hif::mrpt_adapter
{
class IniSection
{
public:
    /** Checks the syntax of the configuration's text (when it has one: a file, or text in
     *  memory): every section header closed, every line of `section` a key = value. */
    IniSection(const mrpt::config::CConfigFileBase& config, std::string section);

    /** Throws if the section holds a key not in `known`, suggesting the nearest known one. */
    void requireKnownKeys(const std::vector<std::string>& known) const;

    /** Reads `key` into `value` if the section has it (else leaves it); throws if what is
     *  written is not a whole value of the type. */
    void read(const char* key, double& value) const;
    void read(const char* key, bool& value) const;
    void read(const char* key, uint64_t& value) const;
    /** Numbers separated by spaces or commas; throws if any is not a whole number. */
    void read(const char* key, std::vector<double>& values) const;
    /** Whether the section has `key`. */
    [[nodiscard]] bool has(const char* key) const;

    /** "'<file>', [<section>]" (or "[<section>]" when the configuration has no file). */
    [[nodiscard]] const std::string& where() const { return where_; }
    /** Throws std::invalid_argument "<where>: <problem>". */
    [[noreturn]] void fail(const std::string& problem) const;

private:
    /** The text written for `key`, trimmed; false if the section does not have it. */
    bool text(const char* key, std::string& out) const;

    const mrpt::config::CConfigFileBase& config_;
    std::string section_;
    std::string where_;
};

}  // namespace hif::mrpt_adapter
