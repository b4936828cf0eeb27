// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Worker.cpp
 * @brief  The worker's thread and its hand-over.
 */
#include "hif/apps/Worker.h"

#include <utility>

namespace hif::apps
{
Worker::Worker() : thread_([this] { loop(); }) {}

Worker::~Worker()
{
    {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock, [this] { return !busy_; });
        stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
}

void Worker::run(std::function<void()> job)
{
    std::unique_lock<std::mutex> lock(mutex_);
    settle(lock);
    job_ = std::move(job);
    busy_ = true;
    lock.unlock();
    cv_.notify_all();
}

void Worker::wait()
{
    std::unique_lock<std::mutex> lock(mutex_);
    settle(lock);
}

void Worker::settle(std::unique_lock<std::mutex>& lock)
{
    cv_.wait(lock, [this] { return !busy_; });
    if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
}

void Worker::loop()
{
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;)
    {
        cv_.wait(lock, [this] { return busy_ || stop_; });
        if (!busy_) return;  // stopped
        std::function<void()> job = std::move(job_);
        lock.unlock();
        std::exception_ptr error;
        try
        {
            job();
        }
        catch (...)
        {
            error = std::current_exception();
        }
        job = nullptr;  // what the job holds goes before the caller is told it is done
        lock.lock();
        if (error && !error_) error_ = error;
        busy_ = false;
        cv_.notify_all();
    }
}

}  // namespace hif::apps
