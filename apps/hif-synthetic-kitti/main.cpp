// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-synthetic-kitti/main.cpp
 * @brief  Writes a synthetic LiDAR sequence in the SemanticKITTI layout, with exact labels: a
 *         street with sloping ground, buildings, trees and parked cars, cars and people that
 *         move, seen by a LiDAR model (a 64-beam scanner by default, or another of Sensor.h;
 *         ray casting, so occlusion is real).
 */
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <vector>

#include "Scene.h"
#include "Sensor.h"
#include "hif/apps/Cli.h"
#include "hif/apps/Staged.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"

namespace fs = std::filesystem;

namespace
{
using namespace synth;

constexpr double kScanPeriod = 0.1;  // s (10 Hz)

struct Cli
{
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
        "",    "scene",  "street (default), walkers, radial or cyclists",
        false, "street", "street|walkers|radial|cyclists",
        cmd};
    TCLAP::ValueArg<double> ego_speed{
        "",
        "ego-speed",
        "Speed of the sensor, m/s, >= 0 (default: 8 for street, 3 for the others)",
        false,
        8.0,
        "m/s",
        cmd};
    TCLAP::ValueArg<int> groups{
        "",
        "groups",
        "Walkers, radial and cyclists scenes: groups of people or cyclists (default: 6)",
        false,
        6,
        "N",
        cmd};
    TCLAP::ValueArg<std::string> sensor{"",
                                        "sensor",
                                        "The LiDAR: hdl-64e (default, KITTI's), hdl-32e, vlp-16, "
                                        "os1-128 or mid-70 (a Livox-style rosette, 70 degrees "
                                        "ahead)",
                                        false,
                                        "hdl-64e",
                                        "name",
                                        cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite", "Replace an existing sequence folder", cmd};
};

int run(Cli& cli)
{
    const std::string tag = "[hif-synthetic-kitti]";
    const std::string dir = hif::apps::cleanDir(cli.output.getValue());
    const auto n = static_cast<std::size_t>(
        hif::apps::flagInRange(cli.scans.getValue(), "--scans", 1, 999999));
    const auto seed = static_cast<std::mt19937::result_type>(
        hif::apps::flagInRange(cli.seed.getValue(), "--seed", 0, 4294967295LL));
    const std::string kind = cli.scene.getValue();
    if (kind != "street" && kind != "walkers" && kind != "radial" && kind != "cyclists")
        throw std::runtime_error("--scene '" + kind +
                                 "' is not street, walkers, radial or cyclists");
    const double ego_speed =
        cli.ego_speed.isSet() ? cli.ego_speed.getValue() : (kind == "street" ? 8.0 : 3.0);
    if (!(ego_speed >= 0.0 && ego_speed <= 60.0))
        throw std::runtime_error("--ego-speed " + std::to_string(ego_speed) +
                                 " is not in [0, 60] m/s");
    const Sensor& sensor = sensorNamed(cli.sensor.getValue());
    if (cli.groups.getValue() < 0 || cli.groups.getValue() > 100)
        throw std::runtime_error("--groups " + std::to_string(cli.groups.getValue()) +
                                 " is not in [0, 100]");
    // Written aside and put in place when complete: a stopped run leaves no half sequence.
    hif::apps::StagedFolder staged(dir,
                                   {"velodyne", "labels", "poses.txt", "calib.txt", "times.txt"},
                                   cli.overwrite.getValue(), "--overwrite");
    const std::string out = staged.path();
    hif::apps::makeDirs(out + "/velodyne");
    hif::apps::makeDirs(out + "/labels");

    std::mt19937 rng(seed);
    const double length = ego_speed * kScanPeriod * double(n);
    const double duration = kScanPeriod * double(n);
    const int groups = cli.groups.getValue();
    const Scene scene = kind == "street"    ? streetScene(rng, length)
                        : kind == "walkers" ? walkersScene(rng, length, duration, groups)
                        : kind == "radial"  ? radialWalkersScene(rng, length, duration, groups)
                                            : cyclistsScene(rng, length, duration, groups);
    std::normal_distribution<double> noise(0.0, 0.01);

    // KITTI's LiDAR-to-camera calibration, rounded: camera x = -y, y = -z, z = x.
    Eigen::Isometry3d Tr = Eigen::Isometry3d::Identity();
    Tr.linear() << 0, -1, 0, 0, 0, -1, 1, 0, 0;
    Tr.translation() = Eigen::Vector3d(-0.004, -0.076, -0.272);
    auto row34 = [](const Eigen::Isometry3d& T)
    {
        std::string s;
        char buf[64];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
            {
                std::snprintf(buf, sizeof(buf), "%s%.9e", (r || c) ? " " : "", T.matrix()(r, c));
                s += buf;
            }
        return s;
    };
    std::ofstream calib(out + "/calib.txt"), poses(out + "/poses.txt"), times(out + "/times.txt");
    calib << "Tr: " << row34(Tr) << "\n";

    hif::apps::Progress progress(tag, "rendering", n);
    std::vector<Eigen::Vector3d> beams;
    std::size_t total_points = 0, moving_points = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double t = double(i) * kScanPeriod;
        const double ex = ego_speed * t;
        Eigen::Isometry3d T_world_velo = Eigen::Isometry3d::Identity();
        T_world_velo.translation() = Eigen::Vector3d(ex, 0, kSlope * ex);
        // poses.txt holds camera-0 poses: P = Tr * T_world_velo * inv(Tr).
        poses << row34(Tr * T_world_velo * Tr.inverse()) << "\n";
        times << t << "\n";

        std::vector<float> pts;
        std::vector<uint32_t> labels;
        const Eigen::Vector3d o = T_world_velo.translation();
        sensor.directions(t, kScanPeriod, beams);
        for (const Eigen::Vector3d& d : beams)
        {
            uint32_t instance = 0;
            const Hit h = scene.cast(o, d, t, sensor.max_range, instance);
            if (h.label == 0) continue;  // no return
            const double r = h.t + noise(rng);
            const Eigen::Vector3d p = d * r;  // LiDAR frame (no rotation in this scene)
            pts.insert(pts.end(), {float(p.x()), float(p.y()), float(p.z()),
                                   float(0.1 + 0.01 * (h.label % 50))});
            labels.push_back(h.label | (instance << 16));
            moving_points += hif::io::isMovingClass(h.label) ? 1 : 0;
        }
        total_points += labels.size();
        const std::string name = hif::io::frameName(i);
        std::ofstream bin(out + "/velodyne/" + name + ".bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(pts.data()),
                  static_cast<std::streamsize>(pts.size() * sizeof(float)));
        bin.close();
        if (!bin)
            throw std::runtime_error("'" + dir + "/velodyne/" + name +
                                     ".bin' could not be written (disk full?)");
        hif::io::writeLabels(out + "/labels/" + name + ".label", labels);
        progress.update(i + 1);
    }
    progress.finish();
    calib.close();
    poses.close();
    times.close();
    if (!calib || !poses || !times)
        throw std::runtime_error("calib.txt, poses.txt or times.txt of '" + dir +
                                 "' could not be written (disk full?)");
    staged.commit();
    std::cout << tag << " sensor " << sensor.name << ": " << sensor.description << "\n";
    std::cout << tag << " wrote " << n << " scans, " << total_points << " points (" << moving_points
              << " on moving objects) to '" << dir << "'\n";
    return 0;
}
}  // namespace

int main(int argc, char** argv)
{
    return hif::apps::cliMain<Cli>("[hif-synthetic-kitti]", argc, argv, run);
}
