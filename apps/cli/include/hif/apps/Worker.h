// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Worker.h
 * @brief  One job at a time on a thread of its own, in the order given: the caller goes on with
 *         the next scan while the last one's files are written.
 */
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace hif::apps
{
/** A thread that runs the jobs handed to it one after the other. At most one job is in hand:
 *  run() waits until the job before is done. What a job throws is thrown again by the next
 *  run() or wait() (and the jobs handed after it are not run); the destructor waits for the job
 *  in hand and drops its error. */
class Worker
{
public:
    Worker();
    ~Worker();
    Worker(const Worker&) = delete;
    Worker& operator=(const Worker&) = delete;

    /** Hands `job` over once the job before is done; throws what that one threw. */
    void run(std::function<void()> job);
    /** Waits until the job in hand is done; throws what it threw. */
    void wait();

private:
    void loop();
    /** With `lock` held: waits until no job is in hand, then rethrows its error, if any. */
    void settle(std::unique_lock<std::mutex>& lock);

    std::mutex mutex_;
    std::condition_variable cv_;
    std::function<void()> job_;  ///< in hand, while `busy_`
    bool busy_ = false, stop_ = false;
    std::exception_ptr error_;
    std::thread thread_;  ///< last: started once the rest is set up
};

}  // namespace hif::apps
