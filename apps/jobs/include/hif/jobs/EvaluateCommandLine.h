// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   EvaluateCommandLine.h
 * @brief  hif-eval's command line: its flags (TCLAP), read into hif::jobs::Evaluate's options. The
 *         app runs it (hif::apps::cliMain()), the tests run it in process
 *         (hif::apps::runCommandLine()).
 */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

#include "hif/jobs/Evaluate.h"

namespace hif::jobs
{
/** hif-eval's flags, parsed by `cmd`. */
struct EvaluateCommandLine
{
    using Job = Evaluate;

    TCLAP::CmdLine cmd{
        "hif-eval: scores predictions (SemanticKITTI .label files, 251 or 252-259 = moving, "
        "anything else = static) against ground-truth labels, point by point: labels 0 and 1 "
        "are not scored, classes 252-259 are dynamic. SA = static kept / static, DA = dynamic "
        "removed / dynamic, AA = sqrt(SA DA), HA = their harmonic mean, in percent; also DA "
        "per moving class and, with --scans, SA and DA per range band. Every prediction file "
        "that has a label file of the same name is scored (the sizes must match); predictions "
        "without ground truth (e.g. scans past the labelled part of a sequence), label files "
        "without a prediction, and prediction values that are neither 9 (static) nor 251-259 "
        "(moving) are counted and reported.",
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
    TCLAP::ValueArg<std::string> scans{
        "",
        "scans",
        "The scans, for ranges: a KITTI velodyne folder (NNNNNN.bin, sensor frame) or a "
        "DynamicMap pcd folder (NNNNNN.pcd, world frame, sensor pose in VIEWPOINT)",
        false,
        "",
        "folder",
        cmd};
    TCLAP::ValueArg<double> ego_radius{
        "",
        "ego-radius",
        "With --scans: also score as the DynamicMap benchmark does, where every point within "
        "this many metres of the sensor (the car's own returns, mostly unlabelled) is dynamic "
        "(default: 3; 0 = no such line)",
        false,
        3.0,
        "metres",
        cmd};
    TCLAP::ValueArg<std::string> png{
        "",
        "png",
        "With --scans: also draw the scored scans from above into this PNG, in the world frame "
        "(a KITTI folder's poses.txt, or the DynamicMap clouds as they are): kept static points "
        "grey by height, removed moving ones red, missed moving ones yellow, wrongly removed "
        "static ones blue",
        false,
        "",
        "map.png",
        cmd};
    TCLAP::ValueArg<std::string> classes_ply{
        "",
        "classes-ply",
        "With --scans: also write every scored scan's points (world frame, as for --png) to "
        "this PLY, coloured by outcome as in the picture (kept light grey, removed moving red, "
        "missed moving yellow, wrongly removed static blue)",
        false,
        "",
        "classes.ply",
        cmd};
    TCLAP::ValueArg<std::string> json{
        "", "json", "Also write the scores to this JSON file", false, "", "file.json", cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite",
                               "Replace the files of --json, --png and --classes-ply if they exist "
                               "(never an input of the run)",
                               cmd};
    TCLAP::SwitchArg objects{
        "", "objects",
        "Also score each moving object apart (a SemanticKITTI instance: its moving class and "
        "instance id): the scans it is in, its points, how many were removed and, with --scans, "
        "its mean range",
        cmd};
    TCLAP::SwitchArg quiet{"q", "quiet", "Print the totals only, not every scan", cmd};

    /** The job's options, from the flags `cmd` parsed. */
    [[nodiscard]] EvaluateOptions options()
    {
        EvaluateOptions o;
        o.labels = labels.getValue();
        o.predictions = predictions.getValue();
        o.scans = scans.getValue();
        o.ego_radius = ego_radius.getValue();
        if (png.isSet()) o.png = png.getValue();
        if (classes_ply.isSet()) o.classes_ply = classes_ply.getValue();
        if (json.isSet()) o.json = json.getValue();
        o.overwrite = overwrite.getValue();
        o.per_scan = !quiet.getValue();
        o.objects = objects.getValue();
        return o;
    }
};

}  // namespace hif::jobs
