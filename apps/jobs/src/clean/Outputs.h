// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Outputs.h
 * @brief  What hif-clean writes per scan (predictions, kept and removed points) and the timings
 *         of a run.
 */
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "RawlogOut.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/apps/Cli.h"
#include "hif/apps/ScanSource.h"
#include "hif/apps/TopView.h"
#include "hif/apps/Worker.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/VoxelMerger.h"

using hif::apps::Clock;
using hif::apps::msSince;

/** Times of a run, milliseconds per scan unless named otherwise. */
struct Timings
{
    std::vector<double> insert_ms;
    std::vector<double> scan_ms;  ///< insert, or insert + classify online
    std::size_t scans = 0;
    std::size_t points = 0;  ///< in the scans inserted, where their type tells without converting
    double files_ms = 0;
    /** Wall time of each stage: set-up (config, maps, input opened), pass 1 (insert, and online
     *  classify), pass 2 (offline classify), finish (clouds completed, map saved). */
    double setup_s = 0, insert_pass_s = 0, classify_pass_s = 0, finish_s = 0;
    double total_s = 0;
};

/** The per-scan outputs: predictions/NNNNNN.label, and the points into the static and removed
 *  clouds (streamed to disk). */
class Outputs
{
public:
    /** `static_files` (none, or some) receive the kept points, `removed_files` the others.
     *  Predictions are named after each scan's frame number when the input gives it (then
     *  `first_frame`, if given, must be the first scan's), else `first_frame` (default 0) + k. */
    Outputs(const std::string& dir, std::optional<std::size_t> first_frame,
            std::vector<std::string> static_files, std::vector<std::string> removed_files);

    /** Classifies scan number `k` against `map`, then writes its points and predictions on
     *  the outputs' thread while the caller goes on (`scan` is unloaded once written, with
     *  `unload`). One scan at a time: the call waits for the writing of the scan before, and
     *  throws what that writing threw (close() throws it for the last scan). */
    void classifyAndWrite(const hif::CHeightIntervalMap& map, const hif::apps::Scan& scan,
                          std::size_t k, bool unload);
    /** Before the first scan is classified: about how many points the kept cloud will get (a
     *  guess: right to the number of digits, it saves a copy of that file). */
    void expectKept(std::size_t points)
    {
        writer_.wait();
        if (kept_cloud_) kept_cloud_->expectCount(points);
    }
    /** Before the first scan: the kept points also go to `files`, merged per cubic voxel of
     *  `voxel` metres (x y z: their centroid, intensity: their mean, uint points: how many), in
     *  bounded memory (a table of at most `memory_bytes` for the voxels around the sensor; the
     *  others wait in run files next to the first file, merged at close()). */
    void mergeKept(double voxel, std::vector<std::string> files, std::size_t memory_bytes);
    /** The voxel map, if written (complete after close()). */
    struct VoxelMap
    {
        double voxel = 0;
        std::size_t points = 0;  ///< voxels written
        std::size_t merged = 0;  ///< kept points merged into them
        std::size_t spills = 0;  ///< run files written on the way
        std::size_t peak_voxels = 0;
    };
    [[nodiscard]] const std::optional<VoxelMap>& voxelMap() const { return voxel_map_; }
    /** Also writes every point to `file`, a PLY: x y z, intensity, a colour by its class
     *  (TopView::kRgb: kept light grey, removed red) and the class (0 kept, 1 removed). */
    void writeClasses(const std::string& file)
    {
        hif::io::PointFields f;
        f.colour = f.label = true;
        classes_.emplace(std::vector<std::string>{file}, f);
    }
    /** Before the first scan: every cloud also gets each point's scan number (the number of
     *  its predictions file) and, if the first scan has a time stamp, its scan's time. */
    void writeScanNumbers() { scan_numbers_ = true; }
    /** Also writes every scan without its dynamic points to `file`, an MRPT rawlog (the one
     *  the user named `name`), gzip-compressed at `level` (0: not compressed). */
    void writeRawlog(const std::string& file, const std::string& name, int level)
    {
        rawlog_.emplace(file, level, name);
    }
    /** The cleaned rawlog, if written: completes it and says how many scans it holds. */
    struct RawlogWritten
    {
        std::size_t scans = 0;
        std::size_t untimed = 0;  ///< of them, written with their number for a time
    };
    RawlogWritten closeRawlog();
    /** Before the first scan: the removed points are also kept in memory (12 bytes each), for
     *  writeScene(). */
    void collectRemoved() { removed_points_.emplace(); }
    /** Writes `file`, a scene for MRPT's SceneViewer3D: what `map` keeps (its static intervals,
     *  getVisualizationInto()) and, if collected, the removed points in red. Throws
     *  std::runtime_error naming the file if it cannot be written. */
    void writeScene(const hif::CHeightIntervalMap& map, const std::string& file) const;
    /** Also draws every point into a bird's-eye picture (see writePicture()). */
    void drawPicture() { view_.emplace(); }
    /** Before the first point: the picture's cells sized for the map's main area. */
    void pictureCovers(const hif::CHeightIntervalMap& map);
    /** Writes the picture as a PNG, if drawn and any point can be drawn; says how. */
    [[nodiscard]] std::optional<hif::apps::TopView::Picture> writePicture(
        const std::string& file, const std::string& title) const;
    /** Whether the clouds hold float64 coordinates (some point at 8 km or more from the
     *  origin: UTM and the like). */
    [[nodiscard]] bool doubleCoordinates() const
    {
        return (kept_cloud_ && kept_cloud_->doubleCoordinates()) ||
               removed_cloud_.doubleCoordinates() ||
               (voxel_cloud_ && voxel_cloud_->doubleCoordinates());
    }
    /** Whether a picture is drawn. */
    [[nodiscard]] bool drawsPicture() const { return view_.has_value(); }
    /** Waits for the last scan's writing (throwing what it threw), then completes the cloud
     *  files. */
    void close();

    /** Counts of the scans written (complete after close()). */
    std::size_t points_in = 0, points_kept = 0, points_removed = 0, points_invalid = 0;
    std::size_t points_near = 0, points_seen_through = 0;
    std::vector<double> classify_ms;
    double write_ms_total = 0;  ///< on the outputs' thread (complete after close())

private:
    /** classifyAndWrite()'s writing, on the outputs' thread. */
    void write(const hif::apps::Scan& scan, const std::vector<uint8_t>& dyn,
               const hif::ClassifyStats& st, std::size_t k);
    /** Keeps a removed point for writeScene(). */
    void keepRemoved(double x, double y, double z);
    /** The number of scan `k` (its predictions file's): the input's, else first_frame + k. */
    [[nodiscard]] std::size_t frameOf(const hif::apps::Scan& scan, std::size_t k) const;

    std::optional<hif::io::CloudWriter> kept_cloud_;
    hif::io::CloudWriter removed_cloud_;
    std::optional<hif::io::VoxelMerger> voxels_;       ///< with mergeKept()
    std::optional<hif::io::CloudWriter> voxel_cloud_;  ///< where they go
    std::optional<VoxelMap> voxel_map_;
    std::string pred_dir_;
    std::optional<std::size_t> first_frame_;
    std::vector<bool> written_;  ///< frame numbers written, to refuse a second scan of one
    std::optional<hif::apps::TopView> view_;
    /** With collectRemoved(): the removed points, float32 relative to removed_anchor_ (the
     *  first one's metre when it lies 8 km or more from the origin: UTM keeps millimetres). */
    std::optional<std::vector<float>> removed_points_;
    double removed_anchor_[3] = {0, 0, 0};
    std::optional<RawlogOut> rawlog_;
    std::optional<hif::io::CloudWriter> classes_;
    bool scan_numbers_ = false;
    bool times_ = false;  ///< with scan_numbers_: the scans' times too
    std::size_t scans_written_ = 0;
    hif::apps::Worker writer_;  ///< last: its job ends before the rest goes
};
