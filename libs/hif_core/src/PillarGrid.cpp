// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarGrid.cpp
 * @brief  The grid's settings, insertion as its steps, point queries and contents.
 */
#include "hif/PillarGrid.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "GridAccess.h"

namespace hif
{
PillarGrid::StateHolder::StateHolder() : p_(std::make_unique<State>()) {}
PillarGrid::StateHolder::~StateHolder() = default;
PillarGrid::StateHolder::StateHolder(const StateHolder& other) : p_(std::make_unique<State>())
{
    p_->pillars = other.p_->pillars;
    p_->arena = other.p_->arena;
}
PillarGrid::StateHolder& PillarGrid::StateHolder::operator=(const StateHolder& other)
{
    if (this != &other) *this = StateHolder(other);
    return *this;
}
PillarGrid::StateHolder::StateHolder(StateHolder&& other) noexcept = default;
PillarGrid::StateHolder& PillarGrid::StateHolder::operator=(StateHolder&& other) noexcept = default;

PillarGrid::PillarGrid(const GridGeometry& geometry, const Params& params)
    : geometry_(geometry), params_(params)
{
    params_.validateWith(geometry_);
    static_logodds_ = logit(params_.static_threshold);
}

bool PillarGrid::empty() const { return state_->pillars.empty(); }

std::size_t PillarGrid::pillarCount() const { return state_->pillars.size(); }

void PillarGrid::clear()
{
    state_->pillars.clear();
    setSensorModel(std::nullopt);
}

void PillarGrid::releaseScanBuffers() { state_->workspace.release(); }

void PillarGrid::setParams(const Params& params)
{
    params.validateWith(geometry_);
    params_ = params;
    static_logodds_ = logit(params_.static_threshold);
}

void PillarGrid::setThreads(std::size_t threads)
{
    if (threads == 0)
        throw std::invalid_argument("hif::PillarGrid::setThreads: the thread count must be >= 1");
    threads_ = threads;
    state_->arena = threads > 1 ? std::make_shared<detail::ThreadArena>(threads) : nullptr;
}

void PillarGrid::setSensorModel(std::optional<SensorModel> model)
{
    if (model) model->validate();
    useSensorModel(std::move(model));
    scans_since_check_ = kSensorCheckInterval - 1;  // given: the next scan is checked
    settle_scans_left_ = 0;
}

void PillarGrid::useSensorModel(std::optional<SensorModel> model)
{
    sensor_ = std::move(model);
    layout_ = RangeImageLayout::forSensor(sensor_);
    beam_tangents_ = sensor_ ? sensor_->beamTangents() : std::vector<double>{};
    next_beam_rows_ = detail::nextBeamRowsTable(layout_, beam_tangents_);
}

double PillarGrid::pEmptyInit() const
{
    constexpr double kNeutral = 0.5;  // no evidence either way
    if (sensor_ && !sensor_->hasRings()) return std::max(params_.p_empty_init, kNeutral);
    return params_.p_empty_init;
}

double PillarGrid::beamGapSlope(double tan_el) const
{
    if (params_.beam_spacing_deg <= 0.0) return 0.0;
    if (sensor_) return sensor_->beamGapSlope(beam_tangents_, tan_el);
    return std::tan(params_.beam_spacing_deg * M_PI / 180.0);
}

InsertStats PillarGrid::insertScan(const PointsView& pts, const Eigen::Isometry3d& T)
{
    bool estimated = false, checked = false;
    std::optional<std::string> contradiction;
    // The model estimated from this scan (validated) is the one used from here on: the next
    // check in kSensorCheckInterval scans.
    auto adopt = [&](std::optional<SensorModel> m)
    {
        useSensorModel(std::move(m));
        scans_since_check_ = 0;
        estimated_from_points_ = pts.size;
        estimated = true;
    };
    if (params_.sensor_from_scans)
    {
        if (!sensor_)
        {
            if (auto m = SensorModel::estimate(pts))
            {
                adopt(std::move(m));
                settle_scans_left_ = kSensorSettleScans;
            }
        }
        else if (settle_scans_left_ > 0)
        {
            // Estimated again only from a scan with more points (by a tenth) than the one the
            // model came from: part of a sweep has fewer than the whole; two whole sweeps
            // differ by less, and an estimate costs about as much as an insertion.
            --settle_scans_left_;
            if (pts.size > estimated_from_points_ + estimated_from_points_ / 10)
            {
                auto m = SensorModel::estimate(pts);
                if (m && sensor_->seesLessThan(*m)) adopt(std::move(m));
            }
        }
        else if (++scans_since_check_ >= kSensorCheckInterval)
        {
            scans_since_check_ = 0;
            if (auto m = SensorModel::estimate(pts))
            {
                checked = true;
                contradiction = sensor_->contradiction(*m);
            }
        }
    }
    detail::ScanBuckets& scan = state_->workspace.scan;
    detail::bucketPoints(*this, pts, T, scan);
    detail::buildSpans(*this, scan);
    if (detail::needsScanImage(params_)) detail::buildScanImage(*this, pts);
    InsertStats st = detail::updatePillars(*this, scan);
    st.sensor_estimated = estimated;
    st.sensor_checked = checked;
    if (contradiction) st.sensor_contradiction = *contradiction;
    if (params_.see_through_range > 0.0) detail::seeThroughMisses(*this, T, scan);
    return st;
}

double PillarGrid::logOddsAt(double x, double y, double z) const
{
    const auto idx = geometry_.pillarOf(x, y);
    const auto zc = geometry_.heightCellOf(z);
    const Pillar* p = idx && zc ? findPillar(*idx) : nullptr;
    if (!p) return logit(pEmptyInit());
    if (const Interval* iv = findInterval(*p, *zc)) return iv->logodds;
    return p->logodds_empty;
}

double PillarGrid::staticProbability(double x, double y, double z) const
{
    const auto idx = geometry_.pillarOf(x, y);
    const auto zc = geometry_.heightCellOf(z);
    if (!idx || !zc) return pEmptyInit();
    const Pillar* p = findPillar(*idx);
    if (!p) return pEmptyInit();
    if (const Interval* iv = findInterval(*p, *zc)) return logistic(iv->logodds);
    return logistic(p->logodds_empty);
}

bool PillarGrid::isStatic(double x, double y, double z) const
{
    return isStaticLogOdds(logOddsAt(x, y, z));
}

std::size_t PillarGrid::intervalCount() const
{
    std::size_t n = 0;
    for (const auto& kv : state_->pillars) n += kv.second.intervals.size();
    return n;
}

std::size_t PillarGrid::staticIntervalCount() const
{
    std::size_t n = 0;
    for (const auto& kv : state_->pillars)
        for (const Interval& iv : kv.second.intervals) n += isStaticLogOdds(iv.logodds);
    return n;
}

std::size_t PillarGrid::maxIntervalsInAPillar() const
{
    std::size_t n = 0;
    for (const auto& kv : state_->pillars) n = std::max(n, kv.second.intervals.size());
    return n;
}

std::size_t PillarGrid::memoryBytes() const
{
    // absl's flat table: one slot and one control byte per bucket (plus a group of control
    // bytes); the intervals live in each pillar's own vector.
    std::size_t bytes =
        state_->pillars.capacity() * (sizeof(std::pair<const uint64_t, Pillar>) + 1) + 16;
    for (const auto& kv : state_->pillars)
        bytes += kv.second.intervals.capacity() * sizeof(Interval);
    return bytes;
}

const Pillar* PillarGrid::findPillar(PillarIndex idx) const
{
    const auto it = state_->pillars.find(packKey(idx));
    return it == state_->pillars.end() ? nullptr : &it->second;
}

std::vector<std::pair<PillarIndex, const Pillar*>> PillarGrid::sortedPillars() const
{
    std::vector<std::pair<PillarIndex, const Pillar*>> v;
    v.reserve(state_->pillars.size());
    for (const auto& kv : state_->pillars) v.emplace_back(unpackKey(kv.first), &kv.second);
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
    state_->pillars[packKey(idx)] = std::move(pillar);
}

bool operator==(const PillarGrid& a, const PillarGrid& b)
{
    if (a.state_->pillars.size() != b.state_->pillars.size()) return false;
    if (a.geometry_ != b.geometry_ || a.params_ != b.params_ || a.sensor_ != b.sensor_)
        return false;
    for (const auto& kv : a.state_->pillars)
    {
        const auto it = b.state_->pillars.find(kv.first);
        if (it == b.state_->pillars.end() || !(it->second == kv.second)) return false;
    }
    return true;
}

}  // namespace hif
