// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   UpdatePillars.cpp
 * @brief  Step 3 of an insertion: the Bayes update of every pillar the scan hit (Eq. 8-18), or
 *         its creation.
 */
#include <algorithm>
#include <cmath>

#include "GridAccess.h"
#include "RangeImage.h"

namespace hif::detail
{
namespace
{
/** Adds a scan's sightings of what stands above pillar `pil`'s ground (ScanBuckets::
 *  object_at) to its mean place (Pillar::object_u, object_v), over the last
 *  Pillar::kObjectSightings sightings at most: the mean follows what stands there now. */
void addObjectSightings(Pillar& pil, const ScanBuckets::ObjectSightings& s)
{
    if (s.count == 0) return;
    const double w = pil.object_weight, n = s.count;
    const double mu = (Pillar::placeOf(pil.object_u) * w + s.sum_u) / (w + n);
    const double mv = (Pillar::placeOf(pil.object_v) * w + s.sum_v) / (w + n);
    pil.object_u = static_cast<uint8_t>(std::clamp(std::floor(mu * 256.0), 0.0, 255.0));
    pil.object_v = static_cast<uint8_t>(std::clamp(std::floor(mv * 256.0), 0.0, 255.0));
    pil.object_weight = static_cast<uint16_t>(std::min<double>(w + n, Pillar::kObjectSightings));
}
}  // namespace

InsertStats updatePillars(PillarGrid& grid, const ScanBuckets& scan)
{
    PillarTable& pillars = GridAccess::pillars(grid);
    Workspace& ws = GridAccess::workspace(grid);
    std::vector<Pillar*>& targets = ws.targets;
    const LogOddsModel model = LogOddsModel::of(grid);
    const std::size_t cap = grid.params().max_intervals_per_pillar;
    ws.updater.reset(model, cap);

    // Params::miss_needs_beam: each pillar's gate looks along its axis in the scan's image.
    const bool gated = grid.params().miss_needs_beam;
    const GridGeometry& geo = grid.geometry();
    const Eigen::Vector3d up = scan.world_to_sensor.col(2);  // world z axis, sensor frame
    // A return beyond the pillar's footprint (half its diagonal from its axis) passed through.
    const double margin = 0.5 * std::sqrt(2.0) * geo.pillar_size;
    // The centre's column and one on each side: columns are half a horizontal step
    // (RangeImageLayout::forSensor), so these hold the beam nearest the pillar's centre.
    constexpr int kHalfCols = 1;
    const double bridge = neighbourBeamsTan(grid);
    const float seen_once = seenOnce(grid);
    const bool surfaces_into = grid.sensorModel() && !grid.sensorModel()->hasRings();
    // Ground seen once: the runs down each column, found once per scan (a new generation).
    if (gated && model.ground_slope_tan > 0.0)
    {
        const std::size_t cells = grid.imageLayout().cells();
        if (ws.ground_runs_cells != cells)
        {
            ws.ground_runs.reset(new std::atomic<uint8_t>[cells]());
            ws.ground_runs_cells = cells;
            ws.ground_generation = 0;
        }
        if (++ws.ground_generation == 1u << 6)  // the generation's 6 bits wrap: start afresh
        {
            for (std::size_t c = 0; c < cells; ++c)
                ws.ground_runs[c].store(0, std::memory_order_relaxed);
            ws.ground_generation = 1;
        }
    }
    // What stands above a pillar's ground is judged by the beams toward where it was seen
    // in the pillar (Pillar::object_u, object_v: before this scan's sightings).
    auto gateOf = [&](std::size_t p, const Pillar& pil)
    {
        const PillarIndex idx = unpackKey(scan.keys[p]);
        const Eigen::Vector3d axis(geo.centreX(idx.m) - scan.sensor.x(),
                                   geo.centreY(idx.n) - scan.sensor.y(), -scan.sensor.z());
        BeamGate gate{&grid.imageLayout(),
                      ws.range_image.data(),
                      scan.world_to_sensor * axis,
                      up,
                      margin,
                      geo.height_resolution,
                      kHalfCols,
                      pillarReach(geo.pillar_size, axis.x(), axis.y()),
                      bridge,
                      &grid,
                      scan.sensor.z(),
                      seen_once,
                      ws.returned_blocks.data()};
        gate.runs = ws.ground_runs.get();
        gate.generation = ws.ground_generation;
        gate.farthest_return = ws.farthest_return;
        gate.next_beam_rows = GridAccess::nextBeamRows(grid);
        gate.edge_spans = scan.edgeSpansOf(p, gate.edge_count);
        gate.surfaces_into = surfaces_into;
        gate.setObjectAxis(geo, idx, pil, scan.sensor, scan.world_to_sensor);
        return gate;
    };

    InsertStats st;
    st.points_used = scan.points_valid;
    st.points_invalid = scan.points_invalid;
    st.points_outside_grid = scan.points_outside_grid;
    st.points_near = scan.points_near;
    const std::size_t np = scan.pillarCount();

    // Pillars already in the map are found and updated in parallel (finds are read-only and
    // pillars independent); the new ones are then created and updated in scan order.
    targets.resize(np);
    // A software pipeline, as the table and the intervals are far bigger than the cache: the
    // slot of pillar p + 2D is prefetched, pillar p + D is found and its intervals prefetched,
    // pillar p is updated.
    constexpr std::size_t kAhead = 8;  // D
    auto updateExisting = [&](std::size_t p0, std::size_t p1, PillarUpdater& updater)
    {
        auto find = [&](std::size_t p)
        {
            const auto it = pillars.find(scan.keys[p]);
            targets[p] = it == pillars.end() ? nullptr : &it->second;
            if (targets[p]) __builtin_prefetch(targets[p]->intervals.data());
        };
        for (std::size_t p = p0; p < std::min(p1, p0 + 2 * kAhead); ++p)
            pillars.prefetch(scan.keys[p]);
        for (std::size_t p = p0; p < std::min(p1, p0 + kAhead); ++p) find(p);
        for (std::size_t p = p0; p < p1; ++p)
        {
            if (p + 2 * kAhead < p1) pillars.prefetch(scan.keys[p + 2 * kAhead]);
            if (p + kAhead < p1) find(p + kAhead);
            if (!targets[p]) continue;
            Pillar& pil = *targets[p];
            const BeamGate gate = gated ? gateOf(p, pil) : BeamGate{};
            updater.update(pil, scan.spans.data() + scan.offsets[p], scan.span_counts[p],
                           scan.ceilings[p], gated ? &gate : nullptr);
            if (gated) addObjectSightings(pil, scan.object_at[p]);
        }
    };
    ThreadArena* arena = GridAccess::arena(grid);
    if (!arena)
        updateExisting(0, np, ws.updater);
    else
        forRanges(arena, np, 256,
                  [&](std::size_t p0, std::size_t p1)
                  {
                      PillarUpdater updater(model, cap);
                      updateExisting(p0, p1, updater);
                  });
    for (std::size_t p = 0; p < np; ++p)
    {
        if (targets[p]) continue;
        // A new pillar is an empty one with the prior p_empty: the general update then gives
        // its intervals Bayesfilter(p_empty_init, alpha, beta) (Eq. 14).
        Pillar& pil = pillars[scan.keys[p]];
        pil.logodds_empty = model.clamp(model.empty_init);
        ++st.pillars_created;
        const BeamGate gate = gated ? gateOf(p, pil) : BeamGate{};
        ws.updater.update(pil, scan.spans.data() + scan.offsets[p], scan.span_counts[p],
                          scan.ceilings[p], gated ? &gate : nullptr);
        if (gated) addObjectSightings(pil, scan.object_at[p]);
    }
    st.pillars_updated = np - st.pillars_created;
    return st;
}

}  // namespace hif::detail
