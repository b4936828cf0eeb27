// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-eval/main.cpp
 * @brief  Point-level scores of moving-object predictions against SemanticKITTI labels, with
 *         the protocol of the dynamic-points-removal benchmark: labels 0 and 1 excluded, classes
 *         252-259 dynamic; SA, DA, AA, HA per scan and in total.
 */
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "hif/apps/Cli.h"
#include "hif/io/Labels.h"

namespace fs = std::filesystem;

namespace
{
struct Cli
{
    TCLAP::CmdLine cmd{
        "hif-eval: scores predictions (SemanticKITTI .label files, 251 or 252-259 = moving, "
        "anything else = static) against ground-truth labels, point by point: labels 0 and 1 "
        "are not scored, classes 252-259 are dynamic. SA = static kept / static, DA = dynamic "
        "removed / dynamic, AA = sqrt(SA DA), HA = their harmonic mean, in percent. Every "
        "prediction file that has a label file of the same name is scored (the sizes must "
        "match); predictions without ground truth (e.g. scans past the labelled part of a "
        "sequence) are counted and reported.",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> labels{
        "", "labels", "Ground-truth folder (NNNNNN.label)", true, "", "folder", cmd};
    TCLAP::ValueArg<std::string> predictions{
        "",
        "predictions",
        "Predictions folder (NNNNNN.label, as hif-clean writes)",
        true,
        "",
        "folder",
        cmd};
    TCLAP::ValueArg<std::string> json{
        "", "json", "Also write the scores to this JSON file", false, "", "file.json", cmd};
    TCLAP::SwitchArg quiet{"q", "quiet", "Print the total only, not every scan", cmd};
};

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

int run(Cli& cli)
{
    const std::string pred_dir = cli.predictions.getValue();
    const std::string label_dir = cli.labels.getValue();
    if (!fs::is_directory(pred_dir))
        throw std::runtime_error("predictions folder '" + pred_dir + "' does not exist");
    if (!fs::is_directory(label_dir))
        throw std::runtime_error("labels folder '" + label_dir + "' does not exist");
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(pred_dir))
        if (e.path().extension() == ".label") names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    if (names.empty()) throw std::runtime_error("no .label files in '" + pred_dir + "'");

    hif::io::Scores total;
    std::size_t without_truth = 0, scored = 0;
    nlohmann::ordered_json scans = nlohmann::ordered_json::array();
    if (!cli.quiet.getValue())
        std::printf("%-14s %9s %9s %7s %7s %7s %7s\n", "scan", "static", "dynamic", "SA", "DA",
                    "AA", "HA");
    for (const std::string& name : names)
    {
        const std::string truth_file = (fs::path(label_dir) / name).string();
        if (!fs::exists(truth_file))
        {
            ++without_truth;
            continue;
        }
        ++scored;
        const auto truth = hif::io::readLabels(truth_file);
        const auto pred = hif::io::readLabels((fs::path(pred_dir) / name).string());
        if (truth.size() != pred.size())
            throw std::runtime_error("'" + (fs::path(pred_dir) / name).string() + "' has " +
                                     std::to_string(pred.size()) + " points, '" + truth_file +
                                     "' has " + std::to_string(truth.size()));
        hif::io::Scores s;
        for (std::size_t i = 0; i < truth.size(); ++i)
            s.add(truth[i], hif::io::isPredictedMoving(pred[i]));
        total += s;
        auto js = toJson(s);
        js["scan"] = fs::path(name).stem().string();
        scans.push_back(js);
        if (!cli.quiet.getValue())
            std::printf("%-14s %9zu %9zu %7.2f %7.2f %7.2f %7.2f\n",
                        fs::path(name).stem().string().c_str(), s.static_total, s.dynamic_total,
                        s.sa(), s.da(), s.aa(), s.ha());
    }
    if (scored == 0)
        throw std::runtime_error("none of the " + std::to_string(names.size()) +
                                 " predictions in '" + pred_dir + "' has a label file in '" +
                                 label_dir + "'");
    if (without_truth > 0)
        std::printf("[hif-eval] %zu of %zu predictions have no label file in '%s': not scored\n",
                    without_truth, names.size(), label_dir.c_str());
    std::printf("%-14s %9zu %9zu %7.2f %7.2f %7.2f %7.2f\n", "TOTAL", total.static_total,
                total.dynamic_total, total.sa(), total.da(), total.aa(), total.ha());
    std::printf("[hif-eval] %zu scans: SA %.2f  DA %.2f  AA %.2f  HA %.2f\n", scored, total.sa(),
                total.da(), total.aa(), total.ha());

    if (cli.json.isSet())
    {
        nlohmann::ordered_json j;
        j["labels"] = label_dir;
        j["predictions"] = pred_dir;
        j["scans_scored"] = scored;
        j["predictions_without_labels"] = without_truth;
        j["total"] = toJson(total);
        j["per_scan"] = scans;
        std::ofstream f(cli.json.getValue());
        f << std::setw(2) << j << "\n";
        if (!f)
            throw std::runtime_error("Error writing to target file '" + cli.json.getValue() + "'");
    }
    return 0;
}
}  // namespace

int main(int argc, char** argv) { return hif::apps::cliMain<Cli>("[hif-eval]", argc, argv, run); }
