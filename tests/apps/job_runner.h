// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   job_runner.h
 * @brief  Test helper: run an app's job in process, as the app would run it (its log, and an
 *         error as the app's "<tag> error: <what>" line with a non-zero code), with the options
 *         of the app's flags, or with its command line (runInProcess()); `Result` and
 *         expectError() as for the apps run as programs.
 */
#pragma once

#include <exception>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "app_runner.h"
#include "hif/apps/Cli.h"
#include "hif/jobs/Clean.h"
#include "hif/jobs/Evaluate.h"
#include "hif/jobs/IcpSlam.h"
#include "hif/jobs/KittiToRawlog.h"
#include "hif/jobs/SyntheticKitti.h"

namespace hif::test
{
/** `job.run(log)` in process: code 0 and its log, or code 1 and its log with the error line
 *  its app would print. */
template <typename Job>
Result runJob(const Job& job)
{
    std::ostringstream log;
    try
    {
        job.run(log);
        return {0, log.str()};
    }
    catch (const std::exception& e)
    {
        return {1, log.str() + hif::apps::errorLine(Job::kTag, e)};
    }
}

/** The words of a command line as a POSIX shell splits them, for the tests' flags: blanks
 *  separate words, and single or double quotes group them. Throws std::invalid_argument on what
 *  a shell would read otherwise (escapes, variables, redirections, an open quote). */
std::vector<std::string> shellWords(const std::string& line);

/** `app args` run in process as its binary runs it (hif::apps::runCommandLine() with the
 *  app's command line, argv[0] the program's path): its exit code, and what it wrote on
 *  std::cout and std::cerr (the job's log, TCLAP's messages, the error line), interleaved, as
 *  runApp() gives them. Not in it: the progress line (on the C stream stderr), the signals'
 *  handling and the allocator's settings of main(); the tests of those run the programs.
 *  (job_runner.cpp: the five command lines are compiled there once.) */
Result runInProcess(const std::string& app, const std::string& args);

/** hif-clean -i `input` -o `output` -q, with what `set` changes. */
inline Result clean(const std::string& input, const std::string& output,
                    const std::function<void(jobs::CleanOptions&)>& set = {})
{
    jobs::CleanOptions o;
    o.input = input;
    o.output = output;
    o.show_progress = false;
    if (set) set(o);
    return runJob(jobs::Clean(o));
}

/** hif-synthetic-kitti -o `output` -n `scans`, with what `set` changes. */
inline Result synthesize(const std::string& output, long long scans,
                         const std::function<void(jobs::SyntheticKittiOptions&)>& set = {})
{
    jobs::SyntheticKittiOptions o;
    o.output = output;
    o.scans = scans;
    o.show_progress = false;
    if (set) set(o);
    return runJob(jobs::SyntheticKitti(o));
}

/** kitti2rawlog -i `input` -o `output` -q, with what `set` changes. */
inline Result toRawlog(const std::string& input, const std::string& output,
                       const std::function<void(jobs::KittiToRawlogOptions&)>& set = {})
{
    jobs::KittiToRawlogOptions o;
    o.input = input;
    o.output = output;
    o.show_progress = false;
    if (set) set(o);
    return runJob(jobs::KittiToRawlog(o));
}

/** hif-eval --labels `labels` --predictions `predictions` -q, with what `set` changes. */
inline Result evaluate(const std::string& labels, const std::string& predictions,
                       const std::function<void(jobs::EvaluateOptions&)>& set = {})
{
    jobs::EvaluateOptions o;
    o.labels = labels;
    o.predictions = predictions;
    o.per_scan = false;
    if (set) set(o);
    return runJob(jobs::Evaluate(o));
}

/** hif-icp-slam -i `input` -o `output` -q, with what `set` changes. */
inline Result icpSlam(const std::string& input, const std::string& output,
                      const std::function<void(jobs::IcpSlamOptions&)>& set = {})
{
    jobs::IcpSlamOptions o;
    o.input = input;
    o.output = output;
    o.show_progress = false;
    if (set) set(o);
    return runJob(jobs::IcpSlam(o));
}

}  // namespace hif::test
