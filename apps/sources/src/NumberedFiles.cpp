// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   NumberedFiles.cpp
 * @brief  A folder's files named by their number.
 */
#include "NumberedFiles.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

namespace fs = std::filesystem;

namespace hif::apps
{
NumberedFiles numberedFiles(const std::string& folder, const std::vector<std::string>& extensions)
{
    NumberedFiles out;
    // Candidates: a stem that is a number of up to 8 digits after a prefix without digits or
    // dots (none, "scans_", "frame"), with one of the extensions.
    struct Candidate
    {
        std::string prefix;
        std::size_t number;
        std::string path;
    };
    std::vector<Candidate> candidates;
    for (const auto& e : fs::directory_iterator(folder))
    {
        const std::string stem = e.path().stem().string();
        const auto first_digit = stem.find_last_not_of("0123456789") + 1;  // npos + 1 = 0
        const std::string prefix = stem.substr(0, first_digit), digits = stem.substr(first_digit);
        const bool numbered =
            !digits.empty() && digits.size() <= 8 &&
            std::none_of(prefix.begin(), prefix.end(),
                         [](unsigned char c) { return std::isdigit(c) || c == '.'; });
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() && numbered &&
            std::find(extensions.begin(), extensions.end(), ext) != extensions.end())
            candidates.push_back({prefix, std::stoul(digits), e.path().string()});
        else
            out.other.push_back(e.path().filename().string());
    }
    // The scans: those named by their number alone, else those of one prefix shared by all
    // (FAST-LIO's scans_12.pcd); anything else is not a scan.
    const bool bare = std::any_of(candidates.begin(), candidates.end(),
                                  [](const Candidate& c) { return c.prefix.empty(); });
    const bool one_prefix =
        !candidates.empty() &&
        std::all_of(candidates.begin(), candidates.end(),
                    [&](const Candidate& c) { return c.prefix == candidates.front().prefix; });
    for (Candidate& c : candidates)
        if (bare ? c.prefix.empty() : one_prefix)
            out.files.emplace_back(c.number, std::move(c.path));
        else
            out.other.push_back(fs::path(c.path).filename().string());
    std::sort(out.files.begin(), out.files.end());
    std::sort(out.other.begin(), out.other.end());
    for (std::size_t k = 1; k < out.files.size(); ++k)
        if (out.files[k].first == out.files[k - 1].first)
            throw std::runtime_error("'" + folder + "' holds two files of scan " +
                                     std::to_string(out.files[k].first) + ": " +
                                     fs::path(out.files[k - 1].second).filename().string() +
                                     " and " + fs::path(out.files[k].second).filename().string());
    return out;
}

TimedFiles timedFiles(const std::string& folder, const std::vector<std::string>& extensions)
{
    TimedFiles out;
    const auto digits = [](const std::string& s)
    {
        return !s.empty() &&
               std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
    };
    for (const auto& e : fs::directory_iterator(folder))
    {
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() ||
            std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
            continue;
        const std::string stem = e.path().stem().string();
        const auto dot = stem.find('.');
        double seconds = 0.0;
        if (dot != std::string::npos && digits(stem.substr(0, dot)) && digits(stem.substr(dot + 1)))
            seconds = std::stod(stem);  // seconds.fraction
        else if (stem.size() == 19 && digits(stem))
            // Nanoseconds: whole seconds and the rest apart, so that no digit is lost to the
            // double before the point.
            seconds = double(std::stoull(stem.substr(0, 10))) + 1e-9 * std::stod(stem.substr(10));
        else
            continue;
        out.files.emplace_back(seconds, e.path().string());
    }
    std::sort(out.files.begin(), out.files.end());
    for (std::size_t k = 1; k < out.files.size(); ++k)
        if (out.files[k].first == out.files[k - 1].first)
            throw std::runtime_error("'" + folder + "' holds two clouds of one time: " +
                                     fs::path(out.files[k - 1].second).filename().string() +
                                     " and " + fs::path(out.files[k].second).filename().string());
    return out;
}

std::string listNames(const std::vector<std::string>& names)
{
    std::string s;
    for (std::size_t k = 0; k < names.size() && k < 5; ++k) s += (k ? ", " : "") + names[k];
    if (names.size() > 5) s += " and " + std::to_string(names.size() - 5) + " more";
    return s;
}

}  // namespace hif::apps
