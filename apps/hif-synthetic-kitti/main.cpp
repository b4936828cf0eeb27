// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   hif-synthetic-kitti/main.cpp
 * @brief  Writes a synthetic LiDAR sequence in the SemanticKITTI layout, with exact labels: a
 *         street with sloping ground, buildings, trees and parked cars, cars and people that
 *         move, seen by a 64-beam scanner model (ray casting, so occlusion is real).
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

#include "hif/apps/Cli.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/Labels.h"

namespace fs = std::filesystem;

namespace
{
// SemanticKITTI classes used by the scene.
constexpr uint32_t kRoad = 40, kBuilding = 50, kVegetation = 70, kTrunk = 71, kCar = 10;
constexpr uint32_t kMovingCar = 252, kMovingPerson = 254;

constexpr double kSensorHeight = 1.73;  // metres above the ground, as on the KITTI car
constexpr double kSlope = 0.02;         // the street climbs 2 cm per metre along x
constexpr double kEgoSpeed = 8.0;       // m/s
constexpr double kScanPeriod = 0.1;     // s (10 Hz)

double groundZ(double x) { return -kSensorHeight + kSlope * x; }

struct Box
{
    Eigen::Vector3d lo, hi;
    uint32_t label;
};
struct Cylinder  // vertical
{
    double cx, cy, r, z0, z1;
    uint32_t label;
};
struct Sphere
{
    Eigen::Vector3d c;
    double r;
    uint32_t label;
};

/** Something that moves along x or y at a constant speed, as a box of fixed size. */
struct Mover
{
    Eigen::Vector3d start;  // centre of the bottom face at t = 0
    Eigen::Vector3d velocity;
    Eigen::Vector3d size;
    uint32_t label;
    uint32_t instance;
    Box at(double t) const
    {
        const Eigen::Vector3d c = start + velocity * t;
        const Eigen::Vector3d half(size.x() / 2, size.y() / 2, 0);
        const double gz = groundZ(c.x());
        return {
            Eigen::Vector3d(c.x() - half.x(), c.y() - half.y(), gz + 0.15 * (label == kMovingCar)),
            Eigen::Vector3d(c.x() + half.x(), c.y() + half.y(), gz + size.z()), label};
    }
};

struct Hit
{
    double t = std::numeric_limits<double>::infinity();
    uint32_t label = 0;
};

void hitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& b, uint32_t label,
            Hit& h)
{
    double t0 = 0, t1 = h.t;
    for (int k = 0; k < 3; ++k)
    {
        const double inv = 1.0 / d[k];
        double a = (b.lo[k] - o[k]) * inv, c = (b.hi[k] - o[k]) * inv;
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a);
        t1 = std::min(t1, c);
        if (t0 > t1) return;
    }
    if (t0 > 1e-6 && t0 < h.t) h = {t0, label};
}

void hitCylinder(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Cylinder& c, Hit& h)
{
    const double ox = o.x() - c.cx, oy = o.y() - c.cy;
    const double a = d.x() * d.x() + d.y() * d.y();
    const double b = 2 * (ox * d.x() + oy * d.y());
    const double cc = ox * ox + oy * oy - c.r * c.r;
    const double disc = b * b - 4 * a * cc;
    if (a < 1e-12 || disc < 0) return;
    const double t = (-b - std::sqrt(disc)) / (2 * a);
    const double z = o.z() + t * d.z();
    if (t > 1e-6 && t < h.t && z >= c.z0 && z <= c.z1) h = {t, c.label};
}

void hitSphere(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Sphere& s, Hit& h)
{
    const Eigen::Vector3d oc = o - s.c;
    const double b = oc.dot(d);
    const double disc = b * b - (oc.squaredNorm() - s.r * s.r);
    if (disc < 0) return;
    const double t = -b - std::sqrt(disc);
    if (t > 1e-6 && t < h.t) h = {t, s.label};
}

struct Scene
{
    std::vector<Box> boxes;  // static
    std::vector<Cylinder> cylinders;
    std::vector<Sphere> spheres;
    std::vector<Mover> movers;

    explicit Scene(std::mt19937& rng, double length)
    {
        std::uniform_real_distribution<double> u(0, 1);
        // Buildings on both sides, with gaps between them.
        for (int side : {-1, 1})
            for (double x = -30; x < length + 30;)
            {
                const double w = 10 + 15 * u(rng), h = 6 + 10 * u(rng), y0 = 13 + 3 * u(rng);
                const double y_near = side * y0, y_far = side * (y0 + 10);
                boxes.push_back({Eigen::Vector3d(x, std::min(y_near, y_far), groundZ(x) - 1),
                                 Eigen::Vector3d(x + w, std::max(y_near, y_far), groundZ(x) + h),
                                 kBuilding});
                x += w + 3 + 6 * u(rng);
            }
        // Trees along both sidewalks: trunk and canopy.
        for (int side : {-1, 1})
            for (double x = -20 + 6 * u(rng); x < length + 20; x += 10 + 6 * u(rng))
            {
                const double y = side * (9.5 + u(rng)), gz = groundZ(x);
                cylinders.push_back({x, y, 0.2, gz - 0.5, gz + 3.0, kTrunk});
                spheres.push_back(
                    {Eigen::Vector3d(x, y, gz + 4.0), 1.5 + 0.5 * u(rng), kVegetation});
            }
        // Parked cars along both kerbs.
        for (int side : {-1, 1})
            for (double x = -10 + 8 * u(rng); x < length + 10; x += 9 + 12 * u(rng))
            {
                const double y = side * 6.0, gz = groundZ(x);
                boxes.push_back({Eigen::Vector3d(x - 2.1, y - 0.9, gz + 0.15),
                                 Eigen::Vector3d(x + 2.1, y + 0.9, gz + 1.5), kCar});
            }
        // Moving cars: two overtake us in our direction, two come the other way; people walk
        // along the sidewalks and one crosses the street.
        uint32_t id = 1;
        const Eigen::Vector3d car(4.4, 1.9, 1.5), person(0.6, 0.6, 1.75);
        movers.push_back({{-15, -2.0, 0}, {13, 0, 0}, car, kMovingCar, id++});
        movers.push_back({{10, -2.0, 0}, {11, 0, 0}, car, kMovingCar, id++});
        movers.push_back({{length + 10, 2.0, 0}, {-10, 0, 0}, car, kMovingCar, id++});
        movers.push_back({{length + 40, 2.2, 0}, {-12, 0, 0}, car, kMovingCar, id++});
        movers.push_back({{12, -7.5, 0}, {1.4, 0, 0}, person, kMovingPerson, id++});
        movers.push_back({{35, 7.5, 0}, {-1.3, 0, 0}, person, kMovingPerson, id++});
        movers.push_back({{28, -4.0, 0}, {0, 1.2, 0}, person, kMovingPerson, id++});
    }

    /** First hit of the ray from o along unit d (within max_range), at time t. */
    Hit cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_now, double max_range,
             uint32_t& instance) const
    {
        Hit h;
        h.t = max_range;
        const double denom = d.z() - kSlope * d.x();
        if (std::abs(denom) > 1e-9)
        {
            const double t = (groundZ(o.x()) - o.z()) / denom;
            if (t > 0 && t < h.t) h = {t, kRoad};
        }
        for (const Box& b : boxes) hitBox(o, d, b, b.label, h);
        for (const Cylinder& c : cylinders) hitCylinder(o, d, c, h);
        for (const Sphere& s : spheres) hitSphere(o, d, s, h);
        instance = 0;
        for (const Mover& m : movers)
        {
            const uint32_t before = h.label;
            const double t_before = h.t;
            hitBox(o, d, m.at(t_now), m.label, h);
            if (h.t != t_before || h.label != before) instance = m.instance;
        }
        if (h.t >= max_range)
            h.label = 0;
        else if (instance != 0 && !(h.label == kMovingCar || h.label == kMovingPerson))
            instance = 0;
        return h;
    }
};

struct Cli
{
    TCLAP::CmdLine cmd{
        "hif-synthetic-kitti: writes a synthetic LiDAR sequence in the SemanticKITTI layout "
        "(velodyne/NNNNNN.bin, labels/NNNNNN.label, poses.txt, calib.txt, times.txt) with exact "
        "labels: a 64-beam scanner (+2 to -24.8 degrees, 1024 columns, 80 m) driving at 8 m/s "
        "down a sloping street with buildings, trees and parked cars, while cars (class 252) "
        "and people (254) move.",
        ' ', "0.1"};
    TCLAP::ValueArg<std::string> output{"o",      "output", "Output sequence folder", true, "",
                                        "folder", cmd};
    TCLAP::ValueArg<std::size_t> scans{"n", "scans", "Number of scans (default: 30)", false, 30,
                                       "N", cmd};
    TCLAP::ValueArg<unsigned> seed{"",  "seed", "Random seed of the scene (default: 1)", false, 1,
                                   "S", cmd};
    TCLAP::SwitchArg overwrite{"", "overwrite", "Replace an existing sequence folder", cmd};
};

int run(Cli& cli)
{
    const std::string tag = "[hif-synthetic-kitti]";
    const std::string dir = cli.output.getValue();
    const std::size_t n = cli.scans.getValue();
    if (n == 0) throw std::runtime_error("--scans must be at least 1");
    hif::apps::refuseToOverwrite(dir + "/velodyne", cli.overwrite.getValue(), "--overwrite");
    if (cli.overwrite.getValue())
    {
        fs::remove_all(dir + "/velodyne");
        fs::remove_all(dir + "/labels");
    }
    hif::apps::makeDirs(dir + "/velodyne");
    hif::apps::makeDirs(dir + "/labels");

    std::mt19937 rng(cli.seed.getValue());
    const double length = kEgoSpeed * kScanPeriod * double(n);
    const Scene scene(rng, length);
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
    std::ofstream calib(dir + "/calib.txt"), poses(dir + "/poses.txt"), times(dir + "/times.txt");
    calib << "Tr: " << row34(Tr) << "\n";

    constexpr int kBeams = 64, kColumns = 1024;
    constexpr double kMaxRange = 80.0;
    hif::apps::Progress progress(tag, "rendering", n);
    std::size_t total_points = 0, moving_points = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const double t = double(i) * kScanPeriod;
        const double ex = kEgoSpeed * t;
        Eigen::Isometry3d T_world_velo = Eigen::Isometry3d::Identity();
        T_world_velo.translation() = Eigen::Vector3d(ex, 0, kSlope * ex);
        // poses.txt holds camera-0 poses: P = Tr * T_world_velo * inv(Tr).
        poses << row34(Tr * T_world_velo * Tr.inverse()) << "\n";
        times << t << "\n";

        std::vector<float> pts;
        std::vector<uint32_t> labels;
        const Eigen::Vector3d o = T_world_velo.translation();
        for (int b = 0; b < kBeams; ++b)
        {
            const double el = (2.0 - 26.8 * b / (kBeams - 1)) * M_PI / 180.0;
            for (int c = 0; c < kColumns; ++c)
            {
                const double az = 2.0 * M_PI * c / kColumns;
                const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                                        std::sin(el));
                uint32_t instance = 0;
                const Hit h = scene.cast(o, d, t, kMaxRange, instance);
                if (h.label == 0) continue;  // no return
                const double r = h.t + noise(rng);
                const Eigen::Vector3d p = d * r;  // LiDAR frame (no rotation in this scene)
                pts.insert(pts.end(), {float(p.x()), float(p.y()), float(p.z()),
                                       float(0.1 + 0.01 * (h.label % 50))});
                labels.push_back(h.label | (instance << 16));
                moving_points += hif::io::isMovingClass(h.label) ? 1 : 0;
            }
        }
        total_points += labels.size();
        const std::string name = hif::io::frameName(i);
        std::ofstream bin(dir + "/velodyne/" + name + ".bin", std::ios::binary);
        bin.write(reinterpret_cast<const char*>(pts.data()),
                  static_cast<std::streamsize>(pts.size() * sizeof(float)));
        if (!bin)
            throw std::runtime_error("Error writing to target file '" + dir + "/velodyne/" + name +
                                     ".bin'");
        hif::io::writeLabels(dir + "/labels/" + name + ".label", labels);
        progress.update(i + 1);
    }
    progress.finish();
    if (!calib || !poses || !times)
        throw std::runtime_error("Error writing calib.txt, poses.txt or times.txt in '" + dir +
                                 "'");
    std::cout << tag << " wrote " << n << " scans, " << total_points << " points (" << moving_points
              << " on moving objects) to '" << dir << "'\n";
    return 0;
}
}  // namespace

int main(int argc, char** argv)
{
    return hif::apps::cliMain<Cli>("[hif-synthetic-kitti]", argc, argv, run);
}
