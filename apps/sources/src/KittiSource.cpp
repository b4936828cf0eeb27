// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KittiSource.cpp
 * @brief  Scans of a KITTI odometry sequence folder (SemanticKITTI layout, as kitti2rawlog
 *         reads it), without a conversion: velodyne/NNNNNN.bin at the poses of poses.txt.
 */
#include "hif/apps/ScanSource.h"
#include "hif/io/KittiSequence.h"

namespace hif::apps
{
namespace
{
class KittiSource : public ScanSource
{
public:
    explicit KittiSource(const std::string& folder) : seq_(folder) {}

    bool next(Scan& out) override
    {
        if (pos_ >= seq_.size()) return false;
        const std::size_t i = pos_++;
        // Points in the LiDAR frame, at the LiDAR's pose in the world: what kitti2rawlog
        // writes into a rawlog, read straight from the files.
        out.obs = pointCloudObservation(seq_.readScan(i));
        out.obs->timestamp = mrpt::Clock::fromDouble(seq_.time(i));  // as kitti2rawlog stamps
        out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(seq_.pose(i).matrix());
        out.frame = i;
        return true;
    }

    void rewind() override { pos_ = 0; }
    [[nodiscard]] std::size_t knownSize() const override { return seq_.size(); }

private:
    io::KittiSequence seq_;
    std::size_t pos_ = 0;  ///< next scan
};
}  // namespace

std::unique_ptr<ScanSource> openKittiFolder(const std::string& folder)
{
    return std::make_unique<KittiSource>(folder);
}

}  // namespace hif::apps
