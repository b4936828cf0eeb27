// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Breakdown.h
 * @brief  Scores broken down by moving class (car, person, bicyclist, ...), by static class
 *         (road, building, vegetation, pole, ...) and by range band, for hif-eval.
 */
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "hif/io/Labels.h"

namespace hif::io
{
/** SemanticKITTI's name of a class (10 "car", 40 "road", 70 "vegetation", 80 "pole", ...,
 *  252 "moving-car" ... 259 "moving-other-vehicle"), else "class N". */
[[nodiscard]] std::string className(uint32_t cls);

/** Range bands, metres from the sensor: [0, 10), [10, 20), [20, 35), [35, 50), [50, inf). */
constexpr std::array<double, 5> kRangeBandStarts = {0.0, 10.0, 20.0, 35.0, 50.0};
/** "0-10", ..., "50+". */
[[nodiscard]] std::string rangeBandName(std::size_t band);
/** Band of a range (negative or NaN ranges: none, returns kRangeBandStarts.size()). */
[[nodiscard]] std::size_t rangeBand(double range);

/** Scores in total, per moving class present, per static class present, per range band, and
 *  per moving class present in each range band. */
struct Breakdown
{
    using Bands = std::array<Scores, kRangeBandStarts.size()>;
    Scores total;
    std::map<uint32_t, Scores> by_moving_class;  ///< key: class 252-259
    std::map<uint32_t, Scores> by_static_class;  ///< key: a scored class below 252 (or above 259)
    Bands by_range{};
    /** Per moving class (key: class 252-259) with a range, its points in each band. */
    std::map<uint32_t, Bands> by_moving_class_range;
    bool has_ranges = false;  ///< some point was added with a range

    /** One point: its ground-truth label, whether it was removed, and its range from the
     *  sensor in metres (NaN: unknown). */
    void add(uint32_t truth, bool removed, double range);
    Breakdown& operator+=(const Breakdown& o);
};

}  // namespace hif::io
