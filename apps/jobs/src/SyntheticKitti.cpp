// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SyntheticKitti.cpp
 * @brief  A synthetic sequence rendered scan by scan: the scene, the sensor's beams cast into
 *         it, the points and their labels written in the SemanticKITTI layout.
 */
#include "hif/jobs/SyntheticKitti.h"

#include <Eigen/Geometry>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <stdexcept>
#include <vector>

#include "hif/apps/Cli.h"
#include "hif/apps/Staged.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"
#include "synthetic/Scene.h"
#include "synthetic/Sensor.h"

namespace hif::jobs
{
using namespace synth;

namespace
{
constexpr double kScanPeriod = 0.1;  // s (10 Hz)

/** A scene of --scene: its name, the sensor's speed when --ego-speed is not given (m/s), and
 *  how it is made (a street `length` m long, a clip `duration` s long). */
struct SceneKind
{
    const char* name;
    double default_speed;
    Scene (*make)(std::mt19937& rng, double length, double duration, double ego_speed, int groups);
};

constexpr SceneKind kScenes[] = {
    {"street", 8.0,
     [](std::mt19937& rng, double length, double, double, int)
     { return streetScene(rng, length); }},
    {"walkers", 3.0,
     [](std::mt19937& rng, double length, double duration, double, int groups)
     { return walkersScene(rng, length, duration, groups); }},
    {"radial", 3.0,
     [](std::mt19937& rng, double length, double duration, double, int groups)
     { return radialWalkersScene(rng, length, duration, groups); }},
    {"cyclists", 3.0,
     [](std::mt19937& rng, double length, double duration, double, int groups)
     { return cyclistsScene(rng, length, duration, groups); }},
    {"traffic", 12.0,
     [](std::mt19937& rng, double length, double duration, double ego_speed, int groups)
     { return trafficScene(rng, length, duration, ego_speed, groups); }},
};

/** The scene called `name`; an error naming every scene if there is none. */
const SceneKind& sceneNamed(const std::string& name)
{
    std::string names;
    const std::size_t n = std::size(kScenes);
    for (std::size_t k = 0; k < n; ++k)
    {
        if (name == kScenes[k].name) return kScenes[k];
        names += (k == 0 ? "" : k + 1 == n ? " or " : ", ") + std::string(kScenes[k].name);
    }
    throw std::runtime_error("--scene '" + name + "' is not " + names);
}
}  // namespace

SyntheticKittiResult SyntheticKitti::run(std::ostream& log) const
{
    const SyntheticKittiOptions& o = options_;
    const std::string dir = hif::apps::cleanDir(o.output);
    const auto n = static_cast<std::size_t>(hif::apps::flagInRange(o.scans, "--scans", 1, 999999));
    const auto seed = static_cast<std::mt19937::result_type>(
        hif::apps::flagInRange(o.seed, "--seed", 0, 4294967295LL));
    const SceneKind& kind = sceneNamed(o.scene);
    const double ego_speed = o.ego_speed.value_or(kind.default_speed);
    if (!(ego_speed >= 0.0 && ego_speed <= 60.0))
        throw std::runtime_error("--ego-speed " + std::to_string(ego_speed) +
                                 " is not in [0, 60] m/s");
    const Sensor& sensor = sensorNamed(o.sensor);
    if (o.groups < 0 || o.groups > 100)
        throw std::runtime_error("--groups " + std::to_string(o.groups) + " is not in [0, 100]");
    // Written aside and put in place when complete: a stopped run leaves no half sequence.
    hif::apps::StagedFolder staged(dir,
                                   {"velodyne", "labels", "poses.txt", "calib.txt", "times.txt"},
                                   o.overwrite, "--overwrite");
    const std::string out = staged.path();
    hif::apps::makeDirs(out + "/velodyne");
    hif::apps::makeDirs(out + "/labels");

    std::mt19937 rng(seed);
    const double length = ego_speed * kScanPeriod * double(n);
    const double duration = kScanPeriod * double(n);
    const int groups = static_cast<int>(o.groups);
    Scene scene = kind.make(rng, length, duration, ego_speed, groups);
    if (o.foliage)
    {
        // A generator of its own: the scene and its movers are those of the clip without.
        std::mt19937 leaves(seed ^ 0x1eafU);
        addFoliage(scene, leaves, length);
    }
    if (o.roadside)
    {
        // A generator of its own too: the scene and its movers are those of the clip without.
        std::mt19937 furniture(seed ^ 0x5194U);
        addRoadside(scene, furniture, length);
    }
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

    hif::apps::Progress progress(kTag, "rendering", n, o.show_progress);
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
        const Eigen::Vector3d origin = T_world_velo.translation();
        sensor.directions(t, kScanPeriod, beams);
        for (const Eigen::Vector3d& d : beams)
        {
            uint32_t instance = 0;
            const Hit h = scene.cast(origin, d, t, sensor.max_range, instance);
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
    log << kTag << " sensor " << sensor.name << ": " << sensor.description << "\n";
    log << kTag << " wrote " << n << " scans, " << total_points << " points (" << moving_points
        << " on moving objects) to '" << dir << "'\n";
    return {n, total_points, moving_points};
}

}  // namespace hif::jobs
