// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ShippedConfig.h
 * @brief  Where the apps find the configurations shipped in share/hif/config.
 */
#pragma once

#include <string>

namespace hif::apps
{
/** `name` (e.g. "kitti.ini") in the installed share/hif/config beside the running program (any
 *  install prefix), else in the source tree's (a build tree). Throws std::runtime_error naming
 *  both places if it is in neither. */
[[nodiscard]] std::string shippedConfig(const std::string& name);

}  // namespace hif::apps
