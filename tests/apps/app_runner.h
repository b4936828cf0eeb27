// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   app_runner.h
 * @brief  Test helper: run an app's program as a user does (stdout and stderr to one log), check
 *         that a run failed with a message, read JSON, make a work folder.
 */
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "work_dir.h"

namespace hif::test
{
inline const std::string kBin = HIF_APPS_DIR;
inline const std::string kWork = HIF_TEST_WORK_DIR;

struct Result
{
    int code;
    std::string output;  // stdout and stderr, as they were interleaved
};

inline Result runApp(const std::string& app, const std::string& args)
{
    // One log per process: CTest runs two test processes at a time.
    const std::string log = kWork + "/last_command_" + std::to_string(getpid()) + ".log";
    const std::string cmd = kBin + "/" + app + " " + args + " > " + log + " 2>&1";
    const int status = std::system(cmd.c_str());
    std::stringstream ss;
    {
        std::ifstream f(log);
        ss << f.rdbuf();
    }
    std::filesystem::remove(log);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, ss.str()};
}

/** The run failed with a message naming the problem (`message` in its output), without a
 *  backtrace. */
inline void expectError(const Result& r, const std::string& message)
{
    EXPECT_NE(r.code, 0) << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << "expected '" << message << "' in:\n"
                                                         << r.output;
    EXPECT_EQ(r.output.find("Call stack"), std::string::npos) << "a backtrace:\n" << r.output;
}

inline nlohmann::json readJson(const std::string& file)
{
    std::ifstream f(file);
    EXPECT_TRUE(f.good()) << file;
    return nlohmann::json::parse(f);
}

/** A fresh folder `name` in the tests' work folder, removed if the test passes. */
inline WorkDir workDir(const std::string& name) { return WorkDir(kWork + "/" + name); }

inline std::string bytesOf(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
}

}  // namespace hif::test
