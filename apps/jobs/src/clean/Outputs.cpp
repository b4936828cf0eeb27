// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Outputs.cpp
 * @brief  Classification of a scan and its files.
 */
#include "Outputs.h"

#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/opengl/COpenGLScene.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfObjects.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"

Outputs::Outputs(const std::string& dir, std::optional<std::size_t> first_frame,
                 std::vector<std::string> static_files, std::vector<std::string> removed_files)
    : removed_cloud_(std::move(removed_files)),
      pred_dir_(dir + "/predictions"),
      first_frame_(first_frame)
{
    if (!static_files.empty()) kept_cloud_.emplace(std::move(static_files));
    hif::apps::makeDirs(pred_dir_);
}

void Outputs::mergeKept(double voxel, std::vector<std::string> files, std::size_t memory_bytes)
{
    const std::string runs = files.front() + ".voxels-";
    voxels_.emplace(voxel, runs, hif::io::VoxelMerger::voxelsWithin(memory_bytes));
    hif::io::PointFields f;
    f.points = true;
    voxel_cloud_.emplace(std::move(files), f);
}

void Outputs::classifyAndWrite(const hif::CHeightIntervalMap& map, const hif::apps::Scan& scan,
                               std::size_t k, bool unload)
{
    // Classified from the observation and its pose, exactly as it was inserted; the clouds get
    // its world points (write()).
    scan.obs->load();
    const auto t0 = Clock::now();
    std::vector<uint8_t> dyn;
    const auto st = map.classify(*scan.obs, scan.robot_pose, dyn);
    classify_ms.push_back(msSince(t0));
    writer_.run(
        [this, scan, dyn = std::move(dyn), st, k, unload]
        {
            write(scan, dyn, st, k);
            if (unload) scan.obs->unload();
        });
}

void Outputs::write(const hif::apps::Scan& scan, const std::vector<uint8_t>& dyn,
                    const hif::ClassifyStats& st, std::size_t k)
{
    const auto t1 = Clock::now();
    const std::size_t frame = frameOf(scan, k);
    if (scans_written_++ == 0 && scan_numbers_)
    {
        // The scan's number, and its time where the input has times (from the first scan on).
        times_ = scan.obs->timestamp != INVALID_TIMESTAMP;
        for (hif::io::CloudWriter* w : {kept_cloud_ ? &*kept_cloud_ : nullptr, &removed_cloud_,
                                        classes_ ? &*classes_ : nullptr})
        {
            if (!w) continue;
            hif::io::PointFields f = w->fields();
            f.scan = true;
            f.time = times_;
            w->setFields(f);
        }
    }
    hif::io::CloudPoint p;
    p.scan = static_cast<uint32_t>(frame);
    p.time = times_ && scan.obs->timestamp != INVALID_TIMESTAMP
                 ? mrpt::Clock::toDouble(scan.obs->timestamp)
                 : std::numeric_limits<double>::quiet_NaN();
    // Intensities where the scan has them (a point cloud with intensity), else 0.
    const mrpt::maps::CPointsMapXYZI* xyzi = nullptr;
    if (const auto* pc = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(scan.obs.get()))
        xyzi = dynamic_cast<const mrpt::maps::CPointsMapXYZI*>(pc->pointcloud.get());
    std::vector<uint32_t> labels(dyn.size());
    std::size_t points = 0;
    // The world points (in double: UTM coordinates keep their millimetres) a chunk at a time.
    constexpr std::size_t kChunk = 4096;
    const auto writeChunk = [&](const hif::CHeightIntervalMap::WorldPointsChunk& c)
    {
        if (c.total != dyn.size())
            throw std::logic_error("classify() and the world points disagree on the size");
        points += c.size;
        for (std::size_t j = 0; j < c.size; ++j)
        {
            const std::size_t i = c.first + j;
            const bool moving = dyn[i] != 0;
            labels[i] = moving ? hif::io::kLabelMoving : hif::io::kLabelStatic;
            if (view_)
                view_->add(c.xs[j], c.ys[j], static_cast<float>(c.zs[j]),
                           moving ? hif::apps::TopView::kRemoved : hif::apps::TopView::kKept);
            if (!std::isfinite(c.xs[j]) || !std::isfinite(c.ys[j]) || !std::isfinite(c.zs[j]))
                continue;  // counted as invalid, labelled moving, not written to a cloud
            p.x = c.xs[j];
            p.y = c.ys[j];
            p.z = c.zs[j];
            p.intensity = xyzi && i < xyzi->size() ? xyzi->getPointIntensity_fast(i) : 0.0f;
            if (moving)
            {
                removed_cloud_.add(p);
                if (removed_points_) keepRemoved(p.x, p.y, p.z);
            }
            else
            {
                if (kept_cloud_) kept_cloud_->add(p);
                if (voxels_) voxels_->add(p.x, p.y, p.z, p.intensity);
            }
            if (classes_)
            {
                const uint8_t* rgb = hif::apps::TopView::kRgb[moving ? hif::apps::TopView::kRemoved
                                                                     : hif::apps::TopView::kKept];
                p.red = rgb[0];
                p.green = rgb[1];
                p.blue = rgb[2];
                p.label = moving ? 1 : 0;
                classes_->add(p);
            }
        }
    };
    if (!hif::CHeightIntervalMap::forEachWorldPointsChunk(*scan.obs, scan.robot_pose, kChunk,
                                                          writeChunk))
        throw std::runtime_error("unsupported observation type " +
                                 std::string(scan.obs->GetRuntimeClass()->className));
    if (points != dyn.size())
        throw std::logic_error("classify() and the world points disagree on the size");
    if (voxels_) voxels_->nextScan();
    if (rawlog_) rawlog_->write(scan, dyn);
    if (frame < written_.size() && written_[frame])
        throw std::runtime_error("two scans of the input are frame " + std::to_string(frame));
    if (frame >= written_.size()) written_.resize(frame + 1, false);
    written_[frame] = true;
    hif::io::writeLabels(
        pred_dir_ + "/" + (scan.name ? *scan.name : hif::io::frameName(frame)) + ".label", labels);
    write_ms_total += msSince(t1);
    points_in += dyn.size();
    points_kept += st.static_points;
    points_removed += st.dynamic_points;
    points_invalid += st.invalid_points;
    points_near += st.near_points;
    points_seen_through += st.seen_through_points;
}

void Outputs::keepRemoved(double x, double y, double z)
{
    std::vector<float>& v = *removed_points_;
    if (v.empty() && std::max({std::abs(x), std::abs(y), std::abs(z)}) >=
                         hif::io::CloudWriter::kFloatCoordinateLimit)
    {
        removed_anchor_[0] = std::floor(x);
        removed_anchor_[1] = std::floor(y);
        removed_anchor_[2] = std::floor(z);
    }
    v.push_back(static_cast<float>(x - removed_anchor_[0]));
    v.push_back(static_cast<float>(y - removed_anchor_[1]));
    v.push_back(static_cast<float>(z - removed_anchor_[2]));
}

void Outputs::writeScene(const hif::CHeightIntervalMap& map, const std::string& file) const
{
    mrpt::opengl::COpenGLScene scene;
    auto kept = mrpt::opengl::CSetOfObjects::Create();
    map.getVisualizationInto(*kept);
    scene.insert(kept);
    if (removed_points_)
    {
        auto removed = mrpt::opengl::CPointCloud::Create();
        removed->setName("hif: removed points");
        const uint8_t* red = hif::apps::TopView::kRgb[hif::apps::TopView::kRemoved];
        removed->setColor_u8(red[0], red[1], red[2]);
        removed->setPointSize(2.0f);
        removed->setLocation(removed_anchor_[0], removed_anchor_[1], removed_anchor_[2]);
        const std::vector<float>& v = *removed_points_;
        removed->reserve(v.size() / 3);
        for (std::size_t i = 0; i + 2 < v.size(); i += 3)
            removed->insertPoint(v[i], v[i + 1], v[i + 2]);
        scene.insert(removed);
    }
    if (!scene.saveToFile(file))
        throw std::runtime_error("Error writing to target file '" + file + "'");
}

std::size_t Outputs::frameOf(const hif::apps::Scan& scan, std::size_t k) const
{
    if (!scan.frame) return first_frame_.value_or(0) + k;
    if (k == 0 && first_frame_ && *first_frame_ != *scan.frame)
        throw std::runtime_error("--first-frame " + std::to_string(*first_frame_) +
                                 " disagrees with the input, whose first scan is frame " +
                                 std::to_string(*scan.frame) + " (leave --first-frame out)");
    return *scan.frame;
}

void Outputs::pictureCovers(const hif::CHeightIntervalMap& map)
{
    writer_.wait();
    if (!view_) return;
    const auto pillars = map.grid().sortedPillars();
    if (pillars.empty()) return;
    // The map's main area, in blocks of about 32 m: a stray point or pose far from the rest
    // must not set the picture's scale. Each block: its pillar count and their extent.
    const hif::GridGeometry& g = map.geometry();
    const auto per_block = static_cast<int64_t>(std::max(1.0, std::round(32.0 / g.pillar_size)));
    const auto block = [per_block](int32_t i)
    { return i >= 0 ? i / per_block : -((-int64_t{i} - 1) / per_block) - 1; };
    struct Extent
    {
        std::size_t pillars = 0;
        int64_t m0 = std::numeric_limits<int64_t>::max(), m1 = std::numeric_limits<int64_t>::min();
        int64_t n0 = m0, n1 = m1;
    };
    std::map<std::pair<int64_t, int64_t>, Extent> by_block;
    for (const auto& [idx, pillar] : pillars)
    {
        Extent& e = by_block[{block(idx.m), block(idx.n)}];
        ++e.pillars;
        e.m0 = std::min<int64_t>(e.m0, idx.m);
        e.m1 = std::max<int64_t>(e.m1, idx.m);
        e.n0 = std::min<int64_t>(e.n0, idx.n);
        e.n1 = std::max<int64_t>(e.n1, idx.n);
    }
    std::vector<hif::apps::WeightedBlock> blocks;
    for (const auto& [b, e] : by_block) blocks.push_back({b.first, b.second, e.pillars});
    const double block_m = double(per_block) * g.pillar_size;
    const std::vector<bool> in = hif::apps::mainArea(
        blocks, static_cast<int64_t>(std::ceil(hif::apps::kAreaLinkMetres / block_m)));
    Extent all;
    std::size_t k = 0;
    for (const auto& [b, e] : by_block)
        if (in[k++])
        {
            all.m0 = std::min(all.m0, e.m0);
            all.m1 = std::max(all.m1, e.m1);
            all.n0 = std::min(all.n0, e.n0);
            all.n1 = std::max(all.n1, e.n1);
        }
    const int64_t m0 = all.m0, m1 = all.m1, n0 = all.n0, n1 = all.n1;
    view_->cover(g.origin_x + double(m0) * g.pillar_size, g.origin_y + double(n0) * g.pillar_size,
                 g.origin_x + double(m1 + 1) * g.pillar_size,
                 g.origin_y + double(n1 + 1) * g.pillar_size);
}

std::optional<hif::apps::TopView::Picture> Outputs::writePicture(const std::string& file,
                                                                 const std::string& title) const
{
    if (!view_ || view_->empty()) return std::nullopt;
    return view_->write(file, title, false);
}

Outputs::RawlogWritten Outputs::closeRawlog()
{
    writer_.wait();
    if (!rawlog_) return {};
    rawlog_->close();
    return {rawlog_->scans, rawlog_->untimed};
}

void Outputs::close()
{
    writer_.wait();
    if (voxels_)
    {
        VoxelMap v;
        v.voxel = voxels_->voxel();
        v.merged = voxels_->pointsAdded();
        hif::io::CloudPoint c;
        v.points = voxels_->finish(
            [&](const hif::io::MergedPoint& p)
            {
                c.x = p.x;
                c.y = p.y;
                c.z = p.z;
                c.intensity = p.intensity;
                c.points = p.points;
                voxel_cloud_->add(c);
            });
        v.spills = voxels_->spills();
        v.peak_voxels = voxels_->peakVoxels();
        voxels_.reset();
        voxel_cloud_->close();
        voxel_map_ = v;
    }
    if (kept_cloud_) kept_cloud_->close();
    removed_cloud_.close();
    if (classes_) classes_->close();
}
