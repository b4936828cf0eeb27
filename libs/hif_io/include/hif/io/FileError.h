// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FileError.h
 * @brief  The one error that hif's readers and writers throw: it names the file and says what
 *         is wrong with it.
 */
#pragma once

#include <stdexcept>
#include <string>

namespace hif::io
{
/** Throws std::runtime_error "'<file>' <problem>", e.g. "'a/poses.txt' has 3 poses for 10
 *  scans". */
[[noreturn]] inline void throwFileError(const std::string& file, const std::string& problem)
{
    throw std::runtime_error("'" + file + "' " + problem);
}

}  // namespace hif::io
