// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_params.cpp
 * @brief  GridGeometry and Params: defaults (the paper's values), validation messages, and the
 *         field tables behind .ini files, serialization and equality.
 */
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>

#include "field_helpers.h"
#include "hif/Params.h"

using hif::GridGeometry;
using hif::Params;

TEST(Params, DefaultsAreThePapersAndValid)
{
    const Params p;
    EXPECT_DOUBLE_EQ(GridGeometry().pillar_size, 1.0);  // Sec. IV-A
    EXPECT_NO_THROW(GridGeometry().validate());
    EXPECT_DOUBLE_EQ(p.p_min, 0.1);  // Eq. 17
    EXPECT_DOUBLE_EQ(p.p_max, 0.9);
    EXPECT_GT(p.alpha, 0.5);  // Eq. 6
    EXPECT_LT(p.beta, 0.5);
    EXPECT_TRUE(p.low_height_preservation);
    EXPECT_NO_THROW(p.validate());
}

namespace
{
template <typename S>
void expectRejected(const std::function<void(S&)>& change, const std::string& field)
{
    S p;
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
    using G = GridGeometry;
    expectRejected<G>([](G& g) { g.pillar_size = 0; }, "pillar_size");
    expectRejected<G>([](G& g) { g.pillar_size = -1; }, "pillar_size");
    expectRejected<G>([nan](G& g) { g.pillar_size = nan; }, "pillar_size");
    expectRejected<G>([nan](G& g) { g.origin_x = nan; }, "origin_x");
    expectRejected<G>([](G& g) { g.origin_y = std::numeric_limits<double>::infinity(); },
                      "origin_y");
    expectRejected<G>([](G& g) { g.height_resolution = 0; }, "height_resolution");
    // An origin whose own pillar index does not fit in int32 would leave every point outside
    // the grid; UTM-sized ones (millions of metres) are fine.
    expectRejected<G>([](G& g) { g.origin_x = 3e9; }, "origin_x");
    expectRejected<G>(
        [](G& g)
        {
            g.pillar_size = 0.001;
            g.origin_y = -5.8e6;
        },
        "origin_y");
    G utm;
    utm.origin_x = 630000;
    utm.origin_y = 5.8e6;
    EXPECT_NO_THROW(utm.validate());
    expectRejected<Params>([](Params& p) { p.merge_gap = -0.1; }, "merge_gap");
    expectRejected<Params>([](Params& p) { p.interval_padding = -0.1; }, "interval_padding");
    expectRejected<Params>([](Params& p) { p.alpha = 0.5; }, "alpha");
    expectRejected<Params>([](Params& p) { p.alpha = 1.0; }, "alpha");
    expectRejected<Params>([](Params& p) { p.beta = 0.5; }, "beta");
    expectRejected<Params>([](Params& p) { p.beta = 0.0; }, "beta");
    expectRejected<Params>([](Params& p) { p.p_min = 0.0; }, "p_min");
    expectRejected<Params>([](Params& p) { p.p_max = 1.0; }, "p_max");
    expectRejected<Params>(
        [](Params& p)
        {
            p.p_min = 0.6;
            p.p_max = 0.4;
        },
        "p_min");
    expectRejected<Params>([](Params& p) { p.p_empty_init = 0.95; }, "p_empty_init");
    expectRejected<Params>([](Params& p) { p.static_threshold = 1.0; }, "static_threshold");
    expectRejected<Params>([](Params& p) { p.max_intervals_per_pillar = 0; },
                           "max_intervals_per_pillar");
}

TEST(Params, MessagesSayWhatIsAllowed)
{
    Params p;
    p.alpha = 0.5;
    try
    {
        p.validate();
        FAIL() << "alpha 0.5 accepted";
    }
    catch (const std::invalid_argument& e)
    {
        EXPECT_STREQ(e.what(), "hif::Params: invalid alpha = 0.5 (must be in (0.5, 1))");
    }
    // A check across the grid and the parameters: the see-through window is bounded.
    GridGeometry g;
    g.pillar_size = 0.1;
    p = Params();
    p.see_through_range = 300.0;  // valid alone, but 3000 pillars wide
    EXPECT_NO_THROW(p.validate());
    EXPECT_THROW(p.validateWith(g), std::invalid_argument);
    g.pillar_size = 0.2;
    EXPECT_NO_THROW(p.validateWith(g));
}

namespace
{
/** For every field of S: its name is unique, it has a doc, and changing it alone (to another
 *  valid value) makes the struct unequal to the default and keeps it valid. A new field gets
 *  this for free from its line in the table. */
template <typename S>
void checkEveryField()
{
    std::set<std::string> names;
    std::size_t count = 0;
    hif::forEachField<S>(
        [&](const hif::Field<S>& f, auto member)
        {
            ++count;
            EXPECT_TRUE(names.insert(f.name).second) << "duplicate name " << f.name;
            EXPECT_GT(std::string(f.doc).size(), 5u) << f.name << " has no doc";
            S s;
            hif::test::changeField(s, f, member);
            EXPECT_NE(s, S()) << f.name << " is not compared";
            EXPECT_NO_THROW(s.validate()) << f.name;
        });
    EXPECT_EQ(count, S::fields().size());
}
}  // namespace

TEST(FieldTables, EveryFieldIsNamedComparedAndValid)
{
    checkEveryField<GridGeometry>();
    checkEveryField<Params>();
    // All changed at once (what the serialization and .ini round trips use) is valid too.
    const Params all = hif::test::everyFieldChanged<Params>();
    EXPECT_NO_THROW(all.validateWith(hif::test::everyFieldChanged<GridGeometry>()));
    hif::forEachField<Params>([&](const hif::Field<Params>& f, auto member)
                              { EXPECT_NE(all.*member, Params().*member) << f.name; });
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

// The field tables' compile-time check (in Params.h and GridGeometry.h) counts members as brace
// initialization does, so that a member added to a settings struct without its row stops the
// build; here, that it counts right.
namespace
{
struct ThreeMembers
{
    double a = 1.0;
    bool b = true;
    std::size_t c = 2;
};
struct FourMembers
{
    double a = 1.0;
    bool b = true;
    std::size_t c = 2;
    double d = 0.0;
};
}  // namespace
static_assert(hif::memberCount<ThreeMembers>() == 3);
static_assert(hif::memberCount<FourMembers>() == 4);
