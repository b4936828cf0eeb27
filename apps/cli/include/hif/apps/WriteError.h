// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   WriteError.h
 * @brief  A write to a file that fails (a full disk, a file-size limit) said as the system says
 *         it, not as MRPT's "Cannot write bytes".
 */
#pragma once

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

namespace hif::apps
{
/** Throws "<what> could not be written (disk full?): <the system's reason for `err`>; nothing
 *  was left behind" (`what` names the file, e.g. "'out.rawlog'"). */
[[noreturn]] inline void throwWriteError(const std::string& what, int err)
{
    throw std::runtime_error(what + " could not be written (disk full?): " +
                             (err != 0 ? std::strerror(err) : "write failed") +
                             "; nothing was left behind");
}

/** Runs `write` (MRPT serialization into a file, or closing it) and turns its failure into
 *  throwWriteError(what, errno). With `closing`, also the failure of the last flush, which
 *  MRPT's streams do not report (errno left at ENOSPC or EFBIG). */
template <typename Write>
void writeOrThrow(const std::string& what, Write&& write, bool closing = false)
{
    errno = 0;
    try
    {
        write();
    }
    catch (const std::exception&)
    {
        throwWriteError(what, errno);
    }
    if (closing && (errno == ENOSPC || errno == EFBIG)) throwWriteError(what, errno);
}

}  // namespace hif::apps
