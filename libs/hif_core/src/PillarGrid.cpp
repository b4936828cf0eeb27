// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarGrid.cpp
 * @brief  Scan integration into the global pillar dictionary, and point queries.
 */
#include "hif/PillarGrid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hif
{
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

    // 1) transform, quantize (Eq. 1) and key every point.
    buf_points_.clear();
    buf_points_.reserve(pts.size);
    for (std::size_t i = 0; i < pts.size; ++i)
    {
        const Eigen::Vector3d p = R * Eigen::Vector3d(pts.x[i], pts.y[i], pts.z[i]) + t;
        const auto idx = pillarOf(p.x(), p.y());
        const auto zc = heightCellOf(p.z());
        if (!idx || !zc)  // NaN/inf fail the range test in quantize()
        {
            ++st.points_invalid;
            continue;
        }
        buf_points_.push_back({packKey(*idx), *zc});
    }
    st.points_used = buf_points_.size();

    // 2) bucket by pillar, heights ascending within each pillar.
    std::sort(buf_points_.begin(), buf_points_.end(),
              [](const KeyCell& a, const KeyCell& b)
              { return a.key < b.key || (a.key == b.key && a.z < b.z); });

    // 3) per pillar: spans of this scan (Eq. 4), then update or create the global pillar.
    const auto gap_cells =
        static_cast<int32_t>(std::floor(params_.merge_gap / params_.height_resolution + 1e-9));
    const auto pad_cells = static_cast<int32_t>(
        std::ceil(params_.interval_padding / params_.height_resolution - 1e-9));
    for (std::size_t b = 0; b < buf_points_.size();)
    {
        const uint64_t key = buf_points_[b].key;
        buf_cells_.clear();
        std::size_t e = b;
        for (; e < buf_points_.size() && buf_points_[e].key == key; ++e)
            buf_cells_.push_back(buf_points_[e].z);
        b = e;
        buildSpans(buf_cells_.data(), buf_cells_.size(), gap_cells, pad_cells, buf_spans_);

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
                     params_.max_intervals_per_pillar, buf_intervals_);
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
