// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   DynamicMapSource.cpp
 * @brief  Scans of a DynamicMap benchmark folder: pcd/NNNNNN.pcd, points in the world frame,
 *         sensor pose in VIEWPOINT.
 */
#include <filesystem>
#include <stdexcept>

#include "NumberedFiles.h"
#include "hif/apps/ScanSource.h"
#include "hif/io/CloudFiles.h"

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
class DynamicMapSource : public ScanSource
{
public:
    explicit DynamicMapSource(const std::string& folder)
    {
        // As strict as the KITTI layout: the scans are the files named by their number
        // (NNNNNN.pcd); anything else there is named and left out.
        const std::string pcd = (fs::path(folder) / "pcd").string();
        NumberedFiles found = numberedFiles(pcd, {".pcd"});
        for (auto& [number, file] : found.files) files_.push_back(std::move(file));
        if (files_.empty())
            throw std::runtime_error(
                "'" + pcd + "' has no scan (files named by their number, NNNNNN.pcd)" +
                (found.other.empty() ? "" : "; it holds " + listNames(found.other)));
        if (!found.other.empty())
            warnings_.push_back(
                "'" + pcd + "' holds " + std::to_string(found.other.size()) +
                " file(s) not named as scans (NNNNNN.pcd), left out: " + listNames(found.other));
    }

    bool next(Scan& out) override
    {
        if (pos_ >= files_.size()) return false;
        const std::string& file = files_[pos_++];
        io::PcdCloud pcd = io::readPcd(file);
        if (!pcd.has_viewpoint)
            throw std::runtime_error("'" + file +
                                     "' has no VIEWPOINT line: a DynamicMap scan holds its sensor "
                                     "pose there (without it, the scan would be taken from the "
                                     "origin)");
        // The benchmark's clouds are in the world frame; the map takes sensor-frame points and
        // the sensor pose (VIEWPOINT), so bring them back to the sensor frame.
        io::toViewpointFrame(pcd);
        out.obs = pointCloudObservation(pcd);
        out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(pcd.viewpoint.matrix());
        // NNNNNN.pcd is scan NNNNNN of its sequence.
        out.frame = static_cast<std::size_t>(std::stoul(fs::path(file).stem().string()));
        return true;
    }

    void rewind() override { pos_ = 0; }
    [[nodiscard]] std::size_t knownSize() const override { return files_.size(); }
    [[nodiscard]] bool isDynamicMapFolder() const override { return true; }
    [[nodiscard]] std::vector<std::string> warnings() const override { return warnings_; }

private:
    std::vector<std::string> warnings_;
    std::vector<std::string> files_;
    std::size_t pos_ = 0;  ///< next file
};
}  // namespace

std::unique_ptr<ScanSource> openDynamicMapFolder(const std::string& folder)
{
    return std::make_unique<DynamicMapSource>(folder);
}

}  // namespace hif::apps
