// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   HeightCells.cpp
 * @brief  Sorting and deduplicating a pillar's height cells.
 */
#include "HeightCells.h"

#include <algorithm>

namespace hif::detail
{
std::size_t sortDistinct(int32_t* cells, std::size_t n)
{
    constexpr std::size_t kSmall = 24;         // below this, insertion sort is fastest
    constexpr int64_t kBitmapCells = 64 * 64;  // bitmap of at most 64 words on the stack
    if (n > kSmall)
    {
        const auto [lo_it, hi_it] = std::minmax_element(cells, cells + n);
        const int64_t lo = *lo_it, range = int64_t{*hi_it} - lo + 1;
        if (range <= kBitmapCells)
        {
            uint64_t bits[kBitmapCells / 64] = {};
            for (std::size_t k = 0; k < n; ++k)
            {
                const auto o = static_cast<uint64_t>(cells[k] - lo);
                bits[o >> 6] |= uint64_t{1} << (o & 63);
            }
            std::size_t m = 0;
            const auto words = static_cast<std::size_t>((range + 63) / 64);
            for (std::size_t w = 0; w < words; ++w)
                for (uint64_t b = bits[w]; b != 0; b &= b - 1)
                    cells[m++] = static_cast<int32_t>(
                        lo +
                        static_cast<int64_t>(w * 64 + static_cast<unsigned>(__builtin_ctzll(b))));
            return m;
        }
        std::sort(cells, cells + n);
    }
    else
    {
        // Insertion sort that drops duplicates as it goes: cells[0, m) is sorted and distinct.
        std::size_t m = n > 0 ? 1 : 0;
        for (std::size_t k = 1; k < n; ++k)
        {
            const int32_t c = cells[k];
            std::size_t j = m;
            while (j > 0 && cells[j - 1] > c) --j;
            if (j > 0 && cells[j - 1] == c) continue;  // already there
            for (std::size_t q = m; q > j; --q) cells[q] = cells[q - 1];
            cells[j] = c;
            ++m;
        }
        return m;
    }
    return static_cast<std::size_t>(std::unique(cells, cells + n) - cells);
}

}  // namespace hif::detail
