// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   SensorModel.cpp
 * @brief  The sensor model estimated from a scan's elevations and azimuths.
 */
#include "hif/SensorModel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>

#include "hif/PillarGrid.h"

namespace hif
{
namespace
{
constexpr double kDeg = 180.0 / M_PI;
/** Azimuth columns, degrees: wider than the horizontal step of any spinning LiDAR of interest
 *  (0.4 degrees at most), so that each column holds a few points of every ring. */
constexpr int kColumns = 360;
/** In one column, elevations closer than this belong to the same ring, degrees: the closest
 *  rings of the LiDARs of interest are 0.125 degrees apart (a Pandar128's middle), while one
 *  ring's points over one degree of azimuth differ by hundredths. */
constexpr double kSameRingDeg = 0.1;
/** More "rings" than this are no rings. */
constexpr std::size_t kMaxRings = 256;

double median(std::vector<double> v)
{
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

/** A point's direction, degrees. */
struct Direction
{
    double el, az;
};

/** One ring's points in one column: mean elevation, and the azimuth steps between them. */
struct Cluster
{
    double el;
    std::size_t first, last;  ///< range in the column's sorted points
};
}  // namespace

std::optional<SensorModel> SensorModel::estimate(const PointsView& pts)
{
    // Points that no LiDAR of interest would give (spacings beyond 10 degrees: a few random
    // points) give no model.
    std::optional<SensorModel> m = estimateAny(pts);
    if (!m) return std::nullopt;
    try
    {
        m->validate();
    }
    catch (const std::invalid_argument&)
    {
        return std::nullopt;
    }
    return m;
}

std::optional<SensorModel> SensorModel::estimateAny(const PointsView& pts)
{
    std::vector<std::vector<Direction>> columns(kColumns);
    // Solid angle: 1 x 1 degree cells of (azimuth, elevation) that hold any point.
    std::vector<uint8_t> cells(360 * 180, 0);
    std::size_t all = 0, used = 0;
    for (std::size_t i = 0; i < pts.size; ++i)
    {
        const double x = pts.x[i], y = pts.y[i], z = pts.z[i];
        if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) continue;
        const double rxy = std::hypot(x, y);
        if (rxy == 0.0) continue;
        const double e = std::atan2(z, rxy) * kDeg;
        const double a = std::atan2(y, x) * kDeg + 180.0;  // [0, 360]
        const int ca = std::min(359, static_cast<int>(a));
        const int ce = std::clamp(static_cast<int>(e + 90.0), 0, 179);
        cells[static_cast<std::size_t>(ce * 360 + ca)] = 1;
        ++all;
        if (rxy < kMinEstimateRange) continue;
        columns[static_cast<std::size_t>(ca)].push_back({e, a});
        ++used;
    }
    if (used < kMinEstimatePoints) return std::nullopt;

    SensorModel m;
    double area_deg2 = 0.0;
    std::vector<uint8_t> az_seen(360, 0);
    for (int ce = 0; ce < 180; ++ce)
        for (int ca = 0; ca < 360; ++ca)
            if (cells[static_cast<std::size_t>(ce * 360 + ca)])
            {
                area_deg2 += std::cos((ce + 0.5 - 90.0) / kDeg);
                az_seen[static_cast<std::size_t>(ca)] = 1;
            }
    m.azimuth_coverage_deg = static_cast<double>(std::count(az_seen.begin(), az_seen.end(), 1));
    const double mean_spacing = std::sqrt(area_deg2 / static_cast<double>(all));

    // Each column's points sorted by elevation and cut into rings where two neighbours are
    // kSameRingDeg or more apart.
    std::vector<std::vector<Cluster>> col_clusters(kColumns);
    std::vector<std::size_t> counts;
    for (std::size_t c = 0; c < columns.size(); ++c)
    {
        auto& col = columns[c];
        if (col.empty()) continue;
        std::sort(col.begin(), col.end(),
                  [](const Direction& a, const Direction& b) { return a.el < b.el; });
        auto& cl = col_clusters[c];
        std::size_t first = 0;
        double sum = col[0].el;
        for (std::size_t k = 1; k <= col.size(); ++k)
        {
            if (k < col.size() && col[k].el - col[k - 1].el < kSameRingDeg)
            {
                sum += col[k].el;
                continue;
            }
            cl.push_back({sum / static_cast<double>(k - first), first, k - 1});
            if (k < col.size())
            {
                first = k;
                sum = col[k].el;
            }
        }
        // A cluster of far fewer points than the column's typical one is a stray (a return
        // between rings at an object's edge), not a ring.
        std::vector<double> sizes;
        for (const Cluster& k : cl) sizes.push_back(static_cast<double>(k.last - k.first + 1));
        const double typical = median(sizes);
        cl.erase(
            std::remove_if(cl.begin(), cl.end(),
                           [&](const Cluster& k)
                           { return static_cast<double>(k.last - k.first + 1) < 0.4 * typical; }),
            cl.end());
        counts.push_back(cl.size());
    }
    // The ring count: what the fullest tenth of the columns hold (others miss beams that went
    // to the sky or were absorbed; none holds more than one cluster per ring).
    std::sort(counts.begin(), counts.end());
    const std::size_t rings =
        counts[static_cast<std::size_t>(0.9 * static_cast<double>(counts.size() - 1))];
    // Full columns (one cluster per ring) give every ring's elevation; with rings, those
    // elevations agree from column to column.
    std::vector<std::vector<double>> ring_el(rings);
    std::size_t full = 0;
    for (const auto& cl : col_clusters)
    {
        if (cl.size() != rings) continue;
        ++full;
        for (std::size_t k = 0; k < rings; ++k) ring_el[k].push_back(cl[k].el);
    }
    bool has_rings = rings >= 2 && rings <= kMaxRings && full >= 3;
    std::vector<double> elevations;
    if (has_rings)
    {
        for (auto& v : ring_el) elevations.push_back(median(v));
        std::vector<double> gaps;
        for (std::size_t k = 1; k < rings; ++k) gaps.push_back(elevations[k] - elevations[k - 1]);
        const double spacing = median(gaps);
        // Consistency: a ring's elevation varies across the full columns by less than half the
        // spacing (in a rosette, "rings" are chance gaps and do not line up).
        std::vector<double> spread;
        for (std::size_t k = 0; k < rings; ++k)
            for (double e : ring_el[k]) spread.push_back(std::abs(e - elevations[k]));
        has_rings = spacing > 0.0 && median(spread) < spacing;

        m.vertical_spacing_deg = spacing;
    }
    if (!has_rings)
    {
        // No rings: the field of view from the 0.1 and 99.9 percentiles of the elevations.
        std::vector<double> el;
        for (const auto& col : columns)
            for (const Direction& d : col) el.push_back(d.el);
        std::sort(el.begin(), el.end());
        const auto at = [&](double q)
        { return el[static_cast<std::size_t>(q * static_cast<double>(el.size() - 1))]; };
        m.elevation_min_deg = at(0.001);
        m.elevation_max_deg = at(0.999);
        m.vertical_spacing_deg = mean_spacing;
        m.horizontal_resolution_deg = mean_spacing;
        return m;
    }
    m.beam_elevations_deg = elevations;
    m.elevation_min_deg = elevations.front();
    m.elevation_max_deg = elevations.back();

    // Horizontal resolution: the median azimuth step between the points of one ring in one
    // column.
    std::vector<double> steps;
    std::vector<double> az;
    for (std::size_t c = 0; c < columns.size(); ++c)
        for (const Cluster& cl : col_clusters[c])
        {
            az.clear();
            for (std::size_t k = cl.first; k <= cl.last; ++k) az.push_back(columns[c][k].az);
            std::sort(az.begin(), az.end());
            for (std::size_t k = 1; k < az.size(); ++k)
                if (az[k] - az[k - 1] > 1e-4) steps.push_back(az[k] - az[k - 1]);
        }
    m.horizontal_resolution_deg = steps.empty() ? mean_spacing : median(steps);
    return m;
}

SensorModel SensorModel::fromBeams(std::vector<double> el, double horizontal, double azimuth)
{
    if (el.size() < 2)
        throw std::invalid_argument("hif::SensorModel: " + std::to_string(el.size()) +
                                    " beam elevations given (at least 2)");
    std::sort(el.begin(), el.end());
    std::vector<double> gaps;
    for (std::size_t k = 1; k < el.size(); ++k) gaps.push_back(el[k] - el[k - 1]);
    SensorModel m;
    m.elevation_min_deg = el.front();
    m.elevation_max_deg = el.back();
    m.vertical_spacing_deg = median(gaps);
    m.horizontal_resolution_deg = horizontal;
    m.azimuth_coverage_deg = azimuth;
    m.beam_elevations_deg = std::move(el);
    m.validate();  // two beams at one elevation are not ascending
    return m;
}

SensorModel SensorModel::fromPattern(double el_min, double el_max, double spacing, double azimuth)
{
    SensorModel m;
    m.elevation_min_deg = el_min;
    m.elevation_max_deg = el_max;
    m.vertical_spacing_deg = spacing;
    m.horizontal_resolution_deg = spacing;
    m.azimuth_coverage_deg = azimuth;
    m.validate();
    return m;
}

std::vector<double> SensorModel::beamTangents() const
{
    std::vector<double> t;
    for (double e : beam_elevations_deg) t.push_back(std::tan(e / kDeg));
    return t;
}

double SensorModel::beamGapSlope(const std::vector<double>& tangents, double tan_el) const
{
    if (tangents.size() < 2) return std::tan(vertical_spacing_deg / kDeg);
    const auto it = std::upper_bound(tangents.begin(), tangents.end(), tan_el);
    const std::size_t k = std::clamp<std::size_t>(static_cast<std::size_t>(it - tangents.begin()),
                                                  1, tangents.size() - 1);
    return tangents[k] - tangents[k - 1];
}

std::string SensorModel::describe() const
{
    char buf[320];
    if (hasRings())
    {
        // Beams spaced unevenly (a VLP-32C's crowd near the horizon): the widest gap too, where
        // it is wider than the one and a half median spacings that neighbouring beams lie in.
        double widest = 0.0;
        for (std::size_t k = 1; k < beam_elevations_deg.size(); ++k)
            widest =
                std::max(widest, std::abs(beam_elevations_deg[k] - beam_elevations_deg[k - 1]));
        char uneven[64] = "";
        if (widest > 1.5 * vertical_spacing_deg)
            std::snprintf(uneven, sizeof uneven, "; %.3f at the widest", widest);
        std::snprintf(buf, sizeof buf,
                      "%zu beams from %.2f to %.2f deg, %.3f deg apart (median%s), %.3f deg "
                      "horizontally, %.0f deg of azimuth",
                      beam_elevations_deg.size(), elevation_min_deg, elevation_max_deg,
                      vertical_spacing_deg, uneven, horizontal_resolution_deg,
                      azimuth_coverage_deg);
    }
    else
        std::snprintf(buf, sizeof buf,
                      "no rings (non-repetitive pattern), elevations %.2f to %.2f deg, points "
                      "%.3f deg apart, %.0f deg of azimuth",
                      elevation_min_deg, elevation_max_deg, vertical_spacing_deg,
                      azimuth_coverage_deg);
    return buf;
}

void SensorModel::validate() const
{
    auto fail = [](const std::string& what)
    { throw std::invalid_argument("hif::SensorModel: " + what); };
    if (!(vertical_spacing_deg > 0.0 && vertical_spacing_deg <= 10.0))
        fail("vertical_spacing_deg " + std::to_string(vertical_spacing_deg) + " is not in (0, 10]");
    if (!(horizontal_resolution_deg > 0.0 && horizontal_resolution_deg <= 10.0))
        fail("horizontal_resolution_deg " + std::to_string(horizontal_resolution_deg) +
             " is not in (0, 10]");
    if (!(elevation_min_deg >= -90.0 && elevation_min_deg <= elevation_max_deg &&
          elevation_max_deg <= 90.0))
        fail("the field of view " + std::to_string(elevation_min_deg) + " to " +
             std::to_string(elevation_max_deg) + " deg is empty or beyond +-90 deg");
    if (!(azimuth_coverage_deg > 0.0 && azimuth_coverage_deg <= 360.0))
        fail("azimuth_coverage_deg " + std::to_string(azimuth_coverage_deg) +
             " is not in (0, 360]");
    for (std::size_t k = 0; k < beam_elevations_deg.size(); ++k)
    {
        const double e = beam_elevations_deg[k];
        if (!(e >= elevation_min_deg && e <= elevation_max_deg) ||
            (k > 0 && !(e > beam_elevations_deg[k - 1])))
            fail("beam " + std::to_string(k) + " at " + std::to_string(e) +
                 " deg is not ascending within the field of view");
    }
}

std::optional<std::string> SensorModel::contradiction(const SensorModel& o) const
{
    auto differs = [](double a, double b) { return std::abs(a - b) > 0.25 * std::max(a, b); };
    char buf[256];
    if (hasRings() != o.hasRings())
        return std::string(hasRings() ? "rings expected, the scan has none"
                                      : "no rings expected, the scan has rings");
    const double n = static_cast<double>(beam_elevations_deg.size());
    const double no = static_cast<double>(o.beam_elevations_deg.size());
    if (std::abs(n - no) > 0.1 * n)
    {
        std::snprintf(buf, sizeof buf, "%zu beams expected, the scan has %zu",
                      beam_elevations_deg.size(), o.beam_elevations_deg.size());
        return std::string(buf);
    }
    if (differs(vertical_spacing_deg, o.vertical_spacing_deg))
    {
        std::snprintf(buf, sizeof buf, "beams %.3f deg apart expected, the scan's are %.3f",
                      vertical_spacing_deg, o.vertical_spacing_deg);
        return std::string(buf);
    }
    if (differs(horizontal_resolution_deg, o.horizontal_resolution_deg))
    {
        std::snprintf(buf, sizeof buf,
                      "a horizontal resolution of %.3f deg expected, the scan's is %.3f",
                      horizontal_resolution_deg, o.horizontal_resolution_deg);
        return std::string(buf);
    }
    return std::nullopt;
}

bool SensorModel::seesLessThan(const SensorModel& o) const
{
    if (hasRings() != o.hasRings()) return false;  // another kind of sensor: contradiction()
    const double n = static_cast<double>(beam_elevations_deg.size());
    const double no = static_cast<double>(o.beam_elevations_deg.size());
    // By more than a tenth each: scans of one sensor differ by a little (a rosette's edges, a
    // ring that met only sky), a part of a sweep by much more.
    constexpr double kMore = 1.1;
    return no > kMore * n ||
           o.elevation_max_deg - o.elevation_min_deg >
               kMore * (elevation_max_deg - elevation_min_deg) ||
           o.azimuth_coverage_deg > kMore * azimuth_coverage_deg;
}

RangeImageLayout RangeImageLayout::forSensor(const std::optional<SensorModel>& model)
{
    RangeImageLayout l;
    double lo_deg = -30.0, hi_deg = 15.0, row_deg = 0.2;
    if (model)
    {
        const double s = model->vertical_spacing_deg;
        lo_deg = std::max(-80.0, model->elevation_min_deg - 2.0 * s);
        hi_deg = std::min(80.0, model->elevation_max_deg + 2.0 * s);
        // Rows half a vertical spacing, columns half a horizontal step; each 0.05 degrees at
        // least: finer helps no LiDAR of interest and costs memory (and a spacing of a
        // millionth of a degree, which validate() lets through, would ask for billions).
        row_deg = std::max(0.05, 0.5 * s);
        const double step = std::max(0.05, 0.5 * model->horizontal_resolution_deg);
        l.cols = static_cast<int>(std::ceil(360.0 / step));
    }
    l.tan_min = std::tan(lo_deg / kDeg);
    l.tan_max = std::tan(hi_deg / kDeg);
    l.tan_res = row_deg / kDeg;
    l.rows = static_cast<int>((l.tan_max - l.tan_min) / l.tan_res) + 1;
    return l;
}

bool operator==(const SensorModel& a, const SensorModel& b)
{
    return a.beam_elevations_deg == b.beam_elevations_deg &&
           a.elevation_min_deg == b.elevation_min_deg &&
           a.elevation_max_deg == b.elevation_max_deg &&
           a.vertical_spacing_deg == b.vertical_spacing_deg &&
           a.horizontal_resolution_deg == b.horizontal_resolution_deg &&
           a.azimuth_coverage_deg == b.azimuth_coverage_deg;
}

}  // namespace hif
