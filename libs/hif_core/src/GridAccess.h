// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   GridAccess.h
 * @brief  What the insertion steps (detail/InsertSteps.h) reach inside a PillarGrid: its
 *         table of pillars, its threads and its reusable buffers.
 */
#pragma once

#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include <absl/container/flat_hash_map.h>
#include "Parallel.h"
#include "RangeImage.h"

#include "hif/PillarGrid.h"
#include "hif/detail/InsertSteps.h"

namespace hif::detail
{
using PillarTable = absl::flat_hash_map<uint64_t, Pillar, PackedKeyHash>;

/** Per-scan buffers of a grid, kept between insertions so that steady state allocates
 *  nothing. */
struct Workspace
{
    ScanBuckets scan;
    std::vector<Pillar*> targets;              ///< per scan pillar: its map pillar, or null
    PillarUpdater updater{LogOddsModel(), 1};  ///< reset at every insertion
    std::vector<BeamReturn> range_image;       ///< the scan's returns (miss gates)
    std::vector<uint8_t> returned_blocks;      ///< of range_image (buildReturnImage())
    float farthest_return = 0.0f;              ///< of range_image: its farthest return, metres
    /** Online with the free-space test: FreeSpaceTest::pointsFingerprint() of the scan whose
     *  returns range_image holds, and its layout, so that the test takes its image from the
     *  insertion (FreeSpaceTest::add(points, T, grid)); 0 and an empty layout otherwise. */
    uint64_t range_image_points = 0;
    RangeImageLayout range_image_layout{0, 0};
    std::vector<uint8_t> hit;  ///< see-through misses: pillars the scan hit
    /** BeamGate::runs of the scan's image (ground seen once), and the scan's generation. */
    std::unique_ptr<std::atomic<uint8_t>[]> ground_runs;
    std::size_t ground_runs_cells = 0;
    uint8_t ground_generation = 0;

    /** Scan buffers of classify() (const, and may run concurrently): each call takes one, or
     *  a new one, and gives it back; they are freed with the grid. */
    class ClassifyBuffers
    {
    public:
        /** A buffer for one call, given back when it goes. */
        struct Lease
        {
            ClassifyBuffers* owner;
            std::unique_ptr<ScanBuckets> buffer;
            Lease(const Lease&) = delete;
            Lease& operator=(const Lease&) = delete;
            ~Lease()
            {
                const std::lock_guard<std::mutex> lock(owner->mutex_);
                owner->free_.push_back(std::move(buffer));
            }
        };
        [[nodiscard]] Lease take()
        {
            std::unique_ptr<ScanBuckets> buffer;
            {
                const std::lock_guard<std::mutex> lock(mutex_);
                if (!free_.empty())
                {
                    buffer = std::move(free_.back());
                    free_.pop_back();
                }
            }
            if (!buffer) buffer = std::make_unique<ScanBuckets>();
            return Lease{this, std::move(buffer)};
        }

        /** Frees the buffers not lent out. */
        void release()
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            free_.clear();
        }

    private:
        std::mutex mutex_;
        std::vector<std::unique_ptr<ScanBuckets>> free_;
    };
    ClassifyBuffers classify_buffers;

    /** Frees every buffer (PillarGrid::releaseScanBuffers()). */
    void release()
    {
        scan = {};
        targets = {};
        updater = PillarUpdater{LogOddsModel(), 1};
        range_image = {};
        returned_blocks = {};
        range_image_points = 0;
        range_image_layout = {0, 0};
        hit = {};
        ground_runs.reset();
        ground_runs_cells = 0;
        ground_generation = 0;
        classify_buffers.release();
    }
};

}  // namespace hif::detail

namespace hif
{
struct PillarGrid::State
{
    detail::PillarTable pillars;
    std::shared_ptr<detail::ThreadArena> arena;  ///< null on one thread; shared by copies
    /** Not part of the map: a copy starts with empty buffers of its own. */
    detail::Workspace workspace;
};
}  // namespace hif

namespace hif::detail
{
struct GridAccess
{
    static PillarTable& pillars(PillarGrid& g) { return g.state_->pillars; }
    static const PillarTable& pillars(const PillarGrid& g) { return g.state_->pillars; }
    /** Null when the grid runs on one thread. */
    static ThreadArena* arena(const PillarGrid& g) { return g.state_->arena.get(); }
    /** The grid's buffers (classify(), which is const, takes its own from them). */
    static Workspace& workspace(const PillarGrid& g) { return g.state_->workspace; }
    /** tan() of the sensor model's beam elevations, ascending (SensorModel::beamTangents(),
     *  kept with the model); empty without rings. */
    static const std::vector<double>& beamTangents(const PillarGrid& g) { return g.beam_tangents_; }
    /** nextBeamRowsTable() of the grid's image layout and beams, kept with the model; null
     *  without rings. */
    static const uint16_t* nextBeamRows(const PillarGrid& g)
    {
        return g.beam_tangents_.size() < 2 ? nullptr : g.next_beam_rows_.data();
    }
};

}  // namespace hif::detail
