// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   DynamicMapSource.cpp
 * @brief  Scans of a DynamicMap benchmark folder: pcd/NNNNNN.pcd, points in the world frame,
 *         sensor pose in VIEWPOINT.
 */
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
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
        // As strict as the KITTI layout: the scans are the files named by their number
        // (NNNNNN.pcd); anything else there (a gt_cloud.pcd, results written into the folder)
        // is named and left out, never read as one more scan.
        const fs::path pcd = fs::path(folder) / "pcd";
        std::vector<std::string> other;
        for (const auto& e : fs::directory_iterator(pcd))
        {
            const std::string stem = e.path().stem().string();
            const bool numbered = !stem.empty() && stem.size() <= 8 &&
                                  std::all_of(stem.begin(), stem.end(),
                                              [](unsigned char c) { return std::isdigit(c); });
            if (e.is_regular_file() && e.path().extension() == ".pcd" && numbered)
                files_.push_back(e.path().string());
            else
                other.push_back(e.path().filename().string());
        }
        std::sort(files_.begin(), files_.end());
        std::sort(other.begin(), other.end());
        if (files_.empty())
            throw std::runtime_error("'" + pcd.string() +
                                     "' has no scan (files named by their number, NNNNNN.pcd)" +
                                     (other.empty() ? "" : "; it holds " + list(other)));
        if (!other.empty())
            warnings_.push_back(
                "'" + pcd.string() + "' holds " + std::to_string(other.size()) +
                " file(s) not named as scans (NNNNNN.pcd), left out: " + list(other));
        std::map<unsigned long, std::string> numbers;  // 000001.pcd and 1.pcd are one scan
        for (const std::string& f : files_)
        {
            const std::string name = fs::path(f).filename().string();
            const auto [it, fresh] = numbers.emplace(std::stoul(fs::path(f).stem().string()), name);
            if (!fresh)
                throw std::runtime_error("'" + pcd.string() + "' holds two files of scan " +
                                         std::to_string(it->first) + ": " + it->second + " and " +
                                         name);
        }
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
    /** Up to five names, and how many more. */
    static std::string list(const std::vector<std::string>& names)
    {
        std::string s;
        for (std::size_t k = 0; k < names.size() && k < 5; ++k) s += (k ? ", " : "") + names[k];
        if (names.size() > 5) s += " and " + std::to_string(names.size() - 5) + " more";
        return s;
    }

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
