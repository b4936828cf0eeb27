// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   IcpSlam.cpp
 * @brief  ICP-SLAM scan by scan: a constant-velocity guess, CICP against the voxel map of the
 *         static points so far, HIF (online) at the estimated pose, then the trajectory, the
 *         map, the error and the moving points that entered the map.
 */
#include "hif/jobs/IcpSlam.h"

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/slam/CICP.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "hif/CHeightIntervalMap.h"
#include "hif/IniSection.h"
#include "hif/apps/Cli.h"
#include "hif/apps/Config.h"
#include "hif/apps/RunFiles.h"
#include "hif/apps/ScanSource.h"
#include "hif/apps/Staged.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "slam/Trajectory.h"
#include "slam/VoxelMap.h"

namespace fs = std::filesystem;

namespace hif::jobs
{
using hif::apps::Clock;
using hif::apps::msSince;

namespace
{
/** Fewer points than this (after thinning) leave ICP's 6 degrees of freedom undetermined. */
constexpr std::size_t kMinIcpPoints = 3;

/** [SLAM] of the configuration, read as the map's options are (hif::IniSection): every key
 *  known, every value a whole number in its range, a mistake named with the file and section. */
struct Settings : public mrpt::config::CLoadableOptions
{
    double scan_voxel = 0.75;  ///< scans are thinned to one centroid per voxel of this side [m]
    double map_voxel = 0.5;    ///< the map ICP aligns against keeps one point per voxel [m]
    double map_radius = 80;    ///< map points farther from the sensor are dropped [m]
    double min_range = 3;      ///< nearer scan points (the vehicle itself) are not aligned [m]
    double max_range = 80;     ///< farther scan points are not aligned [m]

    void loadFromConfigFile(const mrpt::config::CConfigFileBase& c,
                            const std::string& section) override
    {
        const hif::IniSection s(c, section);
        s.requireKnownKeys({"scan_voxel", "map_voxel", "map_radius", "min_range", "max_range"});
        const auto get = [&](const char* key, double& v, double lo, double hi)
        {
            s.read(key, v);
            if (!(v >= lo && v <= hi))
                s.fail(std::string(key) + " = " + std::to_string(v) + " is not in [" +
                       std::to_string(lo) + ", " + std::to_string(hi) + "]");
        };
        get("scan_voxel", scan_voxel, 0.01, 10);
        get("map_voxel", map_voxel, 0.01, 10);
        get("map_radius", map_radius, 1, 10000);
        get("min_range", min_range, 0, 1000);
        get("max_range", max_range, 0.1, 10000);
        if (min_range >= max_range) s.fail("min_range must be below max_range");
    }
    void saveToConfigFile(mrpt::config::CConfigFileBase& c,
                          const std::string& section) const override
    {
        c.write(section, "scan_voxel", scan_voxel);
        c.write(section, "map_voxel", map_voxel);
        c.write(section, "map_radius", map_radius);
        c.write(section, "min_range", min_range);
        c.write(section, "max_range", max_range);
    }
};

/** Moving points (SemanticKITTI labels) of the scans that entered the ICP map. */
struct MovingInMap
{
    std::size_t labelled_moving = 0, entered_map = 0, scans_labelled = 0;
};

}  // namespace

IcpSlamResult IcpSlam::run(std::ostream& log) const
{
    const IcpSlamOptions& o = options_;
    const auto t_start = Clock::now();
    const std::string& input = o.input;
    const std::string out_dir = hif::apps::cleanDir(o.output);
    const bool use_hif = o.use_hif;
    const std::string cfg_file = o.config ? *o.config : hif::apps::shippedConfig("icp-slam-3d.ini");
    hif::apps::checkConfigFile(cfg_file);
    std::string labels_dir = o.labels;
    if (labels_dir.empty() && fs::is_directory(fs::path(input) / "labels"))
        labels_dir = (fs::path(input) / "labels").string();
    if (!labels_dir.empty() && !fs::is_directory(labels_dir))
        throw std::runtime_error("labels folder '" + labels_dir + "' is not a folder");
    // No output is an input; earlier results are replaced only when asked.
    const std::vector<std::string> names{"poses_kitti.txt", "slam_map.ply", "map.hifmap",
                                         "summary.json"};
    hif::apps::RunFiles files;
    hif::apps::describeInputs(input, files);
    files.input(cfg_file, "the config");
    if (!labels_dir.empty()) files.inputFolder(labels_dir, ".label", "the labels");
    for (const std::string& n : names) files.output(out_dir + "/" + n, "the " + n + " of -o");
    hif::apps::StagedFolder staged(out_dir, names, o.overwrite, "--overwrite");
    const hif::ConfigText cfg(cfg_file);  // read once, by every loader below
    Settings set;
    set.loadFromConfigFile(cfg, "SLAM");
    mrpt::slam::CICP icp;
    icp.options.loadFromConfigFile(cfg, "ICP");

    mrpt::maps::CMultiMetricMap maps;
    hif::CHeightIntervalMap::Ptr hif_map;
    if (use_hif)
    {
        mrpt::maps::TSetOfMetricMapInitializers inits;
        hif::apps::checkMapCounts(cfg, "map", cfg_file);
        inits.loadFromConfigFile(cfg, "map");
        maps.setListOfMaps(inits);
        hif_map = maps.mapByClass<hif::CHeightIntervalMap>();
        if (!hif_map)
            throw std::runtime_error("config '" + cfg_file +
                                     "', section [map] defines no CHeightIntervalMap");
        if (!hif_map->params().online)
            throw std::runtime_error(
                "config '" + cfg_file +
                "': its CHeightIntervalMap is offline (online=false), but SLAM classifies each "
                "scan as it comes: set online=true (as share/hif/config/icp-slam-3d.ini does)");
        // The .ini's threads, else one per hardware thread of this machine.
        if (const auto threads = hif::apps::mapThreads(cfg, "map", std::nullopt))
        {
            hif_map->insertionOptions.threads = *threads;
            hif_map->applyOptions();
        }
    }
    auto source = hif::apps::openScanSource(input, {}, /*poses_required=*/false);
    log << IcpSlam::kTag << " input  : " << input << "\n"
        << IcpSlam::kTag << " config : " << cfg_file << (use_hif ? "" : " (--no-hif)") << "\n"
        << IcpSlam::kTag << " output : " << out_dir << std::endl;

    hif::io::CloudWriter cloud({staged.path() + "/slam_map.ply"});
    hif::slam::VoxelMap local(set.map_voxel);
    std::vector<mrpt::poses::CPose3D> poses, truth;
    bool all_truth = true;
    std::vector<double> scan_ms, icp_ms, hif_ms;
    std::vector<float> xs, ys, zs, sx, sy, sz;
    std::vector<uint8_t> dyn;
    MovingInMap moving;
    std::size_t points_in = 0, points_removed = 0, icp_iterations = 0;
    std::size_t not_aligned = 0;  ///< scans whose pose is the guess: too few points for ICP
    hif::apps::Progress progress(IcpSlam::kTag, "aligning", source->knownSize(), o.show_progress);
    hif::apps::Scan scan;
    for (std::size_t k = 0; source->next(scan); ++k)
    {
        scan.obs->load();
        const auto t0 = Clock::now();
        // Points in the robot frame.
        if (!hif::CHeightIntervalMap::observationToWorldPoints(*scan.obs, mrpt::poses::CPose3D(),
                                                               xs, ys, zs))
            throw std::runtime_error("scan " + std::to_string(k) + " of '" + input +
                                     "' has no points MRPT can give");
        mrpt::poses::CPose3D pose;
        if (k > 0)
        {
            // Constant velocity from the last two poses, refined by ICP against the map.
            const mrpt::poses::CPose3D guess =
                k >= 2 ? poses[k - 1] + (poses[k - 1] - poses[k - 2]) : poses[k - 1];
            const auto thin =
                hif::slam::thinToVoxels(xs, ys, zs, set.scan_voxel, set.min_range, set.max_range);
            pose = guess;
            if (thin.size() < kMinIcpPoints || local.size() < kMinIcpPoints)
                ++not_aligned;  // 6 degrees of freedom need 3 points at least
            else
            {
                const auto t_icp = Clock::now();
                mrpt::slam::CICP::TReturnInfo info;
                const auto pdf = icp.Align3DPDF(&local.points(), &thin,
                                                mrpt::poses::CPose3DPDFGaussian(guess), info);
                icp_ms.push_back(msSince(t_icp));
                icp_iterations += info.nIterations;
                if (info.goodness > 0)
                    pose = pdf->getMeanVal();
                else
                    ++not_aligned;  // nothing matched: the guess stays
            }
        }
        poses.push_back(pose);
        if (scan.has_pose)
            truth.push_back(scan.robot_pose);
        else
            all_truth = false;

        // HIF, online: insert at the estimated pose, then classify with the past only.
        const auto t_hif = Clock::now();
        dyn.assign(xs.size(), 0);
        if (use_hif)
        {
            maps.insertObservation(*scan.obs, pose);
            hif_map->classify(*scan.obs, pose, dyn);
            hif_ms.push_back(msSince(t_hif));
        }
        // The static points enter the map ICP aligns against, and the cleaned map.
        sx.clear();
        sy.clear();
        sz.clear();
        for (std::size_t i = 0; i < xs.size(); ++i)
        {
            if (dyn[i])
            {
                ++points_removed;
                continue;
            }
            sx.push_back(xs[i]);
            sy.push_back(ys[i]);
            sz.push_back(zs[i]);
            if (!std::isfinite(xs[i]) || !std::isfinite(ys[i]) || !std::isfinite(zs[i])) continue;
            double gx, gy, gz;
            pose.composePoint(xs[i], ys[i], zs[i], gx, gy, gz);
            cloud.add(gx, gy, gz, 0.0f);
        }
        points_in += xs.size();
        local.add(hif::slam::thinToVoxels(sx, sy, sz, set.map_voxel, set.min_range, set.max_range),
                  pose);
        local.keepWithin(pose.translation(), set.map_radius);
        scan_ms.push_back(msSince(t0));

        if (!labels_dir.empty())
        {
            const std::string f =
                labels_dir + "/" + hif::io::frameName(scan.frame.value_or(k)) + ".label";
            if (fs::exists(f))
            {
                const auto lab = hif::io::readLabels(f);
                if (lab.size() != xs.size())
                    throw std::runtime_error("'" + f + "' has " + std::to_string(lab.size()) +
                                             " labels for a scan of " + std::to_string(xs.size()) +
                                             " points");
                ++moving.scans_labelled;
                for (std::size_t i = 0; i < lab.size(); ++i)
                    if (hif::io::isMovingClass(lab[i] & 0xFFFFu))
                    {
                        ++moving.labelled_moving;
                        moving.entered_map += dyn[i] ? 0 : 1;
                    }
            }
        }
        scan.obs->unload();
        progress.update(k + 1);
    }
    progress.finish();
    if (poses.empty()) throw std::runtime_error("input '" + input + "' holds no scans");
    if (poses.size() > 1 && not_aligned == poses.size() - 1)
        throw std::runtime_error(
            "ICP could not align any of the " + std::to_string(not_aligned) +
            " scans after the first (fewer than " + std::to_string(kMinIcpPoints) +
            " points each after thinning to scan_voxel within min_range..max_range, or nothing "
            "matched): the poses would be guesses only; check the input's points and [SLAM] of '" +
            cfg_file + "'");

    cloud.close();
    hif::slam::writeKittiPoses(staged.path() + "/poses_kitti.txt", poses);
    if (use_hif) hif_map->saveToFile(staged.path() + "/map.hifmap");
    const std::optional<double> rmse =
        all_truth ? hif::slam::trajectoryRmse(poses, truth) : std::nullopt;
    const double rmse_m = rmse.value_or(-1.0);
    const auto per_scan = hif::apps::timeStats(scan_ms);
    const auto icp_t = hif::apps::timeStats(icp_ms);
    const auto hif_t = hif::apps::timeStats(hif_ms);
    nlohmann::ordered_json j;
    j["input"] = input;
    j["config"] = cfg_file;
    j["hif"] = use_hif;
    j["threads"] =
        hif_map ? nlohmann::json(hif_map->insertionOptions.threads) : nlohmann::json(nullptr);
    j["scans"] = poses.size();
    j["points_in"] = points_in;
    j["points_removed_by_hif"] = points_removed;
    j["map_points"] = local.size();
    j["scan_ms_median"] = per_scan.median;
    j["scan_ms_p90"] = per_scan.p90;
    j["scan_ms_max"] = per_scan.max;
    j["icp_ms_median"] = icp_t.median;
    j["hif_ms_median"] = hif_t.median;
    j["scans_not_aligned"] = not_aligned;
    j["icp_iterations_mean"] =
        icp_ms.empty() ? 0.0 : double(icp_iterations) / double(icp_ms.size());
    j["trajectory_rmse_m"] = rmse ? nlohmann::json(rmse_m) : nlohmann::json(nullptr);
    if (moving.scans_labelled > 0)
        j["moving_points"] = {{"scans_labelled", moving.scans_labelled},
                              {"labelled_moving", moving.labelled_moving},
                              {"entered_map", moving.entered_map}};
    j["total_s"] = msSince(t_start) / 1000.0;
    j["peak_rss_mb"] = hif::apps::peakRssMiB();
    {
        std::ofstream f(staged.path() + "/summary.json");
        f << std::setw(2) << j << "\n";
        if (!f) throw std::runtime_error("cannot write '" + out_dir + "/summary.json'");
    }
    staged.commit();

    log << std::fixed << std::setprecision(3) << IcpSlam::kTag << " scans " << poses.size()
        << ", ms per scan: median " << per_scan.median << " (ICP " << icp_t.median;
    if (use_hif) log << ", HIF " << hif_t.median;
    log << "), p90 " << per_scan.p90 << "\n";
    if (not_aligned > 0)
        log << IcpSlam::kTag << " warning: " << not_aligned << " of " << poses.size() - 1
            << " scans could not be aligned (fewer than " << kMinIcpPoints
            << " points for ICP, or nothing matched): their poses are the constant-velocity "
               "guess\n";
    if (rmse)
        log << IcpSlam::kTag << " trajectory RMSE against the input's poses: " << rmse_m << " m\n";
    else if (poses.size() < 2)
        log << IcpSlam::kTag << " no trajectory error: the input holds one scan\n";
    else
        log << IcpSlam::kTag << " no trajectory error: the input has no pose for every scan\n";
    if (moving.scans_labelled > 0)
        log << IcpSlam::kTag
            << " labelled moving points that entered the map: " << moving.entered_map << " of "
            << moving.labelled_moving << " (" << moving.scans_labelled << " labelled scans)\n";
    log << IcpSlam::kTag << " wrote " << out_dir << "/{poses_kitti.txt, slam_map.ply, summary.json"
        << (use_hif ? ", map.hifmap}" : "}") << "\n";
    IcpSlamResult result;
    result.scans = poses.size();
    result.not_aligned = not_aligned;
    if (rmse) result.rmse_m = rmse_m;
    return result;
}

}  // namespace hif::jobs
