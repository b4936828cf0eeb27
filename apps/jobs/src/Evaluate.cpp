// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Evaluate.cpp
 * @brief  Predictions scored against SemanticKITTI labels, scan by scan, per moving class and
 *         per range band; the tables on the log, the scores in JSON, the outcomes drawn.
 */
#include "hif/jobs/Evaluate.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "hif/apps/Cli.h"
#include "hif/apps/RunFiles.h"
#include "hif/apps/Staged.h"
#include "hif/apps/TopView.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/FileError.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"

namespace fs = std::filesystem;

namespace hif::jobs
{
namespace
{
/** printf's formatting, onto `log`, whole however long (folder names can be). */
__attribute__((format(printf, 2, 3))) void say(std::ostream& log, const char* format, ...)
{
    va_list args, again;
    va_start(args, format);
    va_copy(again, args);
    const int n = std::vsnprintf(nullptr, 0, format, args);
    va_end(args);
    std::string line(n > 0 ? static_cast<std::size_t>(n) : 0, '\0');
    if (n > 0) std::vsnprintf(line.data(), line.size() + 1, format, again);
    va_end(again);
    log << line;
}

nlohmann::ordered_json toJson(const hif::io::Scores& s)
{
    nlohmann::ordered_json j;
    j["SA"] = s.sa();
    j["DA"] = s.da();
    j["AA"] = s.aa();
    j["HA"] = s.ha();
    j["static_total"] = s.static_total;
    j["static_kept"] = s.static_kept;
    j["dynamic_total"] = s.dynamic_total;
    j["dynamic_removed"] = s.dynamic_removed;
    j["ignored"] = s.ignored;
    return j;
}

/** Ranges from the sensor of the points of scan `stem` (NaN when `dir` is empty). */
std::vector<double> ranges(const std::string& dir, const std::string& stem, std::size_t n)
{
    if (dir.empty()) return std::vector<double>(n, std::nan(""));
    std::vector<double> r;
    const fs::path bin = fs::path(dir) / (stem + ".bin"), pcd = fs::path(dir) / (stem + ".pcd");
    if (fs::exists(bin))
    {
        const hif::io::Cloud c = hif::io::readKittiBin(bin.string());
        if (c.size() != n)
            hif::io::throwFileError(bin.string(), "does not hold the " + std::to_string(n) +
                                                      " points of its label file");
        for (std::size_t i = 0; i < n; ++i)
            r.push_back(std::sqrt(double(c.x[i]) * c.x[i] + double(c.y[i]) * c.y[i] +
                                  double(c.z[i]) * c.z[i]));
        return r;
    }
    if (fs::exists(pcd))
    {
        const hif::io::PcdCloud c = hif::io::readPcd(pcd.string());
        if (c.size() != n)
            hif::io::throwFileError(pcd.string(), "does not hold the " + std::to_string(n) +
                                                      " points of its label file");
        if (!c.has_viewpoint)
            hif::io::throwFileError(pcd.string(),
                                    "has no VIEWPOINT line (the sensor pose), so its points' "
                                    "ranges are unknown");
        const Eigen::Vector3d s = c.viewpoint.translation();
        for (std::size_t i = 0; i < n; ++i) r.push_back((c.point(i) - s).norm());
        return r;
    }
    hif::io::throwFileError(dir, "has neither " + stem + ".bin nor " + stem + ".pcd");
}

/** World points of a scan, in double (UTM coordinates keep their millimetres). */
struct WorldPoints
{
    std::vector<double> x, y, z;
    [[nodiscard]] std::size_t size() const { return x.size(); }
};

/** The points of scan `stem` of `dir` in the world frame: a KITTI velodyne folder's at the
 *  poses of its sequence (`seq`), a DynamicMap pcd folder's as they are. */
WorldPoints worldPoints(const std::string& dir, const std::string& stem,
                        const std::optional<hif::io::KittiSequence>& seq)
{
    WorldPoints w;
    const auto put = [&w](const Eigen::Vector3d& p)
    {
        w.x.push_back(p.x());
        w.y.push_back(p.y());
        w.z.push_back(p.z());
    };
    const fs::path pcd = fs::path(dir) / (stem + ".pcd");
    if (fs::exists(pcd))
    {
        const hif::io::PcdCloud c = hif::io::readPcd(pcd.string());
        for (std::size_t i = 0; i < c.size(); ++i) put(c.point(i));
        return w;
    }
    if (!seq)
        hif::io::throwFileError(dir, "has no " + stem +
                                         ".pcd, and is not the velodyne/ folder of "
                                         "a KITTI sequence (for its poses)");
    const std::size_t i = std::stoul(stem);
    const hif::io::Cloud c = seq->readScan(i);
    const Eigen::Isometry3d& T = seq->pose(i);
    for (std::size_t k = 0; k < c.size(); ++k) put(T * Eigen::Vector3d(c.x[k], c.y[k], c.z[k]));
    return w;
}

/** Prediction values that are neither static (9) nor moving (251-259): scored as static, and
 *  reported (another tool's labels, a semantic class, 0 for "not judged"). */
struct OtherValues
{
    std::size_t points = 0, files = 0;
    std::string example;  ///< the first one seen: "<value> in <file>"
};

void printRow(std::ostream& log, const char* name, const hif::io::Scores& s)
{
    say(log, "%-14s %9zu %9zu %7.2f %7.2f %7.2f %7.2f\n", name, s.static_total, s.dynamic_total,
        s.sa(), s.da(), s.aa(), s.ha());
}

/** `v` in `width` characters with `decimals` decimals, or "-" there when there is none to
 *  give (a band without static or dynamic points has no score for them, as in the README's
 *  tables; an object without ranges no mean range). */
std::string orDash(bool have, double v, int width, int decimals)
{
    char text[48];
    if (have)
        std::snprintf(text, sizeof text, "%*.*f", width, decimals, v);
    else
        std::snprintf(text, sizeof text, "%*s", width, "-");
    return text;
}
}  // namespace

EvaluateResult Evaluate::run(std::ostream& log) const
{
    const EvaluateOptions& o = options_;
    const std::string pred_dir = hif::apps::cleanDir(o.predictions);
    const std::string label_dir = hif::apps::cleanDir(o.labels);
    const std::string scan_dir = hif::apps::cleanDir(o.scans);
    for (const auto& [dir, what] :
         {std::pair{pred_dir, "predictions"}, {label_dir, "labels"}, {scan_dir, "scans"}})
        if (!dir.empty() && !fs::is_directory(dir))
            throw std::runtime_error(std::string(what) + " folder '" + dir +
                                     (fs::exists(dir) ? "' is not a folder" : "' does not exist"));
    std::error_code same_ec;
    if (fs::equivalent(pred_dir, label_dir, same_ec))
        throw std::runtime_error("--labels and --predictions are the same folder '" + label_dir +
                                 "': the labels would be scored against themselves");
    const double ego_radius = o.ego_radius;
    if (!(ego_radius >= 0.0))
        throw std::runtime_error("--ego-radius must be >= 0, not " + std::to_string(ego_radius));
    if ((o.png || o.classes_ply) && scan_dir.empty())
        throw std::runtime_error("--png and --classes-ply need --scans (where the points are)");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(pred_dir))
        if (e.path().extension() == ".label") names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    if (names.empty()) throw std::runtime_error("no .label files in '" + pred_dir + "'");

    // What the run reads, and what it writes: never an input, never replaced unasked.
    std::optional<hif::io::KittiSequence> kitti;  // for the poses of velodyne/ scans
    hif::apps::RunFiles files;
    files.inputFolder(label_dir, ".label", "the ground truth (--labels)");
    files.inputFolder(pred_dir, ".label", "the predictions (--predictions)");
    if (!scan_dir.empty())
    {
        files.inputFolder(scan_dir, ".bin", "the scans (--scans)");
        files.inputFolder(scan_dir, ".pcd", "the scans (--scans)");
        const fs::path seq_dir = fs::path(scan_dir).parent_path();
        if ((o.png || o.classes_ply) && fs::path(scan_dir).filename() == "velodyne" &&
            fs::exists(seq_dir / "poses.txt"))
        {
            kitti.emplace(seq_dir.string());
            for (const char* f : {"poses.txt", "calib.txt", "times.txt"})
                files.input((seq_dir / f).string(), std::string("the sequence's ") + f);
        }
    }
    const bool overwrite = o.overwrite;
    std::optional<hif::apps::StagedFile> json_file, png_file, ply_file;
    const std::tuple<const std::optional<std::string>*, std::optional<hif::apps::StagedFile>*,
                     const char*>
        written[] = {{&o.json, &json_file, "--json"},
                     {&o.png, &png_file, "--png"},
                     {&o.classes_ply, &ply_file, "--classes-ply"}};
    // All checked against the inputs and each other before the first is staged.
    for (const auto& [arg, staged, flag] : written)
        if (*arg) files.output(**arg, flag);
    for (const auto& [arg, staged, flag] : written)
        if (*arg) staged->emplace(**arg, overwrite, flag);

    std::optional<hif::apps::TopView> view;
    std::optional<hif::io::CloudWriter> outcome_cloud;
    if (png_file) view.emplace();
    if (ply_file)
        outcome_cloud.emplace(std::vector<std::string>{ply_file->path()},
                              hif::io::PointFields::colourOnly());
    hif::io::Breakdown total;
    hif::io::Scores with_ego;  ///< the DynamicMap benchmark's way (needs ranges)
    // --objects: each moving object (its full label: class and instance id).
    struct Object
    {
        std::size_t scans = 0, points = 0, removed = 0, ranged = 0;
        double range_sum = 0.0;
        std::size_t last_scan = std::numeric_limits<std::size_t>::max();
    };
    std::map<uint32_t, Object> objects;
    std::size_t without_truth = 0, scored = 0;
    OtherValues other;
    nlohmann::ordered_json scans = nlohmann::ordered_json::array();
    if (o.per_scan)
        say(log, "%-14s %9s %9s %7s %7s %7s %7s\n", "scan", "static", "dynamic", "SA", "DA", "AA",
            "HA");
    for (const std::string& name : names)
    {
        const std::string truth_file = (fs::path(label_dir) / name).string();
        if (!fs::exists(truth_file))
        {
            ++without_truth;
            continue;
        }
        ++scored;
        const std::string stem = fs::path(name).stem().string();
        const std::string pred_file = (fs::path(pred_dir) / name).string();
        const auto truth = hif::io::readLabels(truth_file);
        const auto pred = hif::io::readLabels(pred_file);
        if (truth.size() != pred.size())
            throw std::runtime_error("'" + pred_file + "' has " + std::to_string(pred.size()) +
                                     " points, '" + truth_file + "' has " +
                                     std::to_string(truth.size()));
        std::size_t odd = 0;
        for (const uint32_t p : pred)
        {
            const uint32_t c = p & 0xffffu;
            if (c == hif::io::kLabelStatic || hif::io::isPredictedMoving(c)) continue;
            if (other.example.empty())
                other.example = std::to_string(c) + " in '" + pred_file + "'";
            ++odd;
        }
        other.points += odd;
        other.files += odd > 0;
        const std::vector<double> range = ranges(scan_dir, stem, truth.size());
        hif::io::Breakdown s;
        for (std::size_t i = 0; i < truth.size(); ++i)
        {
            const bool removed = hif::io::isPredictedMoving(pred[i]);
            s.add(truth[i], removed, range[i]);
            if (o.objects && hif::io::isMovingClass(truth[i] & 0xffffu))
            {
                Object& ob = objects[truth[i]];
                if (ob.last_scan != scored) ++ob.scans;
                ob.last_scan = scored;
                ++ob.points;
                ob.removed += removed;
                if (std::isfinite(range[i]))
                {
                    ++ob.ranged;
                    ob.range_sum += range[i];
                }
            }
            const bool ego = range[i] < ego_radius;
            with_ego.add(ego ? 252u : truth[i], removed);
        }
        if (view || outcome_cloud)
        {
            using V = hif::apps::TopView;
            const WorldPoints w = worldPoints(scan_dir, stem, kitti);
            if (w.size() != truth.size())
                hif::io::throwFileError(scan_dir, stem + " does not hold the " +
                                                      std::to_string(truth.size()) +
                                                      " points of its label file");
            for (std::size_t i = 0; i < w.size(); ++i)
            {
                const bool removed = hif::io::isPredictedMoving(pred[i]);
                const uint32_t t = truth[i] & 0xFFFFu;
                const bool judged = hif::io::isScored(t), moving = hif::io::isMovingClass(t);
                const V::Outcome outcome = !judged  ? (removed ? V::kRemovedUnlabelled : V::kKept)
                                           : moving ? (removed ? V::kRemoved : V::kMissedMoving)
                                                    : (removed ? V::kWronglyRemoved : V::kKept);
                if (view) view->add(w.x[i], w.y[i], static_cast<float>(w.z[i]), outcome);
                if (outcome_cloud && std::isfinite(w.x[i]) && std::isfinite(w.y[i]) &&
                    std::isfinite(w.z[i]))
                    outcome_cloud->add(w.x[i], w.y[i], w.z[i], V::kRgb[outcome][0],
                                       V::kRgb[outcome][1], V::kRgb[outcome][2]);
            }
        }
        total += s;
        auto js = toJson(s.total);
        js["scan"] = stem;
        scans.push_back(js);
        if (o.per_scan) printRow(log, stem.c_str(), s.total);
    }
    if (scored == 0)
        throw std::runtime_error("none of the " + std::to_string(names.size()) +
                                 " predictions in '" + pred_dir + "' has a label file in '" +
                                 label_dir + "'");
    // Ground truth that no prediction scores: a scan the method left out is not a scan it got
    // right.
    std::size_t without_prediction = 0;
    std::string first_missing;
    for (const auto& e : fs::directory_iterator(label_dir))
        if (e.path().extension() == ".label" &&
            !fs::exists(fs::path(pred_dir) / e.path().filename()))
        {
            ++without_prediction;
            const std::string n = e.path().filename().string();
            if (first_missing.empty() || n < first_missing) first_missing = n;
        }
    if (without_truth > 0)
        say(log, "[hif-eval] %zu of %zu predictions have no label file in '%s': not scored\n",
            without_truth, names.size(), label_dir.c_str());
    if (without_prediction > 0)
        say(log,
            "[hif-eval] %zu label files in '%s' have no prediction in '%s' (the first: "
            "%s): those scans are not scored\n",
            without_prediction, label_dir.c_str(), pred_dir.c_str(), first_missing.c_str());
    if (other.points > 0)
        say(log,
            "[hif-eval] warning: %zu predicted points in %zu files are neither 9 (static) "
            "nor 251-259 (moving), e.g. %s: they are scored as static\n",
            other.points, other.files, other.example.c_str());

    nlohmann::ordered_json classes, bands;
    say(log, "%-22s %9s %9s %7s\n", "moving class", "dynamic", "removed", "DA");
    for (const auto& [cls, s] : total.by_moving_class)
    {
        const std::string n = hif::io::className(cls);
        say(log, "%-22s %9zu %9zu %7.2f\n", n.c_str(), s.dynamic_total, s.dynamic_removed, s.da());
        classes[n] = {{"DA", s.da()},
                      {"dynamic_total", s.dynamic_total},
                      {"dynamic_removed", s.dynamic_removed}};
    }
    // Each moving object (--objects), by class, then instance id.
    nlohmann::ordered_json object_rows = nlohmann::ordered_json::array();
    if (o.objects)
    {
        say(log, "%-22s %9s %9s %9s %7s %9s\n", "moving object", "scans", "dynamic", "removed",
            "DA", "range (m)");
        std::vector<std::pair<uint32_t, const Object*>> sorted;
        for (const auto& [label, ob] : objects) sorted.emplace_back(label, &ob);
        std::sort(sorted.begin(), sorted.end(),
                  [](const auto& a, const auto& b)
                  {
                      return std::pair(a.first & 0xffffu, a.first >> 16) <
                             std::pair(b.first & 0xffffu, b.first >> 16);
                  });
        for (const auto& [label, ob] : sorted)
        {
            const std::string cls = hif::io::className(label & 0xffffu);
            const std::string name = cls + " " + std::to_string(label >> 16);
            const double da =
                100.0 * static_cast<double>(ob->removed) / static_cast<double>(ob->points);
            const double mean_range = ob->range_sum / static_cast<double>(ob->ranged);
            say(log, "%-22s %9zu %9zu %9zu %7.2f %s\n", name.c_str(), ob->scans, ob->points,
                ob->removed, da, orDash(ob->ranged > 0, mean_range, 9, 1).c_str());
            nlohmann::ordered_json row = {{"class", cls},
                                          {"instance", label >> 16},
                                          {"scans", ob->scans},
                                          {"dynamic_total", ob->points},
                                          {"dynamic_removed", ob->removed},
                                          {"DA", da}};
            row["mean_range"] =
                ob->ranged > 0 ? nlohmann::ordered_json(mean_range) : nlohmann::ordered_json();
            object_rows.push_back(row);
        }
    }
    // What of each static class was kept (the static map's roads, walls, vegetation, poles).
    nlohmann::ordered_json static_classes = nlohmann::ordered_json::object();
    say(log, "%-22s %9s %9s %7s\n", "static class", "static", "kept", "SA");
    for (const auto& [cls, s] : total.by_static_class)
    {
        const std::string n = hif::io::className(cls);
        say(log, "%-22s %9zu %9zu %7.2f\n", n.c_str(), s.static_total, s.static_kept, s.sa());
        static_classes[n] = {
            {"SA", s.sa()}, {"static_total", s.static_total}, {"static_kept", s.static_kept}};
    }
    if (total.has_ranges)
    {
        // DA per moving class too (the class's name without "moving-"), as held-out
        // benchmarks score sparse and far movers apart.
        say(log, "%-14s %9s %9s %7s %7s", "range (m)", "static", "dynamic", "SA", "DA");
        for (const auto& [cls, class_bands] : total.by_moving_class_range)
        {
            std::string n = hif::io::className(cls);
            if (n.rfind("moving-", 0) == 0) n = n.substr(7);
            say(log, " %9s", n.substr(0, 9).c_str());
        }
        say(log, "\n");
        // A score where the band has points to score (the JSON keeps the convention of
        // Scores: 100).
        const auto pct = [](std::size_t count, double v, int width)
        { return orDash(count > 0, v, width, 2); };
        for (std::size_t b = 0; b < total.by_range.size(); ++b)
        {
            const hif::io::Scores& s = total.by_range[b];
            const std::string n = hif::io::rangeBandName(b);
            say(log, "%-14s %9zu %9zu %s %s", n.c_str(), s.static_total, s.dynamic_total,
                pct(s.static_total, s.sa(), 7).c_str(), pct(s.dynamic_total, s.da(), 7).c_str());
            auto jb = toJson(s);
            jb["band"] = n;
            nlohmann::ordered_json per_class = nlohmann::ordered_json::object();
            for (const auto& [cls, class_bands] : total.by_moving_class_range)
            {
                const hif::io::Scores& c = class_bands[b];
                say(log, " %s", pct(c.dynamic_total, c.da(), 9).c_str());
                if (c.dynamic_total > 0)
                    per_class[hif::io::className(cls)] = {{"DA", c.da()},
                                                          {"dynamic_total", c.dynamic_total},
                                                          {"dynamic_removed", c.dynamic_removed}};
            }
            say(log, "\n");
            jb["per_moving_class"] = per_class;
            bands.push_back(jb);
        }
        if (ego_radius > 0.0)
            say(log,
                "[hif-eval] counting unlabelled points within %.1f m as dynamic (the "
                "DynamicMap benchmark): SA %.2f  DA %.2f  AA %.2f\n",
                ego_radius, with_ego.sa(), with_ego.da(), with_ego.aa());
    }
    printRow(log, "TOTAL", total.total);
    say(log, "[hif-eval] %zu scans: SA %.2f  DA %.2f  AA %.2f  HA %.2f\n", scored, total.total.sa(),
        total.total.da(), total.total.aa(), total.total.ha());

    if (outcome_cloud)
    {
        outcome_cloud->close();
        ply_file->commit();
        say(log, "[hif-eval] wrote %s (%zu points%s)\n", o.classes_ply->c_str(),
            outcome_cloud->count(),
            outcome_cloud->doubleCoordinates() ? ", float64 coordinates" : "");
    }
    if (view)
    {
        char title[160];
        std::snprintf(title, sizeof title, "hif-eval: %zu scans, SA %.2f  DA %.2f  AA %.2f", scored,
                      total.total.sa(), total.total.da(), total.total.aa());
        if (view->empty())
            throw std::runtime_error("--png '" + *o.png + "': the scans have no point to draw");
        const auto pic = view->write(png_file->path(), title, true);
        png_file->commit();
        say(log, "[hif-eval] wrote %s (%d x %d)\n", o.png->c_str(), pic.width, pic.height);
        if (pic.points_outside > 0)
            say(log,
                "[hif-eval] %s shows the main area: %zu of %zu points lie apart from it "
                "(more than 100 m of empty ground away) and are not drawn\n",
                o.png->c_str(), pic.points_outside, pic.points);
    }
    if (json_file)
    {
        nlohmann::ordered_json j;
        j["labels"] = label_dir;
        j["predictions"] = pred_dir;
        j["scans_scored"] = scored;
        j["predictions_without_labels"] = without_truth;
        j["labels_without_predictions"] = without_prediction;
        j["predicted_points_neither_static_nor_moving"] = other.points;
        j["total"] = toJson(total.total);
        j["per_moving_class"] = classes.is_null() ? nlohmann::ordered_json::object() : classes;
        j["per_static_class"] = static_classes;
        if (o.objects) j["per_object"] = object_rows;
        if (total.has_ranges)
        {
            j["per_range"] = bands;
            if (ego_radius > 0.0)
            {
                j["with_ego_points"] = toJson(with_ego);
                j["ego_radius"] = ego_radius;
            }
        }
        j["per_scan"] = scans;
        {
            std::ofstream f(json_file->path());
            f << std::setw(2) << j << "\n";
            f.close();
            if (!f)
                throw std::runtime_error("--json '" + *o.json +
                                         "' could not be written (disk full?)");
        }
        json_file->commit();
    }
    return {scored, total.total};
}

}  // namespace hif::jobs
