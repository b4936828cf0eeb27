// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SyntheticKittiCommandLine.h
 * @brief  hif-synthetic-kitti's command line: its flags (TCLAP), read into
 * hif::jobs::SyntheticKitti's options. The app runs it (hif::apps::cliMain()), the tests run it in
 * process (hif::apps::runCommandLine()).
 */
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <string>
#include <vector>

#include "hif/jobs/SyntheticKitti.h"

namespace hif::jobs
{
/** hif-synthetic-kitti's flags, parsed by `cmd`. */
struct SyntheticKittiCommandLine
{
    using Job = SyntheticKitti;

    TCLAP::CmdLine cmd{
        "hif-synthetic-kitti: writes a synthetic LiDAR sequence in the SemanticKITTI layout "
        "(velodyne/NNNNNN.bin, labels/NNNNNN.label, poses.txt, calib.txt, times.txt) with exact "
        "labels: a LiDAR (--sensor; by default a 64-beam scanner, +2 to -24.8 degrees, 1024 "
        "columns, 80 m) moving down a sloping street with buildings, trees and parked cars. Scene "
        "'street': driving at 8 m/s "
        "while cars (class 252) and people (254) move; scene 'walkers': only people walk, in "
        "groups, along the sidewalks and across the road; scene 'radial': only people walk, "
        "towards the sensor or away from it, within 15 degrees of its line of sight; scene "
        "'cyclists': only cyclists (253) ride, along the road and across it.",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> output{"o",      "output", "Output sequence folder", true, "",
                                        "folder", cmd};
    TCLAP::ValueArg<long long> scans{"n", "scans", "Number of scans (default: 30)", false, 30,
                                     "N", cmd};
    TCLAP::ValueArg<long long> seed{"",  "seed", "Random seed of the scene (default: 1)", false, 1,
                                    "S", cmd};
    TCLAP::ValueArg<std::string> scene{
        "",    "scene",  "street (default), walkers, radial, cyclists or traffic",
        false, "street", "street|walkers|radial|cyclists|traffic",
        cmd};
    TCLAP::ValueArg<double> ego_speed{
        "",
        "ego-speed",
        "Speed of the sensor, m/s, >= 0 (default: 8 for street, 12 for traffic, 3 for the others)",
        false,
        8.0,
        "m/s",
        cmd};
    TCLAP::ValueArg<int> groups{
        "",
        "groups",
        "Walkers, radial, cyclists and traffic scenes: groups of people or cyclists, or vehicles "
        "(default: 6)",
        false,
        6,
        "N",
        cmd};
    TCLAP::ValueArg<std::string> sensor{"",
                                        "sensor",
                                        "The LiDAR: hdl-64e (default, KITTI's), hdl-32e, vlp-16, "
                                        "os1-128, vlp-32c (uneven beams, crowded near the "
                                        "horizon) or mid-70 (a Livox-style rosette, 70 degrees "
                                        "ahead)",
                                        false,
                                        "hdl-64e",
                                        "name",
                                        cmd};
    TCLAP::SwitchArg foliage{
        "", "foliage",
        "Porous vegetation: the trees' canopies, and bushes and hedges along the sidewalks, are "
        "leaves a beam enters, returning from a leaf at a random depth (a mean of 0.3 to 1 m) or "
        "passing through; the same beam a scan later meets another leaf. Without it, vegetation "
        "is solid; the rest of the scene is the same either way",
        cmd};
    TCLAP::SwitchArg roadside{
        "", "roadside",
        "Street furniture thinner than a sparse LiDAR's beam spacing: traffic signs on thin poles "
        "at the sidewalks' edges, street lights, and a railing along a stretch of each sidewalk "
        "(SemanticKITTI's traffic-sign, pole and fence). The rest of the scene is the same either "
        "way",
        cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite", "Replace an existing sequence folder", cmd};

    /** The job's options, from the flags `cmd` parsed. */
    [[nodiscard]] SyntheticKittiOptions options()
    {
        SyntheticKittiOptions o;
        o.output = output.getValue();
        o.scans = scans.getValue();
        o.seed = seed.getValue();
        o.scene = scene.getValue();
        if (ego_speed.isSet()) o.ego_speed = ego_speed.getValue();
        o.groups = groups.getValue();
        o.sensor = sensor.getValue();
        o.foliage = foliage.getValue();
        o.roadside = roadside.getValue();
        o.overwrite = overwrite.getValue();
        return o;
    }
};

}  // namespace hif::jobs
