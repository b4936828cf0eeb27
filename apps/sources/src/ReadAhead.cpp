// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ReadAhead.cpp
 * @brief  A scan source that reads its next scan on a second thread while the caller inserts
 *         or classifies the current one (reading and parsing a scan costs about as much as
 *         inserting it). One reader thread for the whole run, so that its buffers are reused.
 */
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "hif/apps/ScanSource.h"

namespace hif::apps
{
namespace
{
class ReadAhead : public ScanSource
{
public:
    ReadAhead(std::unique_ptr<ScanSource> source, PrepareScan prepare)
        : source_(std::move(source)), prepare_(std::move(prepare)), reader_([this] { readLoop(); })
    {
    }

    ~ReadAhead() override
    {
        settle();
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            stop_ = true;
        }
        cv_.notify_all();
        reader_.join();
    }
    ReadAhead(const ReadAhead&) = delete;
    ReadAhead& operator=(const ReadAhead&) = delete;

    bool next(Scan& out) override
    {
        if (!asked_) ask();
        std::optional<Scan> scan = take();  // rethrows what the reader threw
        if (!scan) return false;
        out = std::move(*scan);
        ask();
        return true;
    }

    void rewind() override
    {
        settle();
        source_->rewind();
    }

    [[nodiscard]] std::size_t knownSize() const override { return source_->knownSize(); }
    [[nodiscard]] std::size_t skippedObjects() const override
    {
        waitIdle();
        return source_->skippedObjects();
    }
    [[nodiscard]] LeftOut leftOutScans() const override
    {
        waitIdle();
        return source_->leftOutScans();
    }
    [[nodiscard]] bool isDynamicMapFolder() const override { return source_->isDynamicMapFolder(); }
    [[nodiscard]] std::vector<std::string> warnings() const override
    {
        return source_->warnings();  // set when the source was opened, before the reader ran
    }

private:
    /** Asks the reader for the next scan. */
    void ask()
    {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            asked_ = true;
            done_ = false;
        }
        cv_.notify_all();
    }

    /** Waits for the scan asked for. */
    std::optional<Scan> take()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock, [this] { return done_; });
        asked_ = false;
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
        return std::exchange(result_, std::nullopt);
    }

    /** Waits until the reader is idle: it counts (skipped objects, scans left out) as it
     *  reads. */
    void waitIdle() const
    {
        std::unique_lock<std::mutex> lock(mutex_);
        cv_.wait(lock, [this] { return !asked_ || done_; });
    }

    /** Waits for a read under way and forgets it (and what it may have thrown: the scan after
     *  the last one asked for is never handed out). */
    void settle()
    {
        if (!asked_) return;
        try
        {
            take();
        }
        catch (const std::exception&)
        {
        }
    }

    void readLoop()
    {
        std::unique_lock<std::mutex> lock(mutex_);
        for (;;)
        {
            cv_.wait(lock, [this] { return stop_ || (asked_ && !done_); });
            if (stop_) return;
            lock.unlock();
            std::optional<Scan> scan;
            std::exception_ptr error;
            try
            {
                Scan s;
                if (source_->next(s))
                {
                    if (prepare_) prepare_(s);
                    scan = std::move(s);
                }
            }
            catch (...)
            {
                error = std::current_exception();
            }
            lock.lock();
            result_ = std::move(scan);
            error_ = error;
            done_ = true;
            cv_.notify_all();
        }
    }

    std::unique_ptr<ScanSource> source_;
    PrepareScan prepare_;
    mutable std::mutex mutex_;
    mutable std::condition_variable cv_;
    bool asked_ = false;  ///< a scan was asked for and not yet taken
    bool done_ = false;   ///< the reader has finished the scan asked for
    bool stop_ = false;
    std::optional<Scan> result_;
    std::exception_ptr error_;
    std::thread reader_;  ///< last: started once the rest is initialized
};
}  // namespace

std::unique_ptr<ScanSource> readingAhead(std::unique_ptr<ScanSource> source, PrepareScan prepare)
{
    return std::make_unique<ReadAhead>(std::move(source), std::move(prepare));
}

}  // namespace hif::apps
