// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Breakdown.cpp
 * @brief  Scores by moving class, static class and range band.
 */
#include "hif/io/Breakdown.h"

#include <cmath>
#include <map>

namespace hif::io
{
std::string className(uint32_t cls)
{
    // SemanticKITTI's classes (semantic-kitti.yaml).
    static const std::map<uint32_t, const char*> names = {{10, "car"},
                                                          {11, "bicycle"},
                                                          {13, "bus"},
                                                          {15, "motorcycle"},
                                                          {16, "on-rails"},
                                                          {18, "truck"},
                                                          {20, "other-vehicle"},
                                                          {30, "person"},
                                                          {31, "bicyclist"},
                                                          {32, "motorcyclist"},
                                                          {40, "road"},
                                                          {44, "parking"},
                                                          {48, "sidewalk"},
                                                          {49, "other-ground"},
                                                          {50, "building"},
                                                          {51, "fence"},
                                                          {52, "other-structure"},
                                                          {60, "lane-marking"},
                                                          {70, "vegetation"},
                                                          {71, "trunk"},
                                                          {72, "terrain"},
                                                          {80, "pole"},
                                                          {81, "traffic-sign"},
                                                          {99, "other-object"},
                                                          {252, "moving-car"},
                                                          {253, "moving-bicyclist"},
                                                          {254, "moving-person"},
                                                          {255, "moving-motorcyclist"},
                                                          {256, "moving-on-rails"},
                                                          {257, "moving-bus"},
                                                          {258, "moving-truck"},
                                                          {259, "moving-other-vehicle"}};
    const auto it = names.find(cls);
    return it != names.end() ? it->second : "class " + std::to_string(cls);
}

std::string rangeBandName(std::size_t band)
{
    if (band + 1 >= kRangeBandStarts.size())
        return std::to_string(static_cast<int>(kRangeBandStarts.back())) + "+";
    return std::to_string(static_cast<int>(kRangeBandStarts[band])) + "-" +
           std::to_string(static_cast<int>(kRangeBandStarts[band + 1]));
}

std::size_t rangeBand(double range)
{
    if (!(range >= 0.0)) return kRangeBandStarts.size();
    std::size_t b = 0;
    while (b + 1 < kRangeBandStarts.size() && range >= kRangeBandStarts[b + 1]) ++b;
    return b;
}

void Breakdown::add(uint32_t truth, bool removed, double range)
{
    total.add(truth, removed);
    if (isScored(truth))
        (isMovingClass(truth) ? by_moving_class : by_static_class)[truth & 0xffffu].add(truth,
                                                                                        removed);
    const std::size_t band = rangeBand(range);
    if (band < by_range.size())
    {
        by_range[band].add(truth, removed);
        if (isScored(truth) && isMovingClass(truth))
            by_moving_class_range[truth & 0xffffu][band].add(truth, removed);
        has_ranges = true;
    }
}

Breakdown& Breakdown::operator+=(const Breakdown& o)
{
    total += o.total;
    for (const auto& [cls, s] : o.by_moving_class) by_moving_class[cls] += s;
    for (const auto& [cls, s] : o.by_static_class) by_static_class[cls] += s;
    for (std::size_t b = 0; b < by_range.size(); ++b) by_range[b] += o.by_range[b];
    for (const auto& [cls, bands] : o.by_moving_class_range)
    {
        Bands& mine = by_moving_class_range[cls];
        for (std::size_t b = 0; b < bands.size(); ++b) mine[b] += bands[b];
    }
    has_ranges = has_ranges || o.has_ranges;
    return *this;
}

}  // namespace hif::io
