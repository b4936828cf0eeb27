// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KeyframesSource.cpp
 * @brief  The keyframes hdl_graph_slam saves (and interactive_slam reads): a subfolder per
 *         keyframe, NNNNNN/cloud.pcd (its points, in its own frame) and NNNNNN/data (its time
 *         and its optimized pose, `estimate`, a 4x4 matrix).
 */
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hif/apps/ScanSource.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/FileError.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/ParseNumber.h"

namespace fs = std::filesystem;

namespace hif::apps
{
namespace
{
/** The numbered subfolders of `folder` (up to 8 digits) that hold a `data` file, by number. */
std::vector<std::pair<std::size_t, fs::path>> keyframeFolders(const fs::path& folder)
{
    std::vector<std::pair<std::size_t, fs::path>> out;
    for (const auto& e : fs::directory_iterator(folder))
    {
        const std::string name = e.path().filename().string();
        if (!e.is_directory() || name.empty() || name.size() > 8 ||
            !std::all_of(name.begin(), name.end(), [](unsigned char c) { return std::isdigit(c); }))
            continue;
        if (fs::is_regular_file(e.path() / "data")) out.emplace_back(std::stoul(name), e.path());
    }
    std::sort(out.begin(), out.end());
    return out;
}

/** A keyframe's time and pose, from its `data` file. */
struct KeyframeData
{
    double time = 0.0;
    bool has_time = false;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

KeyframeData readKeyframeData(const std::string& file)
{
    std::ifstream f(file);
    if (!f) io::throwFileError(file, "cannot be opened");
    KeyframeData d;
    bool has_estimate = false;
    for (std::string token; f >> token;)
    {
        if (token == "stamp")
        {
            unsigned long long sec = 0, nsec = 0;
            if (!(f >> sec >> nsec) || nsec >= 1000000000ull)
                io::throwFileError(file, "has a malformed stamp (seconds and nanoseconds)");
            d.time = double(sec) + 1e-9 * double(nsec);
            d.has_time = true;
        }
        else if (token == "estimate")
        {
            // The optimized pose, a 4x4 matrix row by row: its top 3 rows are a KITTI pose.
            std::string rows, value;
            for (int k = 0; k < 16; ++k)
            {
                if (!(f >> value))
                    io::throwFileError(file, "ends within its estimate (a 4x4 matrix)");
                if (k < 12)
                    rows += value + ' ';
                else
                {
                    const auto v = io::parseNumber(value);
                    if (!v || std::abs(*v - (k == 15 ? 1.0 : 0.0)) > 1e-6)
                        io::throwFileError(file, "has an estimate whose last row is not 0 0 0 1");
                }
            }
            d.pose = io::parseRow34(rows, file, "its estimate");
            has_estimate = true;
        }
    }
    if (!has_estimate)
        io::throwFileError(file, "has no estimate (the keyframe's pose, hdl_graph_slam's)");
    return d;
}

class KeyframesSource : public ScanSource
{
public:
    explicit KeyframesSource(const std::string& folder) : folders_(keyframeFolders(folder))
    {
        if (folders_.empty())
            throw std::runtime_error("'" + folder + "' holds no keyframe (NNNNNN/data)");
        for (const auto& [number, dir] : folders_)
            if (!fs::is_regular_file(dir / "cloud.pcd"))
                io::throwFileError((dir / "cloud.pcd").string(),
                                   "does not exist (a keyframe's points, beside its data)");
    }

    bool next(Scan& out) override
    {
        if (pos_ >= folders_.size()) return false;
        const auto& [number, dir] = folders_[pos_++];
        const KeyframeData d = readKeyframeData((dir / "data").string());
        io::PcdCloud cloud = io::readPcd((dir / "cloud.pcd").string());
        io::absorbOrigin(cloud);
        out.obs = pointCloudObservation(cloud);
        if (d.has_time) out.obs->timestamp = mrpt::Clock::fromDouble(d.time);
        out.robot_pose = mrpt::poses::CPose3D::FromHomogeneousMatrix(d.pose.matrix());
        out.frame = number;
        out.name = std::nullopt;
        out.has_pose = true;
        return true;
    }

    void rewind() override { pos_ = 0; }
    [[nodiscard]] std::size_t knownSize() const override { return folders_.size(); }

private:
    std::vector<std::pair<std::size_t, fs::path>> folders_;
    std::size_t pos_ = 0;  ///< next keyframe
};
}  // namespace

bool isKeyframesFolder(const std::string& folder)
{
    return fs::is_directory(folder) && !keyframeFolders(folder).empty();
}

std::unique_ptr<ScanSource> openKeyframesFolder(const std::string& folder)
{
    return std::make_unique<KeyframesSource>(folder);
}

}  // namespace hif::apps
