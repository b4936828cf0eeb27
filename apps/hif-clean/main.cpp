// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-clean/main.cpp
 * @brief  Builds the maps of an .ini (a hif::CHeightIntervalMap among them) from a rawlog, a
 *         .simplemap or a DynamicMap benchmark folder, and writes the cleaned static map, the
 *         removed points, per-scan SemanticKITTI predictions, the serialized map and a JSON
 *         summary.
 */
#include <mrpt/3rdparty/tclap/CmdLine.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CMultiMetricMap.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/serialization/CArchive.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "ScanReader.h"
#include "hif/CHeightIntervalMap.h"
#include "hif/apps/CloudFiles.h"
#include "hif/apps/KittiSequence.h"
#include "hif/apps/Labels.h"
#include "hif/apps/Util.h"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace
{
const std::string kTag = "[hif-clean]";

double msSince(Clock::time_point t0)
{
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

/** The shipped KITTI configuration for the mode: installed copy first, then the source tree's. */
std::string defaultConfig(bool online)
{
    const std::string name = online ? "kitti-online.ini" : "kitti.ini";
    for (const std::string& dir :
         {std::string(HIF_INSTALLED_SHARE_DIR), std::string(HIF_SOURCE_SHARE_DIR)})
        if (fs::exists(dir + "/config/" + name)) return dir + "/config/" + name;
    throw std::runtime_error("the default configuration " + name + " was not found in '" +
                             std::string(HIF_INSTALLED_SHARE_DIR) + "/config' nor '" +
                             std::string(HIF_SOURCE_SHARE_DIR) + "/config'; pass -c");
}

struct Cli
{
    TCLAP::CmdLine cmd{
        "hif-clean: removes moving objects from a LiDAR sequence with Height Interval "
        "Filtering. Inserts every scan at its pose into the maps of an .ini (which must "
        "define a CHeightIntervalMap), classifies every point, and writes into the output "
        "folder: static_map.{ply,pcd} and removed.{ply,pcd} (world frame, x y z intensity), "
        "predictions/NNNNNN.label (9 = static, 251 = moving, one per input point in input "
        "order), map.hifmap (the serialized map) and summary.json.",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> input{
        "i",
        "input",
        "Input: an MRPT rawlog with a CObservationRobotPose before each scan (as kitti2rawlog "
        "writes), a .simplemap, or a DynamicMap benchmark folder (pcd/NNNNNN.pcd)",
        true,
        "",
        "in.rawlog|in.simplemap|folder",
        cmd};
    TCLAP::ValueArg<std::string> output{
        "o", "output", "Output folder (created if needed)", true, "", "folder", cmd};
    TCLAP::ValueArg<std::string> config{
        "c",
        "config",
        "Map definition .ini (default: the shipped share/hif/config/kitti.ini, or "
        "kitti-online.ini with --online)",
        false,
        "",
        "config.ini",
        cmd};
    TCLAP::ValueArg<std::string> section{
        "",     "section", "Section of the .ini with the map list (default: map)", false, "map",
        "name", cmd};
    TCLAP::SwitchArg online{
        "", "online",
        "Classify each scan right after inserting it, with the map of the past only (what a "
        "SLAM system gets); default: offline, insert all scans then classify every point "
        "against the final map (two passes over the input)",
        cmd};
    TCLAP::ValueArg<std::size_t> first_frame{
        "",
        "first-frame",
        "Number of the first prediction file, e.g. the --first given to kitti2rawlog "
        "(default: 0)",
        false,
        0,
        "N",
        cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite",
                               "Replace earlier results in the output folder (and "
                               "hif_output.pcd in a DynamicMap folder)",
                               cmd};
    TCLAP::ValueArg<std::size_t> threads{
        "t",
        "threads",
        "Threads for insertion and classification (overrides the .ini's threads; the result "
        "is the same for any count)",
        false,
        1,
        "N",
        cmd};
    TCLAP::SwitchArg hold_scans{
        "", "hold-scans",
        "Offline: keep every scan in memory after inserting it, and classify from memory "
        "instead of reading the input a second time (faster on slow storage; memory grows "
        "with the sequence)",
        cmd};
    TCLAP::SwitchArg quiet{"q", "quiet", "No progress bar", cmd};
};

/** World points of a scan and their intensities (0 when the scan has none). */
void worldPoints(const hif::apps::Scan& scan, std::vector<float>& x, std::vector<float>& y,
                 std::vector<float>& z, std::vector<float>& intensity)
{
    scan.obs->load();
    if (!hif::CHeightIntervalMap::observationToWorldPoints(*scan.obs, scan.robot_pose, x, y, z))
        throw std::runtime_error("unsupported observation type " +
                                 std::string(scan.obs->GetRuntimeClass()->className));
    intensity.assign(x.size(), 0.0f);
    if (const auto* pc = dynamic_cast<const mrpt::obs::CObservationPointCloud*>(scan.obs.get()))
        if (const auto* xyzi =
                dynamic_cast<const mrpt::maps::CPointsMapXYZI*>(pc->pointcloud.get()))
            for (std::size_t i = 0; i < x.size() && i < xyzi->size(); ++i)
                intensity[i] = xyzi->getPointIntensity_fast(i);
}

struct Outputs
{
    hif::apps::CloudWriter kept_cloud, removed_cloud;
    std::string pred_dir;
    std::size_t first_frame;
    std::size_t points_in = 0, points_kept = 0, points_removed = 0, points_invalid = 0;
    double classify_ms_total = 0, write_ms_total = 0;
    std::vector<double> classify_ms;

    /** `static_files` receive the kept points; removed.{ply,pcd} in `dir` the others. */
    Outputs(const std::string& dir, std::size_t first, std::vector<std::string> static_files)
        : kept_cloud(std::move(static_files)),
          removed_cloud({dir + "/removed.ply", dir + "/removed.pcd"}),
          pred_dir(dir + "/predictions"),
          first_frame(first)
    {
        hif::apps::makeDirs(pred_dir);
    }

    /** Classifies scan number `k` against `map` and writes its points and predictions. */
    void classifyAndWrite(const hif::CHeightIntervalMap& map, const hif::apps::Scan& scan,
                          std::size_t k, std::vector<float> buf[4])
    {
        worldPoints(scan, buf[0], buf[1], buf[2], buf[3]);
        const auto t0 = Clock::now();
        const hif::PointsView view{buf[0].data(), buf[1].data(), buf[2].data(), buf[0].size()};
        std::vector<uint8_t> dyn;
        const auto st = map.grid().classify(view, dyn);
        const double ms = msSince(t0);
        classify_ms.push_back(ms);
        classify_ms_total += ms;

        const auto t1 = Clock::now();
        std::vector<uint32_t> labels(dyn.size());
        for (std::size_t i = 0; i < dyn.size(); ++i)
        {
            labels[i] = dyn[i] ? hif::apps::kLabelMoving : hif::apps::kLabelStatic;
            if (!std::isfinite(buf[0][i]) || !std::isfinite(buf[1][i]) || !std::isfinite(buf[2][i]))
                continue;  // counted as invalid, labelled moving, not written to a cloud
            (dyn[i] ? removed_cloud : kept_cloud).add(buf[0][i], buf[1][i], buf[2][i], buf[3][i]);
        }
        hif::apps::writeLabels(pred_dir + "/" + hif::apps::frameName(first_frame + k) + ".label",
                               labels);
        write_ms_total += msSince(t1);
        points_in += dyn.size();
        points_kept += st.static_points;
        points_removed += st.dynamic_points;
        points_invalid += st.invalid_points;
    }
};

int run(Cli& cli)
{
    const auto t_start = Clock::now();
    const std::string out_dir = cli.output.getValue();
    const bool online = cli.online.getValue();
    const std::string cfg_file = cli.config.isSet() ? cli.config.getValue() : defaultConfig(online);
    if (!fs::exists(cfg_file)) throw std::runtime_error("config '" + cfg_file + "' not found");

    // Refuse to replace earlier results unless asked.
    for (const char* f : {"summary.json", "map.hifmap", "static_map.ply", "static_map.pcd",
                          "removed.ply", "removed.pcd", "predictions"})
        hif::apps::refuseToOverwrite(out_dir + "/" + f, cli.overwrite.getValue(), "--overwrite");

    hif::apps::ScanReader reader(cli.input.getValue());
    const bool dynamicmap = reader.kind() == hif::apps::ScanReader::Kind::DynamicMapFolder;
    const std::string dm_output = cli.input.getValue() + "/hif_output.pcd";
    if (dynamicmap)
        hif::apps::refuseToOverwrite(dm_output, cli.overwrite.getValue(), "--overwrite");

    // Maps from the .ini, through MRPT's own machinery.
    mrpt::config::CConfigFile cfg(cfg_file);
    mrpt::maps::TSetOfMetricMapInitializers inits;
    inits.loadFromConfigFile(cfg, cli.section.getValue());
    mrpt::maps::CMultiMetricMap maps(inits);
    const auto hif_map = maps.mapByClass<hif::CHeightIntervalMap>();
    if (!hif_map)
        throw std::runtime_error(
            "config '" + cfg_file + "', section [" + cli.section.getValue() +
            "] defines no CHeightIntervalMap (set CHeightIntervalMap_count=1)");
    if (cli.threads.isSet())
    {
        if (cli.threads.getValue() == 0) throw std::runtime_error("--threads must be >= 1");
        hif_map->insertionOptions.threads = cli.threads.getValue();
    }
    if (cli.hold_scans.getValue() && online)
        throw std::runtime_error("--hold-scans applies to offline mode only (not --online)");
    const hif::Params prm = hif_map->params();

    hif::apps::makeDirs(out_dir);
    if (cli.overwrite.getValue()) fs::remove_all(out_dir + "/predictions");
    std::cout << kTag << " input  : " << cli.input.getValue() << "\n"
              << kTag << " config : " << cfg_file << " [" << cli.section.getValue() << "], "
              << maps.maps.size() << " map(s)\n"
              << kTag << " mode   : "
              << (online ? "online (each scan classified with the past only)"
                         : "offline (all scans inserted, then every point classified)")
              << "\n"
              << kTag << " output : " << out_dir << "\n";

    std::vector<std::string> static_files{out_dir + "/static_map.ply", out_dir + "/static_map.pcd"};
    if (dynamicmap) static_files.push_back(dm_output);  // where that benchmark looks
    Outputs out(out_dir, cli.first_frame.getValue(), std::move(static_files));
    std::vector<double> insert_ms, scan_ms;
    std::vector<float> buf[4];
    hif::apps::Scan scan;
    std::vector<hif::apps::Scan> held;  // --hold-scans
    std::size_t scans = 0;
    const bool show = !cli.quiet.getValue();

    // Pass 1: insertion (and, online, classification of each scan after its insertion).
    {
        hif::apps::Progress progress(kTag, online ? "inserting+classifying" : "inserting",
                                     reader.knownSize(), show);
        while (reader.next(scan))
        {
            scan.obs->load();
            const auto t0 = Clock::now();
            maps.insertObservation(*scan.obs, scan.robot_pose);
            const double ms = msSince(t0);
            insert_ms.push_back(ms);
            if (online)
            {
                out.classifyAndWrite(*hif_map, scan, scans, buf);
                scan_ms.push_back(ms + out.classify_ms.back());
            }
            else
                scan_ms.push_back(ms);
            if (cli.hold_scans.getValue())
                held.push_back(scan);
            else
                scan.obs->unload();
            ++scans;
            progress.update(scans);
        }
        progress.finish();
    }
    if (scans == 0) throw std::runtime_error("input '" + cli.input.getValue() + "' holds no scans");

    // Pass 2 (offline): classify every point of every scan against the final map.
    if (!online)
    {
        hif::apps::Progress progress(kTag, "classifying", scans, show);
        std::size_t k = 0;
        if (cli.hold_scans.getValue())
            for (hif::apps::Scan& s : held)
            {
                out.classifyAndWrite(*hif_map, s, k, buf);
                s.obs.reset();  // release each scan once it is written
                progress.update(++k);
            }
        else
        {
            reader.rewind();
            while (reader.next(scan))
            {
                out.classifyAndWrite(*hif_map, scan, k, buf);
                scan.obs->unload();
                progress.update(++k);
            }
        }
        progress.finish();
    }

    // Files.
    const auto t_files = Clock::now();
    out.kept_cloud.close();
    out.removed_cloud.close();
    {
        mrpt::io::CFileGZOutputStream f;
        if (!f.open(out_dir + "/map.hifmap", 1))
            throw std::runtime_error("Error writing to target file '" + out_dir + "/map.hifmap'");
        auto arch = mrpt::serialization::archiveFrom(f);
        arch << *hif_map;
    }
    const double files_ms = msSince(t_files) + out.write_ms_total;

    const auto ins = hif::apps::timeStats(insert_ms);
    const auto per_scan = hif::apps::timeStats(scan_ms);
    const auto cls = hif::apps::timeStats(out.classify_ms);
    const double total_s = msSince(t_start) / 1000.0;
    const double rss = hif::apps::peakRssMiB();

    nlohmann::ordered_json j;
    j["input"] = cli.input.getValue();
    j["config"] = cfg_file;
    j["mode"] = online ? "online" : "offline";
    j["scans"] = scans;
    j["points_in"] = out.points_in;
    j["points_kept"] = out.points_kept;
    j["points_removed"] = out.points_removed;
    j["points_invalid"] = out.points_invalid;
    j["pillars"] = hif_map->pillarCount();
    j["intervals"] = hif_map->intervalCount();
    j["max_intervals_per_pillar_seen"] = hif_map->grid().maxIntervalsInAPillar();
    j["map_bytes"] = hif_map->grid().memoryBytes();
    j["threads"] = hif_map->grid().threads();
    j["held_scans"] = cli.hold_scans.getValue();
    j["scan_ms_median"] = per_scan.median;
    j["scan_ms_p90"] = per_scan.p90;
    j["scan_ms_max"] = per_scan.max;
    j["insert_ms_median"] = ins.median;
    j["classify_ms_median"] = cls.median;
    j["files_s"] = files_ms / 1000.0;
    j["total_s"] = total_s;
    j["peak_rss_mb"] = rss;
    j["skipped_objects"] = reader.skippedObjects();
    nlohmann::ordered_json pj;
    pj["pillar_size"] = prm.pillar_size;
    pj["origin_x"] = prm.origin_x;
    pj["origin_y"] = prm.origin_y;
    pj["height_resolution"] = prm.height_resolution;
    pj["merge_gap"] = prm.merge_gap;
    pj["interval_padding"] = prm.interval_padding;
    pj["alpha"] = prm.alpha;
    pj["beta"] = prm.beta;
    pj["p_min"] = prm.p_min;
    pj["p_max"] = prm.p_max;
    pj["p_empty_init"] = prm.p_empty_init;
    pj["low_height_preservation"] = prm.low_height_preservation;
    pj["high_height_preservation"] = prm.high_height_preservation;
    pj["unseen_height_prior"] = prm.unseen_height_prior;
    pj["beam_spacing_deg"] = prm.beam_spacing_deg;
    pj["see_through_range"] = prm.see_through_range;
    pj["see_through_margin"] = prm.see_through_margin;
    pj["static_threshold"] = prm.static_threshold;
    pj["max_intervals_per_pillar"] = prm.max_intervals_per_pillar;
    j["parameters"] = pj;
    {
        std::ofstream f(out_dir + "/summary.json");
        f << std::setw(2) << j << "\n";
        if (!f)
            throw std::runtime_error("Error writing to target file '" + out_dir + "/summary.json'");
    }

    std::cout << std::fixed << std::setprecision(2) << kTag << " scans " << scans << ", points "
              << out.points_in << ": kept " << out.points_kept << ", removed " << out.points_removed
              << " ("
              << 100.0 * double(out.points_removed) /
                     double(std::max<std::size_t>(1, out.points_in))
              << "%)"
              << (out.points_invalid ? ", invalid " + std::to_string(out.points_invalid) : "")
              << "\n"
              << kTag << " map: " << hif_map->pillarCount() << " pillars, "
              << hif_map->intervalCount() << " intervals, "
              << double(hif_map->grid().memoryBytes()) / (1024.0 * 1024.0) << " MiB\n"
              << kTag << " ms per scan (" << (online ? "insert+classify" : "insert") << "): median "
              << per_scan.median << ", p90 " << per_scan.p90 << ", max " << per_scan.max
              << "; classify median " << cls.median << "\n"
              << kTag << " total " << total_s << " s, peak memory " << rss << " MiB\n"
              << kTag << " wrote " << out_dir << "/{static_map,removed}.{ply,pcd}, predictions/, "
              << "map.hifmap, summary.json" << (dynamicmap ? " and " + dm_output : "") << "\n";
    return 0;
}
}  // namespace

int main(int argc, char** argv) { return hif::apps::cliMain<Cli>(kTag.c_str(), argc, argv, run); }
