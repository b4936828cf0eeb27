// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ReadAhead.cpp
 * @brief  A scan source that reads its next scan on a second thread while the caller inserts
 *         or classifies the current one (reading and parsing a scan costs about as much as
 *         inserting it).
 */
#include <future>

#include "ScanSource.h"

namespace hif::apps
{
namespace
{
class ReadAhead : public ScanSource
{
public:
    explicit ReadAhead(std::unique_ptr<ScanSource> source) : source_(std::move(source)) {}
    ~ReadAhead() override { settle(); }
    ReadAhead(const ReadAhead&) = delete;
    ReadAhead& operator=(const ReadAhead&) = delete;

    bool next(Scan& out) override
    {
        if (!pending_.valid()) start();
        std::optional<Scan> scan = pending_.get();  // rethrows what the reader threw
        if (!scan) return false;
        out = std::move(*scan);
        start();
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
        if (pending_.valid()) pending_.wait();  // the reader counts as it reads
        return source_->skippedObjects();
    }
    [[nodiscard]] bool isDynamicMapFolder() const override { return source_->isDynamicMapFolder(); }

private:
    void start()
    {
        pending_ = std::async(std::launch::async,
                              [this]
                              {
                                  Scan s;
                                  return source_->next(s) ? std::optional<Scan>(std::move(s))
                                                          : std::nullopt;
                              });
    }

    /** Waits for a read under way and forgets it (and what it may have thrown: the scan after
     *  the last one asked for is never handed out). */
    void settle()
    {
        if (!pending_.valid()) return;
        try
        {
            pending_.get();
        }
        catch (const std::exception&)
        {
        }
    }

    std::unique_ptr<ScanSource> source_;
    std::future<std::optional<Scan>> pending_;
};
}  // namespace

std::unique_ptr<ScanSource> readingAhead(std::unique_ptr<ScanSource> source)
{
    return std::make_unique<ReadAhead>(std::move(source));
}

}  // namespace hif::apps
