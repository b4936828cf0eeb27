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
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app_runner.h"
#include "hif/apps/Cli.h"
#include "hif/jobs/CleanCommandLine.h"
#include "hif/jobs/EvaluateCommandLine.h"
#include "hif/jobs/IcpSlamCommandLine.h"
#include "hif/jobs/KittiToRawlogCommandLine.h"
#include "hif/jobs/SyntheticKittiCommandLine.h"

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
        return {1, log.str() + Job::kTag + " error: " + hif::apps::errorMessage(e) + "\n"};
    }
}

/** The words of a command line as a POSIX shell splits them, for the tests' flags: blanks
 *  separate words, and single or double quotes group them. Throws std::invalid_argument on what
 *  a shell would read otherwise (escapes, variables, redirections, an open quote). */
inline std::vector<std::string> shellWords(const std::string& line)
{
    std::vector<std::string> words;
    std::string word;
    bool in_word = false;
    char quote = 0;
    for (const char c : line)
    {
        if (quote != 0)
        {
            if (c == quote)
                quote = 0;
            else
                word += c;
        }
        else if (c == '\'' || c == '"')
        {
            quote = c;
            in_word = true;
        }
        else if (c == ' ' || c == '\t' || c == '\n')
        {
            if (in_word) words.push_back(word);
            word.clear();
            in_word = false;
        }
        else if (std::string("\\$`<>|;&*?").find(c) != std::string::npos)
            throw std::invalid_argument("shellWords: '" + std::string(1, c) + "' in: " + line);
        else
        {
            word += c;
            in_word = true;
        }
    }
    if (quote != 0) throw std::invalid_argument("shellWords: an open quote in: " + line);
    if (in_word) words.push_back(word);
    return words;
}

/** `app args` run in process as its binary runs it (hif::apps::runCommandLine() with the
 *  app's command line): its exit code, and what it wrote on std::cout and std::cerr (the job's
 *  log, TCLAP's messages, the error line), interleaved, as runApp() gives them. Not in it: the
 *  progress line (on the C stream stderr), the signals' handling and the allocator's settings
 *  of main(); the tests of those run the programs. */
inline Result runInProcess(const std::string& app, const std::string& args)
{
    const std::vector<std::string> words = shellWords(args);
    const std::string program = kBin + "/" + app;  // argv[0] as the program's
    std::vector<const char*> argv{program.c_str()};
    for (const std::string& w : words) argv.push_back(w.c_str());
    const int argc = static_cast<int>(argv.size());
    argv.push_back(nullptr);

    std::stringstream text;
    struct Redirect
    {
        std::streambuf* out;
        std::streambuf* err;
        ~Redirect()
        {
            std::cout.rdbuf(out);
            std::cerr.rdbuf(err);
        }
    } redirect{std::cout.rdbuf(text.rdbuf()), std::cerr.rdbuf(text.rdbuf())};

    int code = 0;
    if (app == "hif-clean")
        code = apps::runCommandLine<jobs::CleanCommandLine>(argc, argv.data(), text, text);
    else if (app == "hif-eval")
        code = apps::runCommandLine<jobs::EvaluateCommandLine>(argc, argv.data(), text, text);
    else if (app == "hif-icp-slam")
        code = apps::runCommandLine<jobs::IcpSlamCommandLine>(argc, argv.data(), text, text);
    else if (app == "hif-synthetic-kitti")
        code = apps::runCommandLine<jobs::SyntheticKittiCommandLine>(argc, argv.data(), text, text);
    else if (app == "kitti2rawlog")
        code = apps::runCommandLine<jobs::KittiToRawlogCommandLine>(argc, argv.data(), text, text);
    else
        throw std::invalid_argument("runInProcess: no app " + app);
    return {code, text.str()};
}

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
