// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   synthetic_suite.h
 * @brief  Test helper: a test suite whose tests share one short synthetic sequence and its
 *         rawlog, in a work folder (one per process: CTest runs two test processes at a time)
 *         that goes when the suite passes. Under CTest the sequence is copied from the ones the
 *         fixture `hif_sequences` made once for the run (make_sequences.cpp, folder in
 *         $HIF_TEST_SEQUENCES); run on its own, the suite makes it (in process, the same way).
 */
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "app_runner.h"
#include "job_runner.h"

namespace hif::test
{
/** A synthetic sequence of `scans` scans (the generator's defaults) in `dir`/seq and its
 *  conversion in `dir`/scans.rawlog. */
inline Result makeSequence(const std::string& dir, long long scans)
{
    const auto g = synthesize(dir + "/seq", scans);
    const auto c = g.code == 0 ? toRawlog(dir + "/seq", dir + "/scans.rawlog") : g;
    return {c.code, g.output + (g.code == 0 ? c.output : "")};
}

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
        const char* shared = std::getenv("HIF_TEST_SEQUENCES");
        const std::string made =
            shared ? std::string(shared) + "/" + std::to_string(Suite::kScans) : "";
        if (!made.empty() && std::filesystem::exists(made + "/scans.rawlog"))
        {
            std::error_code ec;
            std::filesystem::copy(made + "/seq", root_ + "/seq",
                                  std::filesystem::copy_options::recursive, ec);
            if (!ec)
                std::filesystem::copy_file(made + "/scans.rawlog", root_ + "/" + Suite::kRawlog,
                                           ec);
            setup_ok_ = !ec;
            setup_log_ = "copying " + made + ": " + ec.message();
            return;
        }
        const auto r = makeSequence(root_, Suite::kScans);
        if (r.code == 0 && std::string(Suite::kRawlog) != "scans.rawlog")
            std::filesystem::rename(root_ + "/scans.rawlog", root_ + "/" + Suite::kRawlog);
        setup_ok_ = r.code == 0;
        setup_log_ = r.output;
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
