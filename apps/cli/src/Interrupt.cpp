// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Interrupt.cpp
 * @brief  The signal thread and the paths it removes.
 */
#include "hif/apps/Interrupt.h"

#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
struct Registry
{
    std::mutex mutex;
    std::map<std::size_t, std::pair<std::string, bool>> paths;  ///< id -> (path, only if empty)
    std::size_t next = 0;
    std::string tag;
    bool installed = false;
    std::atomic<bool> stopping{false};  ///< a stop signal was taken; its thread ends the process
};

/** Never destroyed: the signal thread may use it while the process exits. */
Registry& registry()
{
    static auto* r = new Registry;
    return *r;
}

sigset_t stopSignals()
{
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    return set;
}

/** Removes `path` (a file or a folder and what it holds) that the main thread may still be
 *  writing into: a folder is first moved aside, so that files the main thread opens after that
 *  fail instead of landing in it while it is removed; what it writes under the old name in the
 *  meantime is removed after. Whether anything was removed. */
bool removeWhileWritten(const std::string& path)
{
    std::error_code ec;
    bool removed = false;
    if (fs::is_directory(path, ec))
    {
        const std::string aside = path + ".removing";
        fs::rename(path, aside, ec);
        if (!ec) removed = fs::remove_all(aside, ec) > 0;
    }
    for (int attempt = 0; attempt < 5 && fs::exists(path, ec); ++attempt)
        removed = fs::remove_all(path, ec) > 0 || removed;
    return removed;
}

[[noreturn]] void waitForSignal(sigset_t set)
{
    int sig = 0;
    while (sigwait(&set, &sig) != 0)
    {
    }
    Registry& r = registry();
    r.stopping = true;
    std::size_t removed = 0;
    {
        std::lock_guard<std::mutex> lock(r.mutex);
        // The newest first: a staging folder's own partial files before the folder.
        for (auto it = r.paths.rbegin(); it != r.paths.rend(); ++it)
        {
            const auto& [path, only_if_empty] = it->second;
            std::error_code ec;
            if (only_if_empty)
                removed += fs::is_empty(path, ec) && fs::remove(path, ec) ? 1 : 0;
            else
                removed += removeWhileWritten(path) ? 1 : 0;
        }
    }
    const char* abbrev = sigabbrev_np(sig);
    std::fprintf(stderr, "\n%s stopped by SIG%s: %s\n", r.tag.c_str(), abbrev ? abbrev : "?",
                 removed > 0 ? "its partial outputs were removed, earlier results are as they were"
                             : "nothing was written");
    std::fflush(stderr);
    // End as the signal says (the shell sees 128 + sig).
    signal(sig, SIG_DFL);
    sigset_t one;
    sigemptyset(&one);
    sigaddset(&one, sig);
    pthread_sigmask(SIG_UNBLOCK, &one, nullptr);
    raise(sig);
    _exit(128 + sig);
}
}  // namespace

void removePartialsOnInterrupt(const std::string& tag)
{
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.tag = tag;
    if (r.installed) return;
    const sigset_t set = stopSignals();
    if (pthread_sigmask(SIG_BLOCK, &set, nullptr) != 0) return;  // the default: stop at once
    std::thread(waitForSignal, set).detach();
    r.installed = true;
}

void endHereIfStopped()
{
    if (!registry().stopping) return;
    for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
}

RemoveOnInterrupt::RemoveOnInterrupt(const std::string& path, bool only_if_empty)
{
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    id_ = r.next++;
    r.paths.emplace(id_, std::make_pair(fs::absolute(path).string(), only_if_empty));
}

RemoveOnInterrupt::~RemoveOnInterrupt()
{
    Registry& r = registry();
    std::lock_guard<std::mutex> lock(r.mutex);
    r.paths.erase(id_);
}

}  // namespace hif::apps
