// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FreeSpace.cpp
 * @brief  The free-space test: was a point of this scan seen through by other scans?
 */
#include "FreeSpace.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "GridAccess.h"
#include "RangeImage.h"

namespace hif::detail
{
namespace
{
/** What one other scan says about one point. */
enum class View : uint8_t
{
    None,      ///< no beam near the point's direction, or one that stopped before it
    Occupied,  ///< a return near the point
    Vetoed,    ///< the beam toward it returned clearly beyond, but another one near it
    Free       ///< the beam toward it returned clearly beyond, and none near it
};

/** The window's scans that may judge the classified scan, with what a test needs. */
struct Judge
{
    std::size_t id;
    Eigen::Vector3d t;  ///< sensor position, world frame
    Eigen::Matrix3d Rt;
    const uint16_t* image;  ///< centimetres (ScanWindow::Scan::image)
    double baseline = 0.0;  ///< distance to the classified scan's sensor

    /** Range of the nearest return in cell (r, c), metres; +inf for none. */
    [[nodiscard]] float at(int r, int c) const
    {
        const uint16_t v = image[static_cast<std::size_t>(r) * kImageCols + c];
        return v == ScanWindow::kNoReturn ? std::numeric_limits<float>::infinity()
                                          : static_cast<float>(v) * 0.01f;
    }
};

/** What scan `j` saw at world point `p` (range margin `margin(d)`). */
View look(const Judge& j, const Eigen::Vector3d& p, double margin0, double margin_per_m)
{
    const Eigen::Vector3d q = j.Rt * (p - j.t);
    const double rxy = std::sqrt(q.x() * q.x() + q.y() * q.y());
    if (rxy == 0.0) return View::None;
    const double tan_el = q.z() / rxy;
    if (!(tan_el >= kTanMin && tan_el < kTanMax)) return View::None;
    const int c = std::min(kImageCols - 1,
                           static_cast<int>(pseudoAzimuth(q.x(), q.y()) * (kImageCols / 4.0)));
    const int r = std::min(kImageRows - 1, static_cast<int>((tan_el - kTanMin) / kTanRes));
    const double d = std::sqrt(rxy * rxy + q.z() * q.z());
    const double m = margin0 + margin_per_m * d;
    // The beam through the point: that of its own cell, else the nearest one around it.
    const float own = j.at(r, c);
    if (own <= d + m) return own > d - m ? View::Occupied : View::None;  // or occluded
    float e = own;
    bool near = false;
    int best = std::numeric_limits<int>::max();
    for (int dr = -1; dr <= 1; ++dr)
    {
        const int rr = r + dr;
        if (rr < 0 || rr >= kImageRows) continue;
        for (int dc = -1; dc <= 1; ++dc)
        {
            const float f = j.at(rr, (c + dc + kImageCols) % kImageCols);
            if (!std::isfinite(f)) continue;
            near = near || (f > d - m && f <= d + m);
            const int dist = dr * dr + dc * dc;
            if (!std::isfinite(own) && (dist < best || (dist == best && f > e)))
            {
                best = dist;
                e = f;
            }
        }
    }
    if (!std::isfinite(e)) return View::None;  // no beam near the point's direction
    if (e <= d + m) return e > d - m ? View::Occupied : View::None;
    return near ? View::Vetoed : View::Free;  // passed, unless something is near it
}
}  // namespace

std::size_t markSeenThrough(const PillarGrid& grid, const ScanBuckets& scan, const PointsView& pts,
                            const Eigen::Isometry3d& T, const ScanWindow& window,
                            std::optional<std::size_t> self, std::vector<uint8_t>& is_dynamic)
{
    const Params& prm = grid.params();
    const double res = grid.geometry().height_resolution;
    std::vector<Judge> judges;
    for (const ScanWindow::Scan& s : window.scans())
    {
        if (self &&
            (s.id == *self || (s.id < *self ? *self - s.id : s.id - *self) > prm.free_space_window))
            continue;
        judges.push_back(
            {s.id, s.sensor_to_world.translation(), s.world_to_sensor_rotation, s.image.data()});
    }
    if (judges.empty()) return 0;

    const Eigen::Matrix3d R = T.linear();
    const Eigen::Vector3d t = T.translation();
    for (Judge& j : judges) j.baseline = (j.t - t).norm();
    const double range2 = prm.free_space_range * prm.free_space_range;
    const auto clearance = static_cast<int32_t>(std::ceil(prm.free_space_clearance / res - 1e-9));
    const int32_t below = clearance / 2;  // marked from half the clearance up
    const double cos_parallax = std::cos(prm.free_space_max_parallax_deg * M_PI / 180.0);
    // Seen from a point at distance a, two sensors a baseline b apart subtend at most
    // asin(b / a): within the limit without computing the angle when b <= a sin(limit).
    const double sin_parallax = prm.free_space_max_parallax_deg >= 90.0
                                    ? 1.0
                                    : std::sin(prm.free_space_max_parallax_deg * M_PI / 180.0);
    // Where the classified scan sits among the judges by id (a scan without one is newer
    // than the whole window, as online).
    const std::size_t self_pos =
        self ? static_cast<std::size_t>(std::lower_bound(judges.begin(), judges.end(), *self,
                                                         [](const Judge& j, std::size_t id)
                                                         { return j.id < id; }) -
                                        judges.begin())
             : judges.size();
    auto rangeSq = [&](uint32_t i)
    {
        const double x = pts.x[i], y = pts.y[i], z = pts.z[i];
        return x * x + y * y + z * z;
    };

    // Whether other scans showed the point of entry k gone: the judges that saw it occupied,
    // with this scan, span a stretch of time; only a judge outside it that saw through the point
    // shows it gone. On each side of the scan, walking in from the farthest judge, the first
    // one with an opinion decides that side: seen through, gone; occupied, the stretch reaches
    // it, so no nearer judge of that side can show the point gone.
    auto shownGone = [&](uint32_t k)
    {
        const uint32_t i = scan.index[k];
        const Eigen::Vector3d p_w = R * Eigen::Vector3d(pts.x[i], pts.y[i], pts.z[i]) + t;
        const Eigen::Vector3d from_self = p_w - t;
        const double self_dist = from_self.norm();
        auto opinion = [&](const Judge& j)
        {
            const Eigen::Vector3d from_j = p_w - j.t;
            const bool in_view = j.baseline <= self_dist * sin_parallax ||
                                 from_self.dot(from_j) >= cos_parallax * self_dist * from_j.norm();
            return in_view ? look(j, p_w, prm.free_space_margin, prm.free_space_margin_per_m)
                           : View::None;
        };
        for (std::size_t j = 0; j < self_pos; ++j)  // the earlier judges, oldest first
        {
            const View v = opinion(judges[j]);
            if (v == View::Free) return true;
            if (v == View::Occupied) break;
        }
        for (std::size_t j = judges.size(); j-- > self_pos;)  // the later ones, newest first
        {
            const View v = opinion(judges[j]);
            if (v == View::Free) return true;
            if (v == View::Occupied) break;
        }
        return false;
    };

    std::size_t marked = 0;
    std::vector<uint32_t> tested;
    for (std::size_t p = 0; p < scan.pillarCount(); ++p)
    {
        const uint32_t b = scan.offsets[p], e = scan.offsets[p + 1];
        int32_t low = std::numeric_limits<int32_t>::max();
        for (uint32_t k = b; k < e; ++k) low = std::min(low, scan.cells[k]);
        // The pillar's kept points clear of its lowest return, within range.
        tested.clear();
        int32_t top = std::numeric_limits<int32_t>::min();
        int32_t bottom = std::numeric_limits<int32_t>::max();
        for (uint32_t k = b; k < e; ++k)
        {
            const uint32_t i = scan.index[k];
            if (is_dynamic[i] || scan.cells[k] < low + clearance || rangeSq(i) > range2) continue;
            tested.push_back(k);
            top = std::max(top, scan.cells[k]);
            bottom = std::min(bottom, scan.cells[k]);
        }
        if (tested.size() < 3 || (top - bottom + 1) * res < prm.free_space_min_extent) continue;

        // Stops as soon as the outcome is known.
        const auto need = static_cast<std::size_t>(
            std::ceil(prm.free_space_fraction * static_cast<double>(tested.size()) - 1e-9));
        std::size_t gone = 0, left = tested.size();
        for (uint32_t k : tested)
        {
            if (gone >= need || gone + left < need) break;
            gone += shownGone(k);
            --left;
        }
        if (gone < need) continue;
        for (uint32_t k = b; k < e; ++k)
        {
            const uint32_t i = scan.index[k];
            if (is_dynamic[i] || scan.cells[k] < low + below || rangeSq(i) > range2) continue;
            is_dynamic[i] = 1;
            ++marked;
        }
    }
    return marked;
}

}  // namespace hif::detail
