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

}  // namespace hif
