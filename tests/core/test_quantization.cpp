// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   test_quantization.cpp
 * @brief  Eq. 1-3: floor quantization (negative coordinates), exact keys, hash mixing.
 */
#include <gtest/gtest.h>

#include <set>

#include "hif/GridGeometry.h"
#include "hif/PillarIndex.h"

using namespace hif;

TEST(Quantization, FloorIsRightForNegativeCoordinates)
{
    EXPECT_EQ(*quantize(-0.01, 0.0, 1.0), -1);
    EXPECT_EQ(*quantize(-1.0, 0.0, 1.0), -1);
    EXPECT_EQ(*quantize(-1.0001, 0.0, 1.0), -2);
    EXPECT_EQ(*quantize(0.0, 0.0, 1.0), 0);
    EXPECT_EQ(*quantize(0.999, 0.0, 1.0), 0);
    EXPECT_EQ(*quantize(1.0, 0.0, 1.0), 1);
    // Eq. 2: pillar m covers [x_o + m dx, x_o + (m+1) dx).
    EXPECT_EQ(*quantize(10.2, 10.5, 0.5), -1);
    EXPECT_EQ(*quantize(10.5, 10.5, 0.5), 0);
    EXPECT_EQ(*quantize(10.99, 10.5, 0.5), 0);
    EXPECT_EQ(*quantize(11.0, 10.5, 0.5), 1);
}

TEST(Quantization, OutOfRangeAndNonFiniteAreRejected)
{
    EXPECT_FALSE(quantize(1e12, 0.0, 1.0).has_value());
    EXPECT_FALSE(quantize(-1e12, 0.0, 1.0).has_value());
    EXPECT_FALSE(quantize(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0).has_value());
    EXPECT_FALSE(quantize(std::numeric_limits<double>::infinity(), 0.0, 1.0).has_value());
}

TEST(PillarKey, PackIsExactAndInjective)
{
    std::set<uint64_t> keys;
    for (int m = -50; m <= 50; ++m)
        for (int n = -50; n <= 50; ++n)
        {
            const PillarIndex idx{m, n};
            const uint64_t k = packKey(idx);
            EXPECT_EQ(unpackKey(k), idx);
            keys.insert(k);
        }
    EXPECT_EQ(keys.size(), 101u * 101u);
    const PillarIndex extreme{std::numeric_limits<int32_t>::min(),
                              std::numeric_limits<int32_t>::max()};
    EXPECT_EQ(unpackKey(packKey(extreme)), extreme);
}

TEST(PillarKey, HashMixesAllBits)
{
    // Neighbouring pillars must spread over the low bits a power-of-two table uses.
    std::set<uint64_t> low_bits;
    for (int m = 0; m < 64; ++m)
        for (int n = 0; n < 64; ++n) low_bits.insert(pillarHash({m, n}) & 0xfff);
    EXPECT_GT(low_bits.size(), 2400u);  // 4096 keys into 4096 buckets: ~2589 expected
    EXPECT_NE(pillarHash({1, 2}), pillarHash({2, 1}));
}

TEST(GridGeometry, PillarOfUsesOriginAndSize)
{
    GridGeometry g;
    g.pillar_size = 2.0;
    g.origin_x = 1.0;
    g.origin_y = -1.0;
    EXPECT_EQ(*g.pillarOf(0.99, -1.0), (PillarIndex{-1, 0}));
    EXPECT_EQ(*g.pillarOf(3.0, -3.01), (PillarIndex{1, -2}));
    EXPECT_EQ(*g.heightCellOf(-0.01), -1);
    EXPECT_EQ(*g.heightCellOf(0.05), 1);
}
