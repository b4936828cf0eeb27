// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ParseNumber.h
 * @brief  One number read from a token of a text file, whole or not at all.
 */
#pragma once

#include <cstdlib>
#include <optional>
#include <string>

namespace hif::io
{
/** The number `token` holds, read whole ("1e-3", "inf" and "nan" included, which operator>>
 *  does not read), or nullopt ("1.5m", "", "abc"). */
[[nodiscard]] inline std::optional<double> parseNumber(const std::string& token)
{
    if (token.empty()) return std::nullopt;
    const char* begin = token.c_str();
    char* end = nullptr;
    const double v = std::strtod(begin, &end);
    if (end != begin + token.size()) return std::nullopt;
    return v;
}

}  // namespace hif::io
