// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Cli.cpp
 * @brief  Progress line, memory, statistics, folders.
 */
#include "hif/apps/Cli.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numeric>
#include <stdexcept>

namespace hif::apps
{
double peakRssMiB()
{
    std::ifstream f("/proc/self/status");
    for (std::string line; std::getline(f, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;  // kB
    return 0.0;
}

TimeStats timeStats(std::vector<double> v)
{
    TimeStats s;
    if (v.empty()) return s;
    std::sort(v.begin(), v.end());
    auto rank = [&](double q)
    {
        const auto k = static_cast<std::size_t>(std::ceil(q * double(v.size())));
        return v[std::min(v.size() - 1, k == 0 ? 0 : k - 1)];
    };
    s.median = rank(0.5);
    s.p90 = rank(0.9);
    s.max = v.back();
    s.mean = std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
    return s;
}

Progress::Progress(std::string prefix, std::string what, std::size_t total, bool enabled)
    : prefix_(std::move(prefix)),
      what_(std::move(what)),
      total_(total),
      enabled_(enabled),
      tty_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      last_(start_)
{
}

void Progress::print(std::size_t done, bool final_line)
{
    // What was written to stdout first comes first, also when both go to one file.
    std::cout.flush();
    std::fflush(stdout);
    printed_ = true;
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double rate = secs > 0 ? double(done) / secs : 0.0;
    const char* end = (final_line || !tty_) ? "\n" : "";
    if (total_ == 0)
    {
        std::fprintf(stderr, "%s%s %s %zu scans, %.1f scans/s%s", tty_ ? "\r" : "", prefix_.c_str(),
                     what_.c_str(), done, rate, end);
    }
    else
    {
        constexpr int kWidth = 30;
        const int filled = static_cast<int>(kWidth * double(done) / double(total_));
        std::string bar(static_cast<std::size_t>(filled), '#');
        bar.resize(kWidth, '.');
        std::fprintf(stderr, "%s%s %s [%s] %zu/%zu scans, %.1f scans/s%s", tty_ ? "\r" : "",
                     prefix_.c_str(), what_.c_str(), bar.c_str(), done, total_, rate, end);
    }
    std::fflush(stderr);
}

void Progress::update(std::size_t done)
{
    if (!enabled_ || finished_) return;
    done_ = done;
    const auto now = std::chrono::steady_clock::now();
    if (tty_)
    {
        if (now - last_ < std::chrono::milliseconds(200) && done < total_) return;
        last_ = now;
        print(done, false);
    }
    else if (total_ == 0)
    {
        if (now - last_ < std::chrono::seconds(10)) return;  // unknown length: every 10 s
        last_ = now;
        print(done, false);
    }
    else
    {
        const std::size_t decile = done * 10 / total_;
        if (decile == last_decile_) return;
        last_decile_ = decile;
        print(done, false);
    }
}

void Progress::finish()
{
    if (!enabled_ || finished_) return;
    finished_ = true;
    // On a terminal, the last state stays; in a log, a run too short for any line, or of
    // unknown length, still says how it went.
    if (tty_ || !printed_ || total_ == 0) print(done_, true);
}

void makeDirs(const std::string& dir)
{
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw std::runtime_error("cannot create folder '" + dir + "': " + ec.message());
}

void refuseToOverwrite(const std::string& file, bool overwrite, const std::string& flag)
{
    std::error_code ec;
    if (!overwrite &&
        std::filesystem::symlink_status(file, ec).type() != std::filesystem::file_type::not_found)
        throw std::runtime_error("'" + file + "' already exists; pass " + flag + " to replace it");
}

}  // namespace hif::apps
