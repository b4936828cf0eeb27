// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarGrid.cpp
 * @brief  Scan integration into the global pillar dictionary, and point queries.
 */
#include "hif/PillarGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace hif
{
namespace
{
// Points closer than this (horizontally) to the sensor are ignored when measuring the top
// beam's elevation: there, range noise makes z / range unreliable.
constexpr double kMinRangeForElevation = 2.0;
}  // namespace

PillarGrid::PillarGrid(const Params& params) : params_(params)
{
    params_.validate();
    model_ = LogOddsModel::fromParams(params_);
}

void PillarGrid::setParams(const Params& params)
{
    params.validate();
    const bool same_geometry = params.pillar_size == params_.pillar_size &&
                               params.origin_x == params_.origin_x &&
                               params.origin_y == params_.origin_y &&
                               params.height_resolution == params_.height_resolution;
    if (!same_geometry && !empty())
        throw std::invalid_argument(
            "hif::PillarGrid::setParams: pillar_size, origin_x, origin_y and height_resolution "
            "cannot change once the map holds pillars (clear it first)");
    params_ = params;
    model_ = LogOddsModel::fromParams(params_);
}

std::optional<PillarIndex> PillarGrid::pillarOf(double x, double y) const
{
    const auto m = quantize(x, params_.origin_x, params_.pillar_size);
    const auto n = quantize(y, params_.origin_y, params_.pillar_size);
    if (!m || !n) return std::nullopt;
    return PillarIndex{*m, *n};
}

std::optional<int32_t> PillarGrid::heightCellOf(double z) const
{
    return quantize(z, 0.0, params_.height_resolution);
}

InsertStats PillarGrid::insertScan(const PointsView& pts, const Eigen::Isometry3d& T)
{
    InsertStats st;
    const Eigen::Matrix3d R = T.linear();
    const Eigen::Vector3d t = T.translation();

    // 1) transform, quantize (Eq. 1) and key every point; note the top beam's elevation
    //    (largest z / horizontal range in the sensor frame) for High-Height Preservation.
    buf_points_.clear();
    buf_points_.reserve(pts.size);
    double top_slope = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < pts.size; ++i)
    {
        const Eigen::Vector3d ps(pts.x[i], pts.y[i], pts.z[i]);
        const Eigen::Vector3d p = R * ps + t;
        const auto idx = pillarOf(p.x(), p.y());
        const auto zc = heightCellOf(p.z());
        if (!idx || !zc)  // NaN/inf fail the range test in quantize()
        {
            ++st.points_invalid;
            continue;
        }
        const double r2 = ps.x() * ps.x() + ps.y() * ps.y();
        if (r2 > kMinRangeForElevation * kMinRangeForElevation)
            top_slope = std::max(top_slope, ps.z() / std::sqrt(r2));
        buf_points_.push_back({packKey(*idx), *zc});
    }
    st.points_used = buf_points_.size();

    // 2) bucket by pillar, heights ascending within each pillar.
    std::sort(buf_points_.begin(), buf_points_.end(),
              [](const KeyCell& a, const KeyCell& b)
              { return a.key < b.key || (a.key == b.key && a.z < b.z); });

    // 3) per pillar: spans of this scan (Eq. 4), then update or create the global pillar.
    const double res = params_.height_resolution;
    const double beam_slope = std::tan(params_.beam_spacing_deg * M_PI / 180.0);
    const bool need_ceiling = (params_.high_height_preservation || params_.unseen_height_prior) &&
                              std::isfinite(top_slope);
    for (std::size_t b = 0; b < buf_points_.size();)
    {
        const uint64_t key = buf_points_[b].key;
        buf_cells_.clear();
        std::size_t e = b;
        for (; e < buf_points_.size() && buf_points_[e].key == key; ++e)
            buf_cells_.push_back(buf_points_[e].z);
        b = e;

        // Horizontal distance from the sensor to the pillar's centre.
        const PillarIndex idx = unpackKey(key);
        const double cx = params_.origin_x + (idx.m + 0.5) * params_.pillar_size;
        const double cy = params_.origin_y + (idx.n + 0.5) * params_.pillar_size;
        const double d = std::hypot(cx - t.x(), cy - t.y());
        const double beam_gap = d * beam_slope;  // vertical distance between beams at d
        const auto gap_cells =
            static_cast<int32_t>(std::floor(std::max(params_.merge_gap, beam_gap) / res + 1e-9));
        const auto pad_cells = static_cast<int32_t>(
            std::ceil(std::max(params_.interval_padding, 0.5 * beam_gap) / res - 1e-9));
        buildSpans(buf_cells_.data(), buf_cells_.size(), gap_cells, pad_cells, buf_spans_);

        int32_t ceiling = kAllHeights;
        if (need_ceiling)
        {
            const double top = (t.z() + d * top_slope) / res;
            if (top < static_cast<double>(kAllHeights))
                ceiling = static_cast<int32_t>(
                    std::max<double>(std::ceil(top), std::numeric_limits<int32_t>::min() + 1.0));
        }

        auto [it, inserted] = pillars_.try_emplace(key);
        if (inserted)
        {
            // A new pillar is an empty one with the prior p_empty: the general update then
            // gives its intervals Bayesfilter(p_empty_init, alpha, beta) (Eq. 14).
            it->second.logodds_empty = model_.clamp(model_.empty_init);
            ++st.pillars_created;
        }
        else
            ++st.pillars_updated;
        updatePillar(it->second, buf_spans_.data(), buf_spans_.size(), model_,
                     params_.max_intervals_per_pillar, buf_intervals_, ceiling);
    }
    return st;
}

double PillarGrid::staticProbability(double x, double y, double z) const
{
    const auto idx = pillarOf(x, y);
    const auto zc = heightCellOf(z);
    if (!idx || !zc) return params_.p_empty_init;
    const Pillar* p = findPillar(*idx);
    if (!p) return params_.p_empty_init;
    if (const Interval* iv = findInterval(*p, *zc)) return logistic(iv->logodds);
    return logistic(p->logodds_empty);
}

bool PillarGrid::isStatic(double x, double y, double z) const
{
    return staticProbability(x, y, z) >= params_.static_threshold;
}

ClassifyStats PillarGrid::classify(const PointsView& pts, std::vector<uint8_t>& is_dynamic,
                                   const Eigen::Isometry3d& T) const
{
    ClassifyStats st;
    is_dynamic.assign(pts.size, 1);
    const Eigen::Matrix3d R = T.linear();
    const Eigen::Vector3d t = T.translation();
    for (std::size_t i = 0; i < pts.size; ++i)
    {
        const Eigen::Vector3d p = R * Eigen::Vector3d(pts.x[i], pts.y[i], pts.z[i]) + t;
        if (!p.allFinite())
        {
            ++st.invalid_points;
            ++st.dynamic_points;
            continue;
        }
        const bool stat = isStatic(p.x(), p.y(), p.z());
        is_dynamic[i] = stat ? 0 : 1;
        ++(stat ? st.static_points : st.dynamic_points);
    }
    return st;
}

std::size_t PillarGrid::intervalCount() const
{
    std::size_t n = 0;
    for (const auto& kv : pillars_) n += kv.second.intervals.size();
    return n;
}

std::size_t PillarGrid::maxIntervalsInAPillar() const
{
    std::size_t n = 0;
    for (const auto& kv : pillars_) n = std::max(n, kv.second.intervals.size());
    return n;
}

const Pillar* PillarGrid::findPillar(PillarIndex idx) const
{
    const auto it = pillars_.find(packKey(idx));
    return it == pillars_.end() ? nullptr : &it->second;
}

std::vector<std::pair<PillarIndex, const Pillar*>> PillarGrid::sortedPillars() const
{
    std::vector<std::pair<PillarIndex, const Pillar*>> v;
    v.reserve(pillars_.size());
    for (const auto& kv : pillars_) v.emplace_back(unpackKey(kv.first), &kv.second);
    std::sort(v.begin(), v.end(),
              [](const auto& a, const auto& b) {
                  return a.first.m < b.first.m || (a.first.m == b.first.m && a.first.n < b.first.n);
              });
    return v;
}

void PillarGrid::setPillar(PillarIndex idx, Pillar pillar)
{
    auto bad = [&](const std::string& what)
    {
        std::ostringstream os;
        os << "hif::PillarGrid::setPillar: pillar (" << idx.m << ", " << idx.n << ") " << what;
        throw std::invalid_argument(os.str());
    };
    if (!std::isfinite(pillar.logodds_empty)) bad("has a non-finite p_empty");
    const auto& iv = pillar.intervals;
    if (iv.size() > params_.max_intervals_per_pillar)
        bad("has " + std::to_string(iv.size()) + " intervals, above max_intervals_per_pillar");
    for (std::size_t k = 0; k < iv.size(); ++k)
    {
        if (!(iv[k].lo < iv[k].hi)) bad("has an empty interval");
        if (!std::isfinite(iv[k].logodds)) bad("has a non-finite probability");
        if (k > 0 && iv[k - 1].hi > iv[k].lo) bad("has unsorted or overlapping intervals");
    }
    pillars_[packKey(idx)] = std::move(pillar);
}

bool operator==(const PillarGrid& a, const PillarGrid& b)
{
    if (a.pillars_.size() != b.pillars_.size()) return false;
    if (a.params_ != b.params_) return false;
    for (const auto& kv : a.pillars_)
    {
        const auto it = b.pillars_.find(kv.first);
        if (it == b.pillars_.end() || !(it->second == kv.second)) return false;
    }
    return true;
}

}  // namespace hif
