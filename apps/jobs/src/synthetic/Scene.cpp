// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Scene.cpp
 * @brief  Ray casting against boxes, vertical cylinders and spheres; the scenes.
 */
#include "Scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace synth
{
namespace
{
/** Where the ray from o along d is inside the box, within [0, t_max]: [t0, t1]; false if nowhere.
 */
bool boxSpan(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& b, double t_max,
             double& t0, double& t1)
{
    t0 = 0;
    t1 = t_max;
    for (int k = 0; k < 3; ++k)
    {
        const double inv = 1.0 / d[k];
        double a = (b.lo[k] - o[k]) * inv, c = (b.hi[k] - o[k]) * inv;
        if (a > c) std::swap(a, c);
        t0 = std::max(t0, a);
        t1 = std::min(t1, c);
        if (t0 > t1) return false;
    }
    return true;
}

void hitBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Box& b, uint32_t label,
            Hit& h)
{
    double t0 = 0, t1 = 0;
    if (boxSpan(o, d, b, h.t, t0, t1) && t0 > 1e-6 && t0 < h.t) h = {t0, label};
}

/** Where the ray from o along unit d is inside the sphere: [t0, t1] (t0 may be negative). */
bool sphereSpan(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Sphere& s, double& t0,
                double& t1)
{
    const Eigen::Vector3d oc = o - s.c;
    const double b = oc.dot(d);
    const double disc = b * b - (oc.squaredNorm() - s.r * s.r);
    if (disc < 0) return false;
    t0 = -b - std::sqrt(disc);
    t1 = -b + std::sqrt(disc);
    return true;
}

/** SplitMix64's finalizer: a well-mixed 64-bit value from any. */
uint64_t mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/** A depth in leaves of mean `free_path`, the same for the same ray, time, volume and seed. */
double leafDepth(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t, std::size_t volume,
                 uint64_t seed, double free_path)
{
    uint64_t h = mix(seed ^ (volume * 0x9e3779b97f4a7c15ULL));
    for (const double v : {o.x(), o.y(), o.z(), d.x(), d.y(), d.z(), t})
    {
        uint64_t bits = 0;
        std::memcpy(&bits, &v, sizeof bits);
        h = mix(h ^ bits);
    }
    const double u = double(h >> 11) * 0x1.0p-53;  // [0, 1)
    return -free_path * std::log1p(-u);
}

/** A beam's return from the leaves of [t0, t1] when it lies in front of h. */
void hitLeaves(double t0, double t1, double depth, Hit& h)
{
    t0 = std::max(t0, 0.0);
    const double t = t0 + depth;
    if (t1 > t0 && t < t1 && t > 1e-6 && t < h.t) h = {t, kVegetation};
}

/** A box of half-extents `half` (along u, v = z x u, and z) centred at `c`, u horizontal. */
void hitOrientedBox(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& c,
                    const Eigen::Vector3d& u, const Eigen::Vector3d& half, uint32_t label, Hit& h)
{
    const Eigen::Vector3d v(-u.y(), u.x(), 0.0);
    const Eigen::Vector3d oc = o - c;
    const Eigen::Vector3d o_local(oc.dot(u), oc.dot(v), oc.z());
    const Eigen::Vector3d d_local(d.dot(u), d.dot(v), d.z());
    hitBox(o_local, d_local, {-half, half, label}, label, h);
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

/** Buildings, trees and parked cars on both sides of the street, from -30 to length + 30. */
void addStreet(Scene& s, std::mt19937& rng, double length)
{
    std::uniform_real_distribution<double> u(0, 1);
    // Buildings on both sides, with gaps between them.
    for (int side : {-1, 1})
        for (double x = -30; x < length + 30;)
        {
            const double w = 10 + 15 * u(rng), h = 6 + 10 * u(rng), y0 = 13 + 3 * u(rng);
            const double y_near = side * y0, y_far = side * (y0 + 10);
            s.boxes.push_back({Eigen::Vector3d(x, std::min(y_near, y_far), groundZ(x) - 1),
                               Eigen::Vector3d(x + w, std::max(y_near, y_far), groundZ(x) + h),
                               kBuilding});
            x += w + 3 + 6 * u(rng);
        }
    // Trees along both sidewalks: trunk and canopy.
    for (int side : {-1, 1})
        for (double x = -20 + 6 * u(rng); x < length + 20; x += 10 + 6 * u(rng))
        {
            const double y = side * (9.5 + u(rng)), gz = groundZ(x);
            s.cylinders.push_back({x, y, 0.2, gz - 0.5, gz + 3.0, kTrunk});
            s.spheres.push_back({Eigen::Vector3d(x, y, gz + 4.0), 1.5 + 0.5 * u(rng), kVegetation});
        }
    // Parked cars along both kerbs.
    for (int side : {-1, 1})
        for (double x = -10 + 8 * u(rng); x < length + 10; x += 9 + 12 * u(rng))
        {
            const double y = side * 6.0, gz = groundZ(x);
            s.boxes.push_back({Eigen::Vector3d(x - 2.1, y - 0.9, gz + 0.15),
                               Eigen::Vector3d(x + 2.1, y + 0.9, gz + 1.5), kCar});
        }
}

/** Where a group stands at mid-clip: `dist` from the sensor's mid-clip position (x_mid, 0),
 *  `y` to the side, ahead of it (`ahead` +1) or behind (-1); at least 1 m along x. */
Eigen::Vector3d groupCentre(double x_mid, double ahead, double dist, double y)
{
    return {x_mid + ahead * std::sqrt(std::max(1.0, dist * dist - y * y)), y, 0.0};
}
/** A group of 1 to 3 people side by side (0.7 m apart, across `along`, the unit direction of
 *  `vel`), centred on `mid` at time t_mid, walking at about `vel` with swinging legs. */
void addWalkers(Scene& s, std::mt19937& rng, const Eigen::Vector3d& mid, const Eigen::Vector3d& vel,
                const Eigen::Vector3d& along, double t_mid, uint32_t& id)
{
    std::uniform_real_distribution<double> u(0, 1);
    const int members = u(rng) < 0.5 ? 1 : (u(rng) < 0.6 ? 2 : 3);
    const Eigen::Vector3d beside(-along.y(), along.x(), 0.0);
    for (int k = 0; k < members; ++k)
    {
        Mover m;
        m.velocity = vel * (1.0 + 0.05 * (u(rng) - 0.5));
        m.start = mid + beside * (0.7 * k) - m.velocity * t_mid;
        m.size = Eigen::Vector3d(0.5, 0.5, 1.6 + 0.25 * u(rng));
        m.label = kMovingPerson;
        m.instance = id++;
        m.shape = Mover::Shape::Walker;
        m.phase = 2 * M_PI * u(rng);
        s.movers.push_back(m);
    }
}
}  // namespace

void Mover::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t, Hit& h) const
{
    const Eigen::Vector3d c = start + velocity * t;
    const double gz = groundZ(c.x());
    if (shape == Shape::Box)
    {
        const Eigen::Vector3d half(size.x() / 2, size.y() / 2, 0);
        hitBox(
            o, d,
            {Eigen::Vector3d(c.x() - half.x(), c.y() - half.y(), gz + 0.15 * (label == kMovingCar)),
             Eigen::Vector3d(c.x() + half.x(), c.y() + half.y(), gz + size.z()), label},
            label, h);
        return;
    }
    const double speed = velocity.norm();
    const Eigen::Vector3d u =
        speed > 0 ? Eigen::Vector3d(velocity / speed) : Eigen::Vector3d::UnitX();
    const Eigen::Vector3d v(-u.y(), u.x(), 0.0);
    if (shape == Shape::Cyclist)
    {
        // A bicycle 1.72 m long: wheels 0.68 m across and 0.05 m thick, a frame between them;
        // its rider: legs beside the frame up to the saddle (0.95 m), pedalling, a torso
        // leaning forward to 1.45 m, a head at 1.6 m.
        for (const double along : {-0.52, 0.52})
            hitOrientedBox(o, d, Eigen::Vector3d(c.x(), c.y(), gz + 0.34) + u * along, u,
                           Eigen::Vector3d(0.34, 0.025, 0.34), label, h);
        hitOrientedBox(o, d, Eigen::Vector3d(c.x(), c.y(), gz + 0.62), u,
                       Eigen::Vector3d(0.45, 0.03, 0.14), label, h);
        const double pedal = 0.15 * std::sin(2 * M_PI * 1.2 * t + phase);
        for (int side : {-1, 1})
        {
            const Eigen::Vector3d leg = c + v * (0.12 * side) + u * (0.05 + pedal * side);
            hitCylinder(o, d,
                        {leg.x(), leg.y(), 0.07, gz + 0.35 + 0.1 * side * pedal, gz + 0.95, label},
                        h);
        }
        const Eigen::Vector3d torso = c + u * 0.05;
        hitCylinder(o, d, {torso.x(), torso.y(), 0.17, gz + 0.95, gz + 1.45, label}, h);
        hitSphere(o, d, {c + u * 0.3 + Eigen::Vector3d(0, 0, gz + 1.6 - c.z()), 0.11, label}, h);
        return;
    }
    // A person of height size.z(): legs 0.07 m thick up to 49 % of the height, swinging
    // 0.25 m forward and back at a cadence that grows with speed; a torso 0.18 m in radius up
    // to 84 %; a head.
    const double height = size.z();
    const double swing =
        0.25 * std::min(1.0, speed) * std::sin(2 * M_PI * (speed / 1.4) * t + phase);
    for (int side : {-1, 1})
    {
        const Eigen::Vector3d leg = c + v * (0.1 * side) + u * (swing * side);
        hitCylinder(o, d, {leg.x(), leg.y(), 0.07, gz, gz + 0.49 * height, label}, h);
    }
    hitCylinder(o, d, {c.x(), c.y(), 0.18, gz + 0.49 * height, gz + 0.84 * height, label}, h);
    hitSphere(o, d, {Eigen::Vector3d(c.x(), c.y(), gz + 0.92 * height), 0.11, label}, h);
}

Hit Scene::cast(const Eigen::Vector3d& o, const Eigen::Vector3d& d, double t_now, double max_range,
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
    for (std::size_t k = 0; k < foliage_boxes.size(); ++k)
    {
        const FoliageBox& f = foliage_boxes[k];
        double t0 = 0, t1 = 0;
        if (boxSpan(o, d, f.box, h.t, t0, t1))
            hitLeaves(t0, t1, leafDepth(o, d, t_now, k, foliage_seed, f.free_path), h);
    }
    for (std::size_t k = 0; k < foliage_spheres.size(); ++k)
    {
        const FoliageSphere& f = foliage_spheres[k];
        double t0 = 0, t1 = 0;
        if (sphereSpan(o, d, f.sphere, t0, t1) && t0 < h.t)
            hitLeaves(t0, t1,
                      leafDepth(o, d, t_now, foliage_boxes.size() + k, foliage_seed, f.free_path),
                      h);
    }
    instance = 0;
    for (const Mover& m : movers)
    {
        const uint32_t before = h.label;
        const double t_before = h.t;
        m.cast(o, d, t_now, h);
        if (h.t != t_before || h.label != before) instance = m.instance;
    }
    if (h.t >= max_range)
        h.label = 0;
    else if (instance != 0 &&
             !(h.label == kMovingCar || h.label == kMovingPerson || h.label == kMovingBicyclist))
        instance = 0;
    return h;
}

void addFoliage(Scene& s, std::mt19937& rng, double length)
{
    // Leaf area densities of 1-2 m2/m3 (urban trees) to 6-7 (a trimmed hedge), half of it facing
    // a beam: a free path of about 1 m in a canopy, 0.4 m in a bush, 0.3 m in a hedge.
    constexpr double kCanopy = 1.0, kBush = 0.4, kHedge = 0.3;
    std::uniform_real_distribution<double> u(0, 1);
    const uint64_t high = rng();  // two statements: the order of the two draws is defined
    s.foliage_seed = (high << 32) | rng();
    std::vector<Sphere> solid;
    for (const Sphere& c : s.spheres)
        if (c.label == kVegetation)
            s.foliage_spheres.push_back({c, kCanopy});
        else
            solid.push_back(c);
    s.spheres = std::move(solid);
    auto nearTrunk = [&](double x, double y, double r)
    {
        for (const Cylinder& c : s.cylinders)
            if (c.label == kTrunk && std::hypot(c.cx - x, c.cy - y) < c.r + r + 0.1) return true;
        return false;
    };
    for (int side : {-1, 1})
    {
        // Bushes 0.9-1.3 m tall along the sidewalk's outer edge, between the trees.
        for (double x = -20 + 4 * u(rng); x < length + 20; x += 2.5 + 5 * u(rng))
        {
            const double r = 0.6 + 0.3 * u(rng), y = side * (9.2 + 1.2 * u(rng));
            if (nearTrunk(x, y, r)) continue;
            s.foliage_spheres.push_back(
                {{Eigen::Vector3d(x, y, groundZ(x) + 0.3 + 0.1 * u(rng)), r, kVegetation}, kBush});
        }
        // Hedges 1-1.8 m tall and about 1 m thick in front of the buildings, with gaps.
        for (double x = -30 + 5 * u(rng); x < length + 30;)
        {
            const double w = 4 + 6 * u(rng), h = 1.0 + 0.8 * u(rng), y0 = 11.0 + 0.3 * u(rng);
            const double y_near = side * y0, y_far = side * (y0 + 0.8 + 0.4 * u(rng));
            s.foliage_boxes.push_back(
                {{Eigen::Vector3d(x, std::min(y_near, y_far), groundZ(x) - 0.2),
                  Eigen::Vector3d(x + w, std::max(y_near, y_far), groundZ(x + w) + h), kVegetation},
                 kHedge});
            x += w + 2 + 4 * u(rng);
        }
    }
}

void addRoadside(Scene& s, std::mt19937& rng, double length)
{
    std::uniform_real_distribution<double> u(0, 1);
    for (int side : {-1, 1})
    {
        // Traffic signs at the sidewalk's edge, behind the parked cars.
        for (double x = -20 + 10 * u(rng); x < length + 20; x += 12 + 15 * u(rng))
        {
            const double y = side * 7.3, gz = groundZ(x);
            const double top = gz + 2.1 + 0.6 * u(rng), w = 0.6 + 0.3 * u(rng);
            const double h = 0.6 + 0.3 * u(rng);
            s.cylinders.push_back({x, y, 0.04, gz - 0.2, top - 0.05, kPole});
            s.boxes.push_back({Eigen::Vector3d(x - 0.065, y - w / 2, top - h),
                               Eigen::Vector3d(x - 0.035, y + w / 2, top), kTrafficSign});
        }
        // Street lights.
        for (double x = -30 + 15 * u(rng); x < length + 30; x += 25 + 15 * u(rng))
        {
            const double gz = groundZ(x);
            s.cylinders.push_back({x, side * 7.6, 0.1, gz - 0.2, gz + 6 + 2 * u(rng), kPole});
        }
        // A railing along a stretch of the sidewalk.
        const double x0 = -10 + (length + 20) * 0.5 * u(rng), x1 = x0 + 20 + 30 * u(rng);
        const double y = side * 8.0;
        for (double x = x0; x < x1; x += 2.0)
        {
            const double gz = groundZ(x);
            s.cylinders.push_back({x, y, 0.025, gz - 0.2, gz + 0.95, kFence});
            const double xe = std::min(x + 2.0, x1);
            s.boxes.push_back({Eigen::Vector3d(x, y - 0.025, gz + 0.95),
                               Eigen::Vector3d(xe, y + 0.025, groundZ(xe) + 1.0), kFence});
        }
    }
}

Scene streetScene(std::mt19937& rng, double length)
{
    Scene s;
    addStreet(s, rng, length);
    // Moving cars: two overtake us in our direction, two come the other way; people walk
    // along the sidewalks and one crosses the street.
    uint32_t id = 1;
    const Eigen::Vector3d car(4.4, 1.9, 1.5), person(0.6, 0.6, 1.75);
    s.movers.push_back({{-15, -2.0, 0}, {13, 0, 0}, car, kMovingCar, id++});
    s.movers.push_back({{10, -2.0, 0}, {11, 0, 0}, car, kMovingCar, id++});
    s.movers.push_back({{length + 10, 2.0, 0}, {-10, 0, 0}, car, kMovingCar, id++});
    s.movers.push_back({{length + 40, 2.2, 0}, {-12, 0, 0}, car, kMovingCar, id++});
    s.movers.push_back({{12, -7.5, 0}, {1.4, 0, 0}, person, kMovingPerson, id++});
    s.movers.push_back({{35, 7.5, 0}, {-1.3, 0, 0}, person, kMovingPerson, id++});
    s.movers.push_back({{28, -4.0, 0}, {0, 1.2, 0}, person, kMovingPerson, id++});
    return s;
}

Scene walkersScene(std::mt19937& rng, double length, double duration, int groups)
{
    Scene s;
    addStreet(s, rng, length);
    std::uniform_real_distribution<double> u(0, 1);
    const double speeds[3] = {0.8, 1.2, 1.6};
    const double t_mid = 0.5 * duration, x_mid = 0.5 * length;
    uint32_t id = 1;
    for (int g = 0; g < groups; ++g)
    {
        const double speed = speeds[std::min(2, static_cast<int>(3 * u(rng)))];
        const bool across = u(rng) < 0.5;
        const double sign = u(rng) < 0.5 ? -1.0 : 1.0;  // direction of walking
        const double side = u(rng) < 0.5 ? -1.0 : 1.0;  // side of the street
        // Where the group is at mid-clip: 8 to 25 m from the sensor, mostly ahead.
        const double dist = 8.0 + 17.0 * u(rng);
        Eigen::Vector3d mid, vel;
        if (across)
        {
            const double y = side * 4.0 * u(rng);  // on the road
            mid = groupCentre(x_mid, u(rng) < 0.8 ? 1.0 : -1.0, dist, y);
            vel = Eigen::Vector3d(0.0, sign * speed, 0.0);
        }
        else
        {
            const double y = side * (7.2 + 1.2 * u(rng));  // sidewalk, by the parked cars
            mid = groupCentre(x_mid, u(rng) < 0.8 ? 1.0 : -1.0, dist, y);
            vel = Eigen::Vector3d(sign * speed, 0.0, 0.0);
        }
        addWalkers(s, rng, mid, vel, vel / speed, t_mid, id);
    }
    return s;
}

Scene radialWalkersScene(std::mt19937& rng, double length, double duration, int groups)
{
    Scene s;
    addStreet(s, rng, length);
    std::uniform_real_distribution<double> u(0, 1);
    const double speeds[3] = {0.8, 1.2, 1.6};
    const double t_mid = 0.5 * duration, x_mid = 0.5 * length;
    const Eigen::Vector3d sensor_mid(x_mid, 0.0, 0.0);
    uint32_t id = 1;
    for (int g = 0; g < groups; ++g)
    {
        const double speed = speeds[std::min(2, static_cast<int>(3 * u(rng)))];
        const bool towards = u(rng) < 0.5;
        // 0 to 15 degrees off the line of sight, to either side.
        const double side = u(rng) < 0.5 ? -1.0 : 1.0;  // drawn first: the order is defined
        const double off = side * 15.0 * u(rng) * M_PI / 180.0;
        // Where the group is at mid-clip: 8 to 25 m from the sensor, mostly ahead, on the road
        // or the sidewalks.
        const double dist = 8.0 + 17.0 * u(rng);
        const double y = (2.0 * u(rng) - 1.0) * std::min(7.8, 0.5 * dist);
        const Eigen::Vector3d mid = groupCentre(x_mid, u(rng) < 0.75 ? 1.0 : -1.0, dist, y);
        const Eigen::Vector3d los = (mid - sensor_mid).normalized();
        const Eigen::Vector3d along =
            Eigen::AngleAxisd(off, Eigen::Vector3d::UnitZ()) * (towards ? -los : los);
        const Eigen::Vector3d vel = along * speed;
        addWalkers(s, rng, mid, vel, along, t_mid, id);
    }
    return s;
}

Scene cyclistsScene(std::mt19937& rng, double length, double duration, int groups)
{
    Scene s;
    addStreet(s, rng, length);
    std::uniform_real_distribution<double> u(0, 1);
    const double speeds[3] = {3.0, 4.5, 6.0};
    const double t_mid = 0.5 * duration, x_mid = 0.5 * length;
    uint32_t id = 1;
    for (int g = 0; g < groups; ++g)
    {
        const double speed = speeds[std::min(2, static_cast<int>(3 * u(rng)))];
        const bool across = u(rng) < 0.3;
        const double sign = u(rng) < 0.5 ? -1.0 : 1.0;  // direction of riding
        const double side = u(rng) < 0.5 ? -1.0 : 1.0;  // side of the street
        // Where the group is at mid-clip: 8 to 35 m from the sensor, mostly ahead.
        const double dist = 8.0 + 27.0 * u(rng);
        const double ahead = u(rng) < 0.8 ? 1.0 : -1.0;
        Eigen::Vector3d mid, vel;
        if (across)
        {
            const double y = side * 4.0 * u(rng);
            mid = groupCentre(x_mid, ahead, dist, y);
            vel = Eigen::Vector3d(0.0, sign * speed, 0.0);
        }
        else
        {
            const double y = side * (3.6 + 1.2 * u(rng));  // by the parked cars
            mid = groupCentre(x_mid, ahead, dist, y);
            vel = Eigen::Vector3d(sign * speed, 0.0, 0.0);
        }
        const int members = u(rng) < 0.6 ? 1 : 2;
        for (int k = 0; k < members; ++k)
        {
            Mover m;
            m.velocity = vel * (1.0 + 0.05 * (u(rng) - 0.5));
            m.start = mid - vel / speed * (2.5 * k) - m.velocity * t_mid;  // one behind the other
            m.size = Eigen::Vector3d(1.72, 0.6, 1.71);
            m.label = kMovingBicyclist;
            m.instance = id++;
            m.shape = Mover::Shape::Cyclist;
            m.phase = 2 * M_PI * u(rng);
            s.movers.push_back(m);
        }
    }
    return s;
}

Scene trafficScene(std::mt19937& rng, double length, double duration, double ego_speed, int groups)
{
    Scene s;
    addStreet(s, rng, length);
    std::uniform_real_distribution<double> u(0, 1);
    const double t_mid = 0.5 * duration, x_mid = 0.5 * length;
    uint32_t id = 1;
    for (int g = 0; g < groups; ++g)
    {
        const int kind = std::min(3, static_cast<int>(4 * u(rng)));
        const bool van = u(rng) < 1.0 / 3.0;
        Mover m;
        m.size = van ? Eigen::Vector3d(5.0, 2.0, 2.5) : Eigen::Vector3d(4.4, 1.9, 1.5);
        m.label = kMovingCar;
        m.instance = id++;
        // Where it is at mid-clip, and its velocity along x: its lane, the sensor's (y = 0)
        // or the next one (y = -3, the same way; y = +3, the other way).
        double x = 0.0, y = 0.0, v = 0.0;
        switch (kind)
        {
            case 0:  // ahead, at about the sensor's speed
                x = x_mid + 12.0 + 18.0 * u(rng);
                v = ego_speed * (0.9 + 0.2 * u(rng));
                break;
            case 1:  // behind, at about the sensor's speed
                x = x_mid - 10.0 - 15.0 * u(rng);
                v = ego_speed * (0.9 + 0.2 * u(rng));
                break;
            case 2:  // the next lane, 1 to 3 m/s faster or slower
            {
                // Each side drawn before its distance or speed: the order of draws is defined.
                const double ahead = u(rng) < 0.5 ? -1.0 : 1.0;
                x = x_mid + ahead * (5.0 + 20.0 * u(rng));
                y = -3.0;
                const double faster = u(rng) < 0.5 ? -1.0 : 1.0;
                v = ego_speed + faster * (1.0 + 2.0 * u(rng));
                break;
            }
            default:  // the other way
                x = x_mid + 15.0 + 25.0 * u(rng);
                y = 3.0;
                v = -(8.0 + 6.0 * u(rng));
                break;
        }
        m.velocity = Eigen::Vector3d(v, 0.0, 0.0);
        m.start = Eigen::Vector3d(x, y, 0.0) - m.velocity * t_mid;
        s.movers.push_back(m);
    }
    return s;
}

}  // namespace synth
