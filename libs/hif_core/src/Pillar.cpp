// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Pillar.cpp
 * @brief  Queries of a pillar.
 */
#include "hif/Pillar.h"

#include <algorithm>

namespace hif
{
const Interval* findInterval(const Pillar& p, int32_t z)
{
    const auto& iv = p.intervals;
    // First interval with hi > z; it contains z iff its lo <= z.
    auto it = std::upper_bound(iv.begin(), iv.end(), z,
                               [](int32_t v, const Interval& a) { return v < a.hi; });
    if (it != iv.end() && it->lo <= z) return &*it;
    return nullptr;
}

namespace
{
/** The bits [a, b) of word w (bits 64 w to 64 w + 63) of a 128-bit window, 0 <= a <= b <= 128. */
uint64_t wordMask(int64_t a, int64_t b, int w)
{
    const int64_t lo = std::max<int64_t>(a, 64 * w), hi = std::min<int64_t>(b, 64 * w + 64);
    if (lo >= hi) return 0;
    const uint64_t ones = hi - lo == 64 ? ~uint64_t{0} : (uint64_t{1} << (hi - lo)) - 1;
    return ones << (lo - 64 * w);
}
}  // namespace

void PassedCells::add(int32_t lo, int32_t hi)
{
    lo = std::max(lo, kNone + 1);  // the lowest cell is kNone's value: one above it
    if (lo >= hi) return;
    if (base == kNone)
        base = lo;
    else if (lo < base)
    {
        // The window moves down to the new lowest cell; what leaves it at the top is dropped.
        const int64_t s = int64_t{base} - lo;
        if (s >= 2 * 64)
            bits[0] = bits[1] = 0;
        else if (s >= 64)
        {
            bits[1] = bits[0] << (s - 64);
            bits[0] = 0;
        }
        else
        {
            bits[1] = (bits[1] << s) | (bits[0] >> (64 - s));
            bits[0] <<= s;
        }
        base = lo;
    }
    const int64_t a = int64_t{lo} - base, b = std::min<int64_t>(int64_t{hi} - base, kCells);
    bits[0] |= wordMask(a, b, 0);
    bits[1] |= wordMask(a, b, 1);
}

bool PassedCells::any(int32_t lo, int32_t hi) const
{
    if (base == kNone) return false;
    const int64_t a = std::max<int64_t>(int64_t{lo} - base, 0);
    const int64_t b = std::min<int64_t>(int64_t{hi} - base, kCells);
    return (bits[0] & wordMask(a, b, 0)) != 0 || (bits[1] & wordMask(a, b, 1)) != 0;
}

}  // namespace hif
