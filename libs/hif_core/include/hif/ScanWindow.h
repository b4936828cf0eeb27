// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ScanWindow.h
 * @brief  The range images of a few scans around the one being classified, for the free-space
 *         test (Params::free_space_window): did another scan see through a point?
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "hif/SensorModel.h"

namespace hif
{
struct PointsView;

/** Scans by number (id, increasing), each kept as its pose and its range image: the nearest
 *  return in every cell of about 0.2 x 0.2 degrees around its sensor, in centimetres. Online,
 *  hold the last free_space_window scans before the one classified; offline, the
 *  free_space_window scans on each side of it. About 0.5 MB per scan of a 64-beam LiDAR. */
class ScanWindow
{
public:
    static constexpr uint16_t kNoReturn = 0xFFFF;

    /** One scan of the window. */
    struct Scan
    {
        std::size_t id = 0;
        Eigen::Isometry3d sensor_to_world = Eigen::Isometry3d::Identity();
        Eigen::Matrix3d world_to_sensor_rotation = Eigen::Matrix3d::Identity();
        /** How `image` is laid out (from the scan's sensor model). */
        RangeImageLayout layout;
        /** layout.cols x layout.rows, row-major, centimetres (up to 655.34 m), kNoReturn where
         *  no return. */
        std::vector<uint16_t> image;
    };

    /** Adds scan `id` (points in the sensor frame, placed by `sensor_to_world`), its range
     *  image laid out as `layout`. Ids must increase; throws std::invalid_argument otherwise. */
    void add(std::size_t id, const PointsView& points, const Eigen::Isometry3d& sensor_to_world,
             const RangeImageLayout& layout);
    /** The costly half of add(): scan `id` with its range image built, not added, so that it
     *  can be built on another thread (into `image`'s memory, if given). */
    [[nodiscard]] static Scan makeScan(std::size_t id, const PointsView& points,
                                       const Eigen::Isometry3d& sensor_to_world,
                                       const RangeImageLayout& layout,
                                       std::vector<uint16_t> image = {});
    /** Adds a scan made by makeScan(); ids must increase, as for add(). */
    void add(Scan scan);
    /** Forgets the scans numbered below `first`. */
    void dropBefore(std::size_t first);
    void clear() { scans_.clear(); }

    [[nodiscard]] const std::deque<Scan>& scans() const { return scans_; }
    [[nodiscard]] bool empty() const { return scans_.empty(); }
    [[nodiscard]] std::size_t size() const { return scans_.size(); }
    /** Id of the newest scan (the window must not be empty). */
    [[nodiscard]] std::size_t lastId() const { return scans_.back().id; }
    [[nodiscard]] std::size_t memoryBytes() const;

private:
    /** Throws std::invalid_argument unless `id` comes after the newest scan. */
    void checkNext(std::size_t id) const;

    std::deque<Scan> scans_;
    std::vector<std::vector<uint16_t>> spare_;  ///< images of dropped scans, reused
};

}  // namespace hif
