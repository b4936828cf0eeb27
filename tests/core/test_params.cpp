// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_params.cpp
 * @brief  Params defaults (the paper's values) and validation messages.
 */
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "hif/Params.h"

using hif::Params;

TEST(Params, DefaultsAreThePapersAndValid)
{
    const Params p;
    EXPECT_DOUBLE_EQ(p.pillar_size, 1.0);  // Sec. IV-A
    EXPECT_DOUBLE_EQ(p.p_min, 0.1);        // Eq. 17
    EXPECT_DOUBLE_EQ(p.p_max, 0.9);
    EXPECT_GT(p.alpha, 0.5);  // Eq. 6
    EXPECT_LT(p.beta, 0.5);
    EXPECT_TRUE(p.low_height_preservation);
    EXPECT_NO_THROW(p.validate());
}

namespace
{
void expectRejected(const std::function<void(Params&)>& change, const std::string& field)
{
    Params p;
    change(p);
    try
    {
        p.validate();
        FAIL() << "validate() accepted a bad " << field;
    }
    catch (const std::invalid_argument& e)
    {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(field), std::string::npos) << msg;
        EXPECT_NE(msg.find(" = "), std::string::npos) << "message names no value: " << msg;
    }
}
}  // namespace

TEST(Params, EachBadFieldIsNamed)
{
    const double nan = std::numeric_limits<double>::quiet_NaN();
    expectRejected([](Params& p) { p.pillar_size = 0; }, "pillar_size");
    expectRejected([](Params& p) { p.pillar_size = -1; }, "pillar_size");
    expectRejected([nan](Params& p) { p.pillar_size = nan; }, "pillar_size");
    expectRejected([nan](Params& p) { p.origin_x = nan; }, "origin_x");
    expectRejected([](Params& p) { p.origin_y = std::numeric_limits<double>::infinity(); },
                   "origin_y");
    expectRejected([](Params& p) { p.height_resolution = 0; }, "height_resolution");
    expectRejected([](Params& p) { p.merge_gap = -0.1; }, "merge_gap");
    expectRejected([](Params& p) { p.interval_padding = -0.1; }, "interval_padding");
    expectRejected([](Params& p) { p.alpha = 0.5; }, "alpha");
    expectRejected([](Params& p) { p.alpha = 1.0; }, "alpha");
    expectRejected([](Params& p) { p.beta = 0.5; }, "beta");
    expectRejected([](Params& p) { p.beta = 0.0; }, "beta");
    expectRejected([](Params& p) { p.p_min = 0.0; }, "p_min");
    expectRejected([](Params& p) { p.p_max = 1.0; }, "p_max");
    expectRejected(
        [](Params& p)
        {
            p.p_min = 0.6;
            p.p_max = 0.4;
        },
        "p_min");
    expectRejected([](Params& p) { p.p_empty_init = 0.95; }, "p_empty_init");
    expectRejected([](Params& p) { p.static_threshold = 1.0; }, "static_threshold");
    expectRejected([](Params& p) { p.max_intervals_per_pillar = 0; }, "max_intervals_per_pillar");
}

TEST(Params, EqualityIsFieldByField)
{
    Params a, b;
    EXPECT_EQ(a, b);
    b.merge_gap = 0.2;
    EXPECT_NE(a, b);
    b = a;
    b.low_height_preservation = false;
    EXPECT_NE(a, b);
}
