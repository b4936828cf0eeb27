// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Cli.h
 * @brief  Small helpers shared by the apps: progress line, memory, timing statistics, output
 *         folders.
 */
#pragma once

#include <mrpt/core/exceptions.h>

#include <chrono>
#include <cstddef>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "hif/apps/Interrupt.h"

namespace hif::apps
{
using Clock = std::chrono::steady_clock;

/** Milliseconds since `t0`. */
[[nodiscard]] inline double msSince(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/** Peak resident memory of this process so far (VmHWM), MiB; 0 if unknown. */
[[nodiscard]] double peakRssMiB();

/** Median, 90th percentile and maximum of a sample (nearest-rank); zeros when empty. */
struct TimeStats
{
    double median = 0, p90 = 0, max = 0, mean = 0;
};
[[nodiscard]] TimeStats timeStats(std::vector<double> v);

/** A one-line progress report on stderr with scans per second: rewritten in place on a
 *  terminal, one line every 10% otherwise (logs, CI). `total` 0 means unknown length (then
 *  no bar; off a terminal, a line every 10 s). */
class Progress
{
public:
    Progress(std::string prefix, std::string what, std::size_t total, bool enabled = true);
    void update(std::size_t done);
    void finish();

private:
    std::string prefix_, what_;
    std::size_t total_;
    bool enabled_, tty_;
    std::chrono::steady_clock::time_point start_, last_;
    std::size_t last_decile_ = 0;
    std::size_t done_ = 0;
    bool finished_ = false;
    bool printed_ = false;
    void print(std::size_t done, bool final_line);
};

/** `value` of integer flag `flag` (e.g. "--threads"), which must lie in [lo, hi] (flags are read
 *  as signed numbers, so that a negative one is an error, not a wrapped huge one); throws
 *  std::runtime_error naming the flag otherwise. */
inline long long flagInRange(long long value, const std::string& flag, long long lo, long long hi)
{
    if (value < lo || value > hi)
        throw std::runtime_error(flag + " " + std::to_string(value) + " is not in [" +
                                 std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return value;
}

/** `dir` without a trailing separator ("out/" -> "out"), so that paths join cleanly. */
[[nodiscard]] inline std::string cleanDir(const std::string& dir)
{
    std::string d = dir;
    while (d.size() > 1 && d.back() == '/') d.pop_back();
    return d;
}

/** Creates `dir` (and parents). Throws std::runtime_error naming it on failure. */
void makeDirs(const std::string& dir);

/** Throws std::runtime_error if `file` exists and `overwrite` is false: nothing the user has
 *  is replaced without being asked. */
void refuseToOverwrite(const std::string& file, bool overwrite, const std::string& flag);

/** The text of an MRPT exception without its frames and backtrace: for one that went through
 *  MRPT several times (a wrapped exception), the innermost message, which says what was wrong.
 *  Any other text is returned as it is. */
inline std::string innermostMessage(std::string m)
{
    const auto at = m.rfind("Message:");
    if (m.find("==== MRPT exception ====") != std::string::npos && at != std::string::npos)
    {
        m = m.substr(at + 8);
        m = m.substr(0, m.find('\n'));
    }
    const auto b = m.find_first_not_of(' ');
    return b == std::string::npos ? m : m.substr(b);
}

/** What an error says, without the call stack MRPT adds when an exception passes through its
 *  code (the user's mistake, not a crash: the message names the file and the problem). */
inline std::string errorMessage(const std::exception& e)
{
    if (const auto* wrapped = dynamic_cast<const mrpt::ExceptionWithCallBackBase*>(&e))
        return innermostMessage(wrapped->originalWhat);
    return e.what();
}

/** The line an app ends with when `e` stopped it: "<tag> error: <what>" (errorMessage()). */
inline std::string errorLine(const char* tag, const std::exception& e)
{
    return std::string(tag) + " error: " + errorMessage(e) + "\n";
}

/** An app's command line run: `argv` parsed into a `CommandLine` (which holds a TCLAP `cmd`
 *  with the app's flags and gives its `Job`'s options()), and the job run with its log on
 *  `out`; any exception becomes its errorLine() on `err` and code 1. MRPT's TCLAP reports
 *  a bad command line and --help / --version itself (on std::cout and std::cerr) and returns
 *  false from parse(): then the job does not run, and the code is 0 for --help / --version, 1
 *  for a bad command line. Returns the app's exit code. The tests run the apps this way in
 *  process (tests/apps/job_runner.h). */
template <typename CommandLine>
int runCommandLine(int argc, const char* const* argv, std::ostream& out, std::ostream& err)
{
    using Job = typename CommandLine::Job;
    try
    {
        CommandLine cli;
        if (!cli.cmd.parse(argc, const_cast<const char**>(argv)))
        {
            for (int i = 1; i < argc; ++i)
            {
                const std::string a = argv[i];
                if (a == "-h" || a == "--help" || a == "--version") return 0;
            }
            return 1;
        }
        Job(cli.options()).run(out);
        return 0;
    }
    catch (const std::exception& e)
    {
        endHereIfStopped();
        err << errorLine(Job::kTag, e);
        return 1;
    }
}

/** The whole main() of an app: from the start, a run stopped by SIGINT, SIGTERM or SIGHUP
 *  removes its partial outputs (removePartialsOnInterrupt()); then runCommandLine() on
 *  std::cout and std::cerr. */
template <typename CommandLine>
int cliMain(int argc, char** argv)
{
    removePartialsOnInterrupt(CommandLine::Job::kTag);
    const int code = runCommandLine<CommandLine>(argc, argv, std::cout, std::cerr);
    if (code != 0) endHereIfStopped();
    return code;
}

}  // namespace hif::apps
