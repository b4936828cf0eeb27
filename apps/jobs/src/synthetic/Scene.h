// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Scene.h
 * @brief  The synthetic world of hif-synthetic-kitti: a sloping street with buildings, trees and
 *         parked cars, and things that move through it, ray-cast at any time.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace synth
{
// SemanticKITTI classes used by the scenes.
constexpr uint32_t kRoad = 40, kBuilding = 50, kVegetation = 70, kTrunk = 71, kCar = 10;
constexpr uint32_t kFence = 51, kPole = 80, kTrafficSign = 81;
constexpr uint32_t kMovingCar = 252, kMovingBicyclist = 253, kMovingPerson = 254;

constexpr double kSensorHeight = 1.73;  // metres above the ground, as on the KITTI car
constexpr double kSlope = 0.02;         // the street climbs 2 cm per metre along x

/** Ground height at x: the sensor's ground at x = 0 is z = -kSensorHeight. */
inline double groundZ(double x) { return -kSensorHeight + kSlope * x; }

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

/** Leaves in a box (a hedge) or a sphere (a tree's canopy, a bush): a beam that enters returns
 *  from a leaf at a depth drawn from an exponential distribution whose mean is the volume's
 *  `free_path` (metres: the inverse of the leaves' projected area per cubic metre), or passes
 *  through when that depth lies beyond the volume. */
struct FoliageBox
{
    Box box;
    double free_path;
};
struct FoliageSphere
{
    Sphere sphere;
    double free_path;
};

struct Hit
{
    double t = std::numeric_limits<double>::infinity();
    uint32_t label = 0;
};

/** Something that moves at a constant velocity: a box of `size` (cars; the street scene's
 *  people), a walking person (two legs that swing, a torso and a head), or a cyclist (a
 *  bicycle and its rider). */
struct Mover
{
    enum class Shape : uint8_t
    {
        Box,
        Walker,
        Cyclist
    };
    Eigen::Vector3d start;  ///< centre of the bottom face at t = 0
    Eigen::Vector3d velocity;
    Eigen::Vector3d size;
    uint32_t label;
    uint32_t instance;
    Shape shape = Shape::Box;
    double phase = 0.0;  ///< of the stride or the pedals, radians

    /** Updates `h` if the ray from o along unit d hits the mover at time t before h.t. */
    void cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t, Hit& h) const;
};

struct Scene
{
    std::vector<Box> boxes;  ///< static
    std::vector<Cylinder> cylinders;
    std::vector<Sphere> spheres;
    std::vector<Mover> movers;
    std::vector<FoliageBox> foliage_boxes;  ///< empty unless addFoliage()
    std::vector<FoliageSphere> foliage_spheres;
    uint64_t foliage_seed = 0;  ///< with the ray and the time, draws each beam's depth in leaves

    /** First hit of the ray from o along unit d (within max_range) at time t, with the
     *  instance id of the mover hit (0 for static things). Label 0: no return. */
    Hit cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t, double max_range,
             uint32_t& instance) const;
};

/** Makes the street's vegetation porous, as real foliage is to a LiDAR: the trees' canopies
 *  become leaves beams enter (free path 1 m) and bushes (0.4 m) and hedges (0.3 m) line the
 *  sidewalks, between the trees and in front of the buildings. Each beam's depth in the leaves is
 *  drawn from the ray and the time, so the same beam a scan later (leaves move in the wind, the
 *  sensor moves) returns from another leaf or passes through. Draws from `rng` only: the rest of
 *  the scene (and its movers) is the same with and without foliage. */
void addFoliage(Scene& s, std::mt19937& rng, double length);

/** Street furniture thinner than a sparse LiDAR's beam spacing, on each side of the street
 *  behind the parked cars: traffic signs 7.3 m from its middle every 12-27 m (a board 0.6-0.9 m
 *  wide and tall, 3 cm thick, facing the traffic, on a pole 8 cm thick with its top 2.1-2.7 m
 *  above the ground); street lights 7.6 m from it every 25-40 m (poles 0.2 m thick, 6-8 m
 *  tall); and a railing 8 m from it along a stretch of 20-50 m (a rail 5 cm square 1 m up, on
 *  posts 5 cm thick every 2 m). A 16-beam LiDAR's beams are 0.5 m apart 15 m away: one ring on
 *  a board, none or one on a rail. Draws from `rng` only: the rest of the scene (and its
 *  movers) is the same with and without. */
void addRoadside(Scene& s, std::mt19937& rng, double length);

/** The street of the default scene, `length` metres long (plus margins): buildings, trees and
 *  parked cars on both sides, four cars that drive and three people (boxes) that walk. */
Scene streetScene(std::mt19937& rng, double length);

/** The same street without cars that drive, and groups of walking people: `groups` groups of
 *  1 to 3 people at 0.8, 1.2 or 1.6 m/s, along the sidewalks (beside parked cars and trees) or
 *  across the road, 8 to 25 m from the sensor at mid-clip. The sensor moves along x from 0 to
 *  `length`; `duration` is the clip's length in seconds. */
Scene walkersScene(std::mt19937& rng, double length, double duration, int groups);

/** People walking along the sensor's line of sight, towards it or away (0 to 15 degrees off
 *  it), at 0.8, 1.2 or 1.6 m/s, 8 to 25 m away at mid-clip, alone or in groups of 2 or 3
 *  side by side: the beams through where they were land on them again, a little nearer or
 *  farther. */
Scene radialWalkersScene(std::mt19937& rng, double length, double duration, int groups);

/** The same street with groups of cyclists instead of people: `groups` groups of 1 or 2
 *  riders (one behind the other) at 3, 4.5 or 6 m/s, along the road by the parked cars, either
 *  way, or across it, 8 to 35 m from the sensor at mid-clip. */
Scene cyclistsScene(std::mt19937& rng, double length, double duration, int groups);

/** The same street with traffic around the sensor, which drives along x at `ego_speed` m/s:
 *  `groups` vehicles (a third of them vans taller than the sensor), each driving ahead of it
 *  in its lane at about its speed (12 to 30 m on at mid-clip), behind it at about its speed,
 *  in the next lane a little faster or slower, or the other way: the cars that follow or lead
 *  the sensor hide their own next places from the scans before. */
Scene trafficScene(std::mt19937& rng, double length, double duration, double ego_speed, int groups);

}  // namespace synth
