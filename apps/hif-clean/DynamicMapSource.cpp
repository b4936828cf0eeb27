// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   DynamicMapSource.cpp
 * @brief  Scans of a DynamicMap benchmark folder: pcd/NNNNNN.pcd, points in the world frame,
 *         sensor pose in VIEWPOINT.
 */
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <stdexcept>

#include "ScanSource.h"
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
        const fs::path pcd = fs::path(folder) / "pcd";
        for (const auto& e : fs::directory_iterator(pcd))
            if (e.path().extension() == ".pcd") files_.push_back(e.path().string());
        std::sort(files_.begin(), files_.end());
        if (files_.empty()) throw std::runtime_error("'" + pcd.string() + "' has no .pcd");
    }

    bool next(Scan& out) override
    {
        if (pos_ >= files_.size()) return false;
        const std::string& file = files_[pos_++];
        io::PcdCloud pcd = io::readPcd(file);
        // The benchmark's clouds are in the world frame; the map takes sensor-frame points and
        // the sensor pose (VIEWPOINT), so bring them back to the sensor frame.
        io::transform(pcd, pcd.viewpoint.inverse());
        out.obs = pointCloudObservation(pcd);
        out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(pcd.viewpoint.matrix());
        // NNNNNN.pcd is scan NNNNNN of its sequence.
        const std::string stem = fs::path(file).stem().string();
        out.frame.reset();
        if (!stem.empty() && stem.size() <= 8 &&
            std::all_of(stem.begin(), stem.end(), [](unsigned char c) { return std::isdigit(c); }))
            out.frame = static_cast<std::size_t>(std::stoul(stem));
        return true;
    }

    void rewind() override { pos_ = 0; }
    [[nodiscard]] std::size_t knownSize() const override { return files_.size(); }
    [[nodiscard]] bool isDynamicMapFolder() const override { return true; }

private:
    std::vector<std::string> files_;
    std::size_t pos_ = 0;  ///< next file
};
}  // namespace

std::unique_ptr<ScanSource> openDynamicMapFolder(const std::string& folder)
{
    return std::make_unique<DynamicMapSource>(folder);
}

}  // namespace hif::apps
