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
    // Candidates: <prefix><seconds>.<fraction> or <prefix><19-digit nanoseconds>, the prefix
    // without digits or dots (pcl_ros's tools take one), shared by all.
    struct Candidate
    {
        std::string prefix, seconds, fraction, path;
    };
    std::vector<Candidate> found;
    for (const auto& e : fs::directory_iterator(folder))
    {
        const std::string ext = e.path().extension().string();
        if (!e.is_regular_file() ||
            std::find(extensions.begin(), extensions.end(), ext) == extensions.end())
            continue;
        const std::string stem = e.path().stem().string();
        const auto start = stem.find_first_of("0123456789");
        if (start == std::string::npos || stem.substr(0, start).find('.') != std::string::npos)
            continue;
        const std::string time = stem.substr(start);
        const auto dot = time.find('.');
        // Up to 12 digits of seconds (a clock's, or the time since a recording started).
        if (dot != std::string::npos && dot <= 12 && digits(time.substr(0, dot)) &&
            digits(time.substr(dot + 1)))
            found.push_back({stem.substr(0, start), time.substr(0, dot), time.substr(dot + 1),
                             e.path().string()});
        else if (time.size() == 19 && digits(time))
            found.push_back(
                {stem.substr(0, start), time.substr(0, 10), time.substr(10), e.path().string()});
    }
    if (found.empty() ||
        std::any_of(found.begin(), found.end(),
                    [&](const Candidate& c) { return c.prefix != found.front().prefix; }))
        return out;
    // The fraction: decimal digits (ROS 1's bag_to_pcd pads the nanoseconds to 9 digits, other
    // tools print a fixed number of decimals), unless the fractions have different lengths and
    // the longest has 9 digits: ROS 2's pointcloud_to_pcd writes the nanoseconds unpadded
    // (<sec>.<nanosec>: 5803421 is 0.005803421 s), and most of them have 9.
    std::size_t shortest = 9, longest = 0;
    for (const Candidate& c : found)
    {
        shortest = std::min(shortest, c.fraction.size());
        longest = std::max(longest, c.fraction.size());
    }
    const bool nanoseconds = longest == 9 && shortest < 9;
    for (const Candidate& c : found)
    {
        // (With nanoseconds, no fraction has more than 9 digits.)
        const double fraction =
            nanoseconds ? 1e-9 * double(std::stoull(c.fraction)) : std::stod("0." + c.fraction);
        out.files.emplace_back(double(std::stoull(c.seconds)) + fraction, c.path);
    }
    out.nanoseconds_unpadded = nanoseconds;
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
