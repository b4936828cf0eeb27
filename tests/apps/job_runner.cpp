// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   job_runner.cpp
 * @brief  runInProcess() and shellWords() of job_runner.h: the apps' five command lines
 *         compiled once for the test program, not in each test file.
 */
#include "job_runner.h"

#include <iostream>
#include <stdexcept>

#include "hif/jobs/CleanCommandLine.h"
#include "hif/jobs/EvaluateCommandLine.h"
#include "hif/jobs/IcpSlamCommandLine.h"
#include "hif/jobs/KittiToRawlogCommandLine.h"
#include "hif/jobs/SyntheticKittiCommandLine.h"

namespace hif::test
{
std::vector<std::string> shellWords(const std::string& line)
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
            else if (quote == '"' && std::string("\\$`").find(c) != std::string::npos)
                throw std::invalid_argument("shellWords: '" + std::string(1, c) + "' in: " + line);
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

Result runInProcess(const std::string& app, const std::string& args)
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

}  // namespace hif::test
