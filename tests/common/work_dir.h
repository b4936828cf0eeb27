// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   work_dir.h
 * @brief  Test helper: a fresh folder for what a test writes (the apps write up to a few
 *         hundred MB a run), removed when the test or test suite that made it passed, kept
 *         (and its path printed) when it failed, for a look at what was written.
 */
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

namespace hif::test
{
class WorkDir
{
public:
    explicit WorkDir(const std::filesystem::path& path) : path_(path.string())
    {
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    WorkDir(const WorkDir&) = delete;
    WorkDir& operator=(const WorkDir&) = delete;

    ~WorkDir()
    {
        if (failed())
        {
            std::cout << "[work folder kept: " << path_ << "]\n";
            return;
        }
        std::error_code ec;  // a folder that cannot be removed is not the test's failure
        std::filesystem::remove_all(path_, ec);
    }

    const std::string& path() const { return path_; }

private:
    /** A failure in the running test, or (from a fixture's TearDownTestSuite) in its suite. */
    static bool failed()
    {
        const auto* suite = ::testing::UnitTest::GetInstance()->current_test_suite();
        return ::testing::Test::HasFailure() || (suite != nullptr && suite->Failed());
    }

    std::string path_;
};

/** A WorkDir in the system's temporary folder, hif_<name>_<process id> (CTest runs two test
 *  processes at a time). */
inline WorkDir tempWorkDir(const std::string& name)
{
    return WorkDir(std::filesystem::temp_directory_path() /
                   ("hif_" + name + "_" + std::to_string(getpid())));
}

}  // namespace hif::test
