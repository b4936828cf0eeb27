// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   IniSection.h
 * @brief  Strict reading of .ini sections, as the map reads its options and applications
 *         may read their own (hif-icp-slam's [SLAM]): every line a key = value, every key
 *         known, every value read whole; a mistake is an error that names the file, the
 *         section, the key and what was written. And ConfigText, an .ini read once from its
 *         file, which MRPT's loaders and this reader then share.
 */
#pragma once

#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cstdint>
#include <string>
#include <vector>

namespace hif
{
/** An .ini file read once into memory, keeping its name: give it to MRPT's loaders
 *  (TSetOfMetricMapInitializers, any CLoadableOptions) in place of a CConfigFile, and the
 *  strict checks below read the text from memory instead of the file again, with the file's
 *  name in their messages. Throws std::runtime_error naming the file if it cannot be read. */
class ConfigText : public mrpt::config::CConfigFileMemory
{
public:
    explicit ConfigText(const std::string& file);
    [[nodiscard]] const std::string& file() const { return file_; }
    [[nodiscard]] const std::string& text() const { return text_; }

private:
    std::string file_, text_;
};

class IniSection
{
public:
    /** Checks the syntax of the configuration's text: every section header closed, every line
     *  of `section` a key = value. The text is a ConfigText's or a CConfigFileMemory's, or a
     *  CConfigFile's file read again (as MRPT's own programs give it). Other kinds of
     *  configuration keep no text (their parser has dropped any line it could not read): for
     *  them only the keys and values are checked, and linesChecked() is false. */
    IniSection(const mrpt::config::CConfigFileBase& config, std::string section);

    /** Whether the lines of the section could be checked (see the constructor). */
    [[nodiscard]] bool linesChecked() const { return lines_checked_; }

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
    bool lines_checked_ = false;
};

}  // namespace hif
