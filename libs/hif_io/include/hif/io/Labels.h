// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Labels.h
 * @brief  SemanticKITTI .label files and the moving-object scores of the dynamic-points-removal
 *         benchmark.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hif::io
{
/** SemanticKITTI moving-object-segmentation labels written by hif-clean. */
constexpr uint32_t kLabelStatic = 9;
constexpr uint32_t kLabelMoving = 251;

/** Reads a .label file (uint32 per point, low 16 bits the class, high 16 bits the instance).
 *  Throws std::runtime_error naming the file when it is missing or its size is not a multiple
 *  of 4 bytes. */
[[nodiscard]] std::vector<uint32_t> readLabels(const std::string& file);
/** Writes a .label file; throws std::runtime_error naming the file on failure. */
void writeLabels(const std::string& file, const std::vector<uint32_t>& labels);

/** Ground truth: classes 252-259 are moving objects. */
[[nodiscard]] inline bool isMovingClass(uint32_t label)
{
    const uint32_t c = label & 0xffffu;
    return c >= 252 && c <= 259;
}
/** Ground truth: classes 0 (unlabeled) and 1 (outlier) are not scored. */
[[nodiscard]] inline bool isScored(uint32_t label) { return (label & 0xffffu) > 1; }
/** Prediction: 251 (moving) or a moving class 252-259 means removed; anything else, kept. */
[[nodiscard]] inline bool isPredictedMoving(uint32_t label)
{
    const uint32_t c = label & 0xffffu;
    return c == kLabelMoving || isMovingClass(c);
}

/** Point-level counts: SA = static kept / static, DA = dynamic removed / dynamic,
 *  AA = sqrt(SA DA), HA = 2 SA DA / (SA + DA), all in percent. */
struct Scores
{
    std::size_t static_total = 0;
    std::size_t static_kept = 0;
    std::size_t dynamic_total = 0;
    std::size_t dynamic_removed = 0;
    std::size_t ignored = 0;  ///< labels 0 and 1

    void add(uint32_t truth, bool removed);
    Scores& operator+=(const Scores& o);
    /** Percentages; a class with no points scores 100 (nothing to get wrong). */
    [[nodiscard]] double sa() const;
    [[nodiscard]] double da() const;
    [[nodiscard]] double aa() const;
    [[nodiscard]] double ha() const;
};

}  // namespace hif::io
