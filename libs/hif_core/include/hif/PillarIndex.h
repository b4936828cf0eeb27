// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarIndex.h
 * @brief  Pillar index (m, n) on the global grid, its exact 64-bit key and its hash (Eq. 1-3).
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>

namespace hif
{
/** Index (m, n) of pillar P_mn, which covers [x_o + m dx, x_o + (m+1) dx) x
 *  [y_o + n dy, y_o + (n+1) dy) (Eq. 2). */
struct PillarIndex
{
    int32_t m = 0;
    int32_t n = 0;

    friend bool operator==(const PillarIndex& a, const PillarIndex& b)
    {
        return a.m == b.m && a.n == b.n;
    }
    friend bool operator!=(const PillarIndex& a, const PillarIndex& b) { return !(a == b); }
};

/** Exact key: (uint32)m in the high half, (uint32)n in the low half. Injective. */
[[nodiscard]] inline uint64_t packKey(PillarIndex idx)
{
    return (static_cast<uint64_t>(static_cast<uint32_t>(idx.m)) << 32) |
           static_cast<uint64_t>(static_cast<uint32_t>(idx.n));
}

[[nodiscard]] inline PillarIndex unpackKey(uint64_t key)
{
    return {static_cast<int32_t>(static_cast<uint32_t>(key >> 32)),
            static_cast<int32_t>(static_cast<uint32_t>(key & 0xffffffffu))};
}

/** Eq. 3: H = h(m) xor (h(n) + C + (h(m) << 6) + (h(m) >> 2)), with h a 64-bit integer
 *  finalizer (splitmix64) and C the 64-bit golden-ratio constant. All 64 bits are mixed, so
 *  power-of-two tables see no clustering. Map equality always uses packKey(), never this. */
[[nodiscard]] inline uint64_t mixInt(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

[[nodiscard]] inline uint64_t pillarHash(PillarIndex idx)
{
    constexpr uint64_t kGolden = 0x9e3779b97f4a7c15ull;
    const uint64_t hm = mixInt(static_cast<uint32_t>(idx.m));
    const uint64_t hn = mixInt(static_cast<uint32_t>(idx.n));
    return hm ^ (hn + kGolden + (hm << 6) + (hm >> 2));
}

/** Hash functor over packed keys, for flat hash maps keyed by packKey(). */
struct PackedKeyHash
{
    std::size_t operator()(uint64_t key) const
    {
        return static_cast<std::size_t>(pillarHash(unpackKey(key)));
    }
};

/** floor(v) as an int32 in `out`, or false when v is not finite or floor(v) does not fit in
 *  int32. Exact for every double; converts by truncation and corrects negatives, which is
 *  several times faster than std::floor on the baseline x86-64 instruction set (no SSE4.1). */
[[nodiscard]] inline bool floorToInt32(double v, int32_t& out)
{
    // floor(v) is in range iff INT32_MIN <= v < INT32_MAX + 1; NaN fails both tests.
    if (!(v >= -2147483648.0 && v < 2147483648.0)) return false;
    const auto t = static_cast<int64_t>(v);  // toward zero
    out = static_cast<int32_t>(t - (v < static_cast<double>(t)));
    return true;
}

/** Eq. 1: m = floor((x - x_o) / dx), computed as floor((x - x_o) * (1 / dx)) everywhere in
 *  hif (insertion, queries, classification), so that all agree bit for bit. Returns nullopt
 *  when the result does not fit in int32 (or the input is not finite), so callers can count
 *  and skip such points. */
[[nodiscard]] inline std::optional<int32_t> quantize(double v, double origin, double size)
{
    int32_t q = 0;
    if (!floorToInt32((v - origin) * (1.0 / size), q)) return std::nullopt;
    return q;
}

}  // namespace hif
