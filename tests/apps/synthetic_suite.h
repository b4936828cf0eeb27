// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   synthetic_suite.h
 * @brief  Test helper: a test suite whose tests share one short synthetic sequence and its
 *         rawlog, made once for the suite (in process), in a work folder (one per process: CTest
 *         runs two test processes at a time) that goes when the suite passes.
 */
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "app_runner.h"
#include "job_runner.h"

namespace hif::test
{
/** The suite `Suite`, which names its folder (`Suite::kFolder`), its number of scans
 *  (`Suite::kScans`) and its rawlog (`Suite::kRawlog`): `root_` holds `seq/` (the sequence) and
 *  the rawlog (its conversion). */
template <typename Suite>
class SyntheticSuite : public ::testing::Test
{
protected:
    static void SetUpTestSuite()
    {
        work_ = std::make_unique<WorkDir>(kWork + "/" + Suite::kFolder + "_" +
                                          std::to_string(getpid()));
        root_ = work_->path();
        const auto g = synthesize(root_ + "/seq", Suite::kScans);
        const auto c = g.code == 0 ? toRawlog(root_ + "/seq", root_ + "/" + Suite::kRawlog) : g;
        setup_ok_ = g.code == 0 && c.code == 0;
        setup_log_ = g.output + c.output;
    }
    // A failed set-up fails every test (gtest would report them as skipped).
    void SetUp() override { ASSERT_TRUE(setup_ok_) << setup_log_; }
    // The folder goes unless a test failed.
    static void TearDownTestSuite() { work_.reset(); }

    /** The shipped kitti.ini with `from` replaced by `to`, written to `name` in the suite's
     *  folder; returns its path. */
    static std::string ini(const std::string& from, const std::string& to,
                           const std::string& name = "bad.ini")
    {
        std::ifstream in(HIF_SHARE_DIR "/config/kitti.ini");
        std::stringstream ss;
        ss << in.rdbuf();
        std::string text = ss.str();
        const auto at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos) text.replace(at, from.size(), to);
        const std::string file = root_ + "/" + name;
        std::ofstream(file) << text;
        return file;
    }

    /** A copy of the sequence, in a fresh folder `name` of the suite. */
    static std::string copyOfSequence(const std::string& name)
    {
        const std::string d = root_ + "/" + name;
        std::filesystem::remove_all(d);
        std::filesystem::copy(root_ + "/seq", d, std::filesystem::copy_options::recursive);
        return d;
    }

    static inline std::unique_ptr<WorkDir> work_;
    static inline std::string root_, setup_log_;
    static inline bool setup_ok_ = false;
};

}  // namespace hif::test
