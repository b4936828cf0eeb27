// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FrameComment.h
 * @brief  How kitti2rawlog tells hif-clean each scan's number in its sequence: a
 *         CObservationComment "kitti frame N" before the scan.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace hif::apps
{
[[nodiscard]] inline std::string kittiFrameComment(std::size_t frame)
{
    return "kitti frame " + std::to_string(frame);
}

/** The frame number of a kittiFrameComment(), or nullopt for any other text. */
[[nodiscard]] inline std::optional<std::size_t> parseKittiFrameComment(const std::string& text)
{
    const std::string prefix = "kitti frame ";
    if (text.rfind(prefix, 0) != 0 || text.size() == prefix.size()) return std::nullopt;
    std::size_t v = 0;
    for (std::size_t k = prefix.size(); k < text.size(); ++k)
    {
        if (text[k] < '0' || text[k] > '9' || v > 99999999) return std::nullopt;
        v = v * 10 + static_cast<std::size_t>(text[k] - '0');
    }
    return v;
}

}  // namespace hif::apps
