// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Interrupt.h
 * @brief  A run stopped by SIGINT, SIGTERM or SIGHUP (Ctrl-C, kill, a closed terminal) removes
 *         what it had only half written, then ends as the signal says.
 */
#pragma once

#include <cstddef>
#include <string>

namespace hif::apps
{
/** From here on, SIGINT, SIGTERM and SIGHUP are taken by a thread of their own: it removes every
 *  path registered with RemoveOnInterrupt, says so on stderr (prefixed by `tag`), and ends the
 *  process with the signal's own status (130 for SIGINT in a shell). Call it before any other
 *  thread starts (the signals are blocked in the threads started after it); cliMain() does.
 *  Idempotent. */
void removePartialsOnInterrupt(const std::string& tag);

/** If a stop signal has been taken, waits here for its thread to end the process: an error the
 *  main thread meets meanwhile (a file it could not open because its folder was just removed)
 *  comes from the stop, not from the run, and is neither reported nor the exit status. */
void endHereIfStopped();

/** A path (a partial file or a staging folder) removed if the run is interrupted, for as long
 *  as this object lives. With `only_if_empty`, a folder is removed only when it is empty (an
 *  output folder the run created). */
class RemoveOnInterrupt
{
public:
    explicit RemoveOnInterrupt(const std::string& path, bool only_if_empty = false);
    ~RemoveOnInterrupt();
    RemoveOnInterrupt(const RemoveOnInterrupt&) = delete;
    RemoveOnInterrupt& operator=(const RemoveOnInterrupt&) = delete;

private:
    std::size_t id_;
};

}  // namespace hif::apps
