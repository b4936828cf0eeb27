// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   IniSection.cpp
 * @brief  Strict reading of the map's .ini sections.
 */
#include "hif/IniSection.h"

#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace hif
{
namespace
{
std::string trim(const std::string& s)
{
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

/** The configuration's text and its file name ("" for text in memory), when it has them. */
std::optional<std::string> textOf(const mrpt::config::CConfigFileBase& c, std::string& file)
{
    if (const auto* t = dynamic_cast<const ConfigText*>(&c))
    {
        file = t->file();
        return t->text();
    }
    if (const auto* f = dynamic_cast<const mrpt::config::CConfigFile*>(&c))
    {
        file = f->getAssociatedFile();
        std::ifstream in(file);
        if (!in) return std::nullopt;
        std::stringstream ss;
        ss << in.rdbuf();
        return ss.str();
    }
    if (const auto* m = dynamic_cast<const mrpt::config::CConfigFileMemory*>(&c))
    {
        std::string s;
        m->getContent(s);
        return s;
    }
    return std::nullopt;
}

/** Edits to turn a into b. */
std::size_t distance(const std::string& a, const std::string& b)
{
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i)
    {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j)
        {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}
}  // namespace

ConfigText::ConfigText(const std::string& file) : file_(file)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error("config '" + file + "' cannot be read");
    std::stringstream ss;
    ss << in.rdbuf();
    text_ = ss.str();
    setContent(text_);
}

IniSection::IniSection(const mrpt::config::CConfigFileBase& config, std::string section)
    : config_(config), section_(std::move(section))
{
    std::string file;
    const std::optional<std::string> text = textOf(config_, file);
    where_ = (file.empty() ? "" : "'" + file + "', ") + "[" + section_ + "]";
    if (!text) return;
    lines_checked_ = true;
    std::istringstream in(*text);
    std::string current;
    int number = 0;
    for (std::string raw; std::getline(in, raw);)
    {
        ++number;
        const std::string line = trim(raw);
        if (line.empty() || line[0] == ';' || line[0] == '#' || line.rfind("//", 0) == 0) continue;
        const std::string at =
            (file.empty() ? "" : "'" + file + "', ") + "line " + std::to_string(number) + ": ";
        if (line[0] == '[')
        {
            const auto close = line.find(']');
            if (close == std::string::npos)
                throw std::invalid_argument(at + "section header '" + line +
                                            "' has no closing ']'");
            current = trim(line.substr(1, close - 1));
        }
        else if (current == section_ && line.find('=') == std::string::npos)
            throw std::invalid_argument(at + "'" + line + "' in [" + section_ +
                                        "] is not key = value");
    }
}

void IniSection::requireKnownKeys(const std::vector<std::string>& known) const
{
    std::vector<std::string> keys;
    config_.getAllKeys(section_, keys);
    for (const std::string& key : keys)
    {
        if (std::find(known.begin(), known.end(), key) != known.end()) continue;
        const auto nearest = std::min_element(known.begin(), known.end(),
                                              [&](const std::string& a, const std::string& b)
                                              { return distance(key, a) < distance(key, b); });
        std::string hint;
        if (nearest != known.end() && distance(key, *nearest) <= 3)
            hint = "; did you mean '" + *nearest + "'?";
        fail("unknown key '" + key + "'" + hint);
    }
}

bool IniSection::text(const char* key, std::string& out) const
{
    if (!config_.keyExists(section_, key)) return false;
    out = trim(config_.read_string(section_, key, "", false));
    return true;
}

void IniSection::fail(const std::string& problem) const
{
    throw std::invalid_argument(where_ + ": " + problem);
}

void IniSection::read(const char* key, double& value) const
{
    std::string s;
    if (!text(key, s)) return;
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE)
        fail(std::string(key) + " = '" + s + "' is not a number");
    value = v;
}

void IniSection::read(const char* key, bool& value) const
{
    std::string s;
    if (!text(key, s)) return;
    std::string l = s;
    std::transform(l.begin(), l.end(), l.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    if (l == "true" || l == "1" || l == "yes")
        value = true;
    else if (l == "false" || l == "0" || l == "no")
        value = false;
    else
        fail(std::string(key) + " = '" + s + "' is not true or false");
}

void IniSection::read(const char* key, uint64_t& value) const
{
    std::string s;
    if (!text(key, s)) return;
    if (s.empty() ||
        !std::all_of(s.begin(), s.end(), [](unsigned char ch) { return std::isdigit(ch); }))
        fail(std::string(key) + " = '" + s + "' is not a whole number >= 0");
    errno = 0;
    const unsigned long long v = std::strtoull(s.c_str(), nullptr, 10);
    if (errno == ERANGE) fail(std::string(key) + " = '" + s + "' is too large");
    value = v;
}

void IniSection::read(const char* key, std::vector<double>& values) const
{
    std::string s;
    if (!text(key, s)) return;
    values.clear();
    std::string item;
    auto flush = [&]
    {
        if (item.empty()) return;
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(item.c_str(), &end);
        if (end != item.c_str() + item.size() || errno == ERANGE || !std::isfinite(v))
            fail(std::string(key) + " = '" + s + "': '" + item + "' is not a number");
        values.push_back(v);
        item.clear();
    };
    for (const char ch : s)
    {
        if (ch == ' ' || ch == ',' || ch == '\t')
            flush();
        else
            item += ch;
    }
    flush();
    if (values.empty()) fail(std::string(key) + " is empty");
}

bool IniSection::has(const char* key) const { return config_.keyExists(section_, key); }

}  // namespace hif
