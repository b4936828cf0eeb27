// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanWindow.cpp
 * @brief  The scans kept for the free-space test.
 */
#include "hif/ScanWindow.h"

#include <stdexcept>
#include <string>

#include "RangeImage.h"

namespace hif
{
static_assert(ScanWindow::kNoReturn == detail::kNoReturnCm);

namespace
{
constexpr std::size_t kMaxSpares = 2;
}

void ScanWindow::checkNext(std::size_t id) const
{
    if (!scans_.empty() && id <= scans_.back().id)
        throw std::invalid_argument("hif::ScanWindow::add: scan " + std::to_string(id) +
                                    " after scan " + std::to_string(scans_.back().id) +
                                    " (ids must increase)");
}

ScanWindow::Scan ScanWindow::makeScan(std::size_t id, const PointsView& points,
                                      const Eigen::Isometry3d& sensor_to_world,
                                      const RangeImageLayout& layout, std::vector<uint16_t> image)
{
    Scan s;
    s.id = id;
    s.sensor_to_world = sensor_to_world;
    s.world_to_sensor_rotation = sensor_to_world.linear().transpose();
    s.layout = layout;
    s.image = std::move(image);
    detail::buildRangeImageCm(layout, points, s.image);
    return s;
}

void ScanWindow::add(Scan scan)
{
    checkNext(scan.id);
    scans_.push_back(std::move(scan));
}

void ScanWindow::add(std::size_t id, const PointsView& points,
                     const Eigen::Isometry3d& sensor_to_world, const RangeImageLayout& layout)
{
    checkNext(id);  // before the image is built
    std::vector<uint16_t> image;
    if (!spare_.empty())
    {
        image = std::move(spare_.back());
        spare_.pop_back();
    }
    add(makeScan(id, points, sensor_to_world, layout, std::move(image)));
}

void ScanWindow::dropBefore(std::size_t first)
{
    while (!scans_.empty() && scans_.front().id < first)
    {
        // add(id, ...) takes one back per scan; add(Scan) brings its own, so keep only a few.
        if (spare_.size() < kMaxSpares) spare_.push_back(std::move(scans_.front().image));
        scans_.pop_front();
    }
}

std::size_t ScanWindow::memoryBytes() const
{
    std::size_t bytes = 0;
    for (const Scan& s : scans_) bytes += sizeof(Scan) + s.image.capacity() * sizeof(uint16_t);
    for (const auto& v : spare_) bytes += v.capacity() * sizeof(uint16_t);
    return bytes;
}

}  // namespace hif
