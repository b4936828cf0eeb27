// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SimpleMapSource.cpp
 * @brief  Scans of an MRPT .simplemap: sensory frames, each with its robot pose.
 */
#include <mrpt/maps/CSimpleMap.h>

#include <stdexcept>

#include "hif/apps/ScanSource.h"

namespace hif::apps
{
namespace
{
class SimpleMapSource : public ScanSource
{
public:
    explicit SimpleMapSource(std::string file) : file_(std::move(file))
    {
        if (!map_.loadFromFile(file_))
            throw std::runtime_error("cannot read the simple map '" + file_ + "'");
    }

    bool next(Scan& out) override
    {
        while (!frame_.next(out))
        {
            if (pos_ >= map_.size()) return false;
            const auto& [pose_pdf, sf] = map_.get(pos_++);
            if (!pose_pdf || !sf)
                throw std::runtime_error("simple map '" + file_ + "': entry " +
                                         std::to_string(pos_ - 1) + " has no pose or no frame");
            frame_.assign(*sf, pose_pdf->getMeanVal());
        }
        checkExternalPoints(*out.obs,
                            "simple map '" + file_ + "', entry " + std::to_string(pos_ - 1));
        return true;
    }

    void rewind() override
    {
        pos_ = 0;
        frame_.clear();
    }

    [[nodiscard]] std::size_t knownSize() const override { return map_.size(); }

private:
    std::string file_;
    mrpt::maps::CSimpleMap map_;
    std::size_t pos_ = 0;  ///< next entry
    FrameScans frame_;
};
}  // namespace

std::unique_ptr<ScanSource> openSimpleMap(const std::string& file)
{
    return std::make_unique<SimpleMapSource>(file);
}

}  // namespace hif::apps
