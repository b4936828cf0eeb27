// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Summary.cpp
 * @brief  summary.json and the closing report.
 */
#include "Summary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "hif/io/Trajectory.h"

namespace
{
/** Every field of a settings struct, by its table (hif/FieldTable.h). */
template <typename S>
void addFields(nlohmann::ordered_json& j, const S& s)
{
    hif::forEachField<S>([&](const hif::Field<S>& f, auto member) { j[f.name] = s.*member; });
}
}  // namespace

void writeSummary(const std::string& file, const SummaryInfo& info,
                  const hif::CHeightIntervalMap& map, const Outputs& out, const Timings& t)
{
    const auto ins = hif::apps::timeStats(t.insert_ms);
    const auto per_scan = hif::apps::timeStats(t.scan_ms);
    const auto cls = hif::apps::timeStats(out.classify_ms);
    nlohmann::ordered_json j;
    j["input"] = info.input;
    if (info.trajectory.empty())
        j["poses"] = nullptr;  // the input's own
    else
    {
        nlohmann::ordered_json extrinsic = nullptr;
        if (info.extrinsic) extrinsic = hif::io::xyzQxyzw(*info.extrinsic);
        j["poses"] = {{"trajectory", info.trajectory},
                      {"extrinsic_xyz_qxyzw", extrinsic},
                      {"world_frame", info.world_frame}};
    }
    j["config"] = info.config;
    j["mode"] = info.online ? "online" : "offline";
    j["scans"] = t.scans;
    j["points_in"] = out.points_in;
    j["points_kept"] = out.points_kept;
    j["points_removed"] = out.points_removed;
    j["points_invalid"] = out.points_invalid;
    j["points_near"] = out.points_near;
    j["points_seen_through"] = out.points_seen_through;
    if (const auto& v = out.voxelMap())
        j["voxel_map"] = {{"voxel_m", v->voxel},
                          {"points", v->points},
                          {"points_merged", v->merged},
                          {"voxels_in_memory_max", v->peak_voxels},
                          {"run_files", v->spills}};
    j["pillars"] = map.pillarCount();
    j["intervals"] = map.intervalCount();
    j["intervals_static"] = map.grid().staticIntervalCount();  // the boxes of map.3Dscene
    j["max_intervals_per_pillar_seen"] = map.grid().maxIntervalsInAPillar();
    j["map_bytes"] = map.grid().memoryBytes();
    j["threads"] = map.grid().threads();
    j["held_scans"] = info.held_scans;
    j["scan_ms_median"] = per_scan.median;
    j["scan_ms_p90"] = per_scan.p90;
    j["scan_ms_max"] = per_scan.max;
    j["insert_ms_median"] = ins.median;
    j["classify_ms_median"] = cls.median;
    j["files_s"] = t.files_ms / 1000.0;
    j["stages_s"] = {{"setup", t.setup_s},
                     {"insert_pass", t.insert_pass_s},
                     {"classify_pass", t.classify_pass_s},
                     {"finish", t.finish_s}};
    j["total_s"] = t.total_s;
    j["peak_rss_mb"] = hif::apps::peakRssMiB();
    j["skipped_objects"] = info.skipped_objects;
    j["scans_left_out"] = info.scans_left_out;
    j["cloud_coordinates"] = out.doubleCoordinates() ? "float64" : "float32";
    if (info.picture)
        j["picture"] = {{"width", info.picture->width},
                        {"height", info.picture->height},
                        {"cell_m", info.picture->cell_metres},
                        {"points_outside", info.picture->points_outside}};
    if (const auto& m = map.grid().sensorModel())
    {
        nlohmann::ordered_json sj;
        sj["beams"] = m->beam_elevations_deg.size();
        sj["beam_elevations_deg"] = m->beam_elevations_deg;
        sj["elevation_min_deg"] = m->elevation_min_deg;
        sj["elevation_max_deg"] = m->elevation_max_deg;
        sj["vertical_spacing_deg"] = m->vertical_spacing_deg;
        sj["horizontal_resolution_deg"] = m->horizontal_resolution_deg;
        sj["azimuth_coverage_deg"] = m->azimuth_coverage_deg;
        // p_empty_init, or 0.5 where that is under it for a sensor without rings
        sj["p_empty_of_a_new_pillar"] = map.grid().pEmptyInit();
        if (info.sensor.estimated_from_scan)
            sj["estimated_from_scan"] = *info.sensor.estimated_from_scan;
        else
            sj["given"] = true;  // in the config (or the map read back)
        sj["scans_checked"] = info.sensor.checks;
        sj["contradictions"] = info.sensor.contradictions;
        j["sensor"] = sj;
    }
    else
        j["sensor"] = nullptr;
    if (info.poses && info.poses->pairs() > 0)
    {
        // NaN (no pair with enough points above the sensor) is written as null.
        const auto number = [](double v)
        { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); };
        j["poses_check"] = {
            {"pairs", info.poses->pairs()},
            {"overlap", info.poses->medianOverlap()},
            {"overlap_above_sensor", number(info.poses->medianAbove())},
            {"overlap_above_sensor_without_motion", number(info.poses->medianAboveNoMotion())},
            {"doubted", info.poses_doubted}};
    }
    else
        j["poses_check"] = nullptr;
    nlohmann::ordered_json pj;
    addFields(pj, map.geometry());
    addFields(pj, map.params());
    j["parameters"] = pj;
    std::ofstream f(file);
    f << std::setw(2) << j << "\n";
    if (!f) throw std::runtime_error("Error writing to target file '" + file + "'");
}

void printReport(std::ostream& log, const std::string& tag, const std::string& out_dir,
                 const std::string& format, const std::string& dm_output, bool online,
                 const hif::CHeightIntervalMap& map, const Outputs& out, const Timings& t,
                 const std::vector<std::string>& extra)
{
    const auto per_scan = hif::apps::timeStats(t.scan_ms);
    const auto cls = hif::apps::timeStats(out.classify_ms);
    log << std::fixed << std::setprecision(2) << tag << " scans " << t.scans << ", points "
        << out.points_in << ": kept " << out.points_kept << ", removed " << out.points_removed
        << " ("
        << 100.0 * double(out.points_removed) / double(std::max<std::size_t>(1, out.points_in))
        << "%)" << (out.points_invalid ? ", invalid " + std::to_string(out.points_invalid) : "")
        << (out.points_near ? ", nearer than min_range " + std::to_string(out.points_near) : "")
        << (out.points_seen_through
                ? "; the free-space test removed " + std::to_string(out.points_seen_through)
                : "")
        << "\n"
        << tag << " map: " << map.pillarCount() << " pillars, " << map.intervalCount()
        << " intervals, " << double(map.grid().memoryBytes()) / (1024.0 * 1024.0) << " MiB\n"
        << tag << " ms per scan (" << (online ? "insert+classify" : "insert") << "): median "
        << per_scan.median << ", p90 " << per_scan.p90 << ", max " << per_scan.max
        << "; classify median " << cls.median << "\n"
        << tag << " total " << t.total_s << " s, peak memory " << hif::apps::peakRssMiB()
        << " MiB\n";
    if (const auto& v = out.voxelMap())
        log << tag << " static_map: " << v->points << " voxels of " << std::defaultfloat
            << std::setprecision(6) << v->voxel << std::fixed << std::setprecision(2)
            << " m from the " << v->merged << " kept points\n";
    log << tag << " wrote " << out_dir << "/{static_map,removed}."
        << (format == "both" ? "{ply,pcd}" : format) << (out.drawsPicture() ? ", map.png" : "")
        << ", predictions/, map.hifmap, ";
    for (const std::string& f : extra) log << f << ", ";
    log << "summary.json" << (dm_output.empty() ? "" : " and " + dm_output) << "\n";
}
