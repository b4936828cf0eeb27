// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   BucketPoints.cpp
 * @brief  Step 1 of an insertion: a scan's points quantized and grouped by pillar.
 */
#include <algorithm>
#include <array>
#include <cmath>

#include "GridAccess.h"
#include "QuantizePass.h"

namespace hif::detail
{
namespace
{
/** The pillars beside a point's edges, for its edge code (EdgeBits): offsets (dm, dn), at most
 *  three (two edges and the corner between them). */
struct Beside
{
    int count = 0;
    int dm[3] = {}, dn[3] = {};
};
constexpr Beside besideOf(int32_t code)
{
    Beside b;
    const int dm = (code & kEdgeLowM) ? -1 : (code & kEdgeHighM) ? 1 : 0;
    const int dn = (code & kEdgeLowN) ? -1 : (code & kEdgeHighN) ? 1 : 0;
    if (dm != 0) b.dm[b.count++] = dm;
    if (dn != 0) b.dn[b.count++] = dn;
    if (dm != 0 && dn != 0)
    {
        b.dm[b.count] = dm;
        b.dn[b.count++] = dn;
    }
    return b;
}
constexpr std::array<Beside, 16> kBeside = {besideOf(0),  besideOf(1),  besideOf(2),  besideOf(3),
                                            besideOf(4),  besideOf(5),  besideOf(6),  besideOf(7),
                                            besideOf(8),  besideOf(9),  besideOf(10), besideOf(11),
                                            besideOf(12), besideOf(13), besideOf(14), besideOf(15)};

/** The edge cells of `out` (ScanBuckets::edge_offsets, edge_cells) from its first v points
 *  and their edge codes: each point near an edge gives its height cell to the pillar beside
 *  it, when the scan hit that pillar (`pillarBeside(k, b, s)`: the index of the pillar at
 *  offset s of Beside b from point k's, or kNone). Gathered in one pass, then placed. */
template <typename PillarBeside>
void bucketEdges(ScanBuckets& out, std::size_t v, PillarBeside&& pillarBeside)
{
    constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
    const std::size_t np = out.pillarCount();
    std::vector<uint32_t>& offsets = out.edge_offsets;
    offsets.assign(np + 1, 0);
    auto& pairs = out.tmp_edge_pairs;
    pairs.clear();
    for (std::size_t k = 0; k < v; ++k)
    {
        const int32_t code = out.tmp_edge[k] & kEdgeBits;
        if (code == 0) continue;
        const Beside& b = kBeside[static_cast<std::size_t>(code)];
        for (int s = 0; s < b.count; ++s)
        {
            const uint32_t p = pillarBeside(k, code, s);
            if (p == kNone) continue;
            ++offsets[p + 1];
            pairs.emplace_back(p, out.tmp_z[k]);
        }
    }
    for (std::size_t p = 0; p < np; ++p) offsets[p + 1] += offsets[p];
    std::vector<uint32_t>& next = out.tmp_counts;
    next.assign(offsets.begin(), offsets.end() - 1);
    out.edge_cells.resize(pairs.size());
    for (const auto& [p, z] : pairs) out.edge_cells[next[p]++] = z;
}
/** ScanBuckets::object_at from the entries' codes (tmp_code, in entry order): the places of
 *  the entries more than Params::ground_max_step above the pillar's lowest. */
void objectSightings(const PillarGrid& grid, ScanBuckets& out)
{
    const auto step = static_cast<int64_t>(
        std::floor(grid.params().ground_max_step / grid.geometry().height_resolution + 1e-9));
    const std::size_t np = out.pillarCount();
    out.object_at.assign(np, {});
    for (std::size_t p = 0; p < np; ++p)
    {
        const uint32_t b = out.offsets[p], e = out.offsets[p + 1];
        int32_t low = out.cells[b];
        for (uint32_t k = b + 1; k < e; ++k) low = std::min(low, out.cells[k]);
        ScanBuckets::ObjectSightings& o = out.object_at[p];
        for (uint32_t k = b; k < e; ++k)
        {
            if (int64_t{out.cells[k]} - low <= step) continue;
            const auto code = static_cast<uint32_t>(out.tmp_code[k]);
            o.sum_u += static_cast<float>(Pillar::placeOf((code >> kPlaceShift) & 255u));
            o.sum_v += static_cast<float>(Pillar::placeOf((code >> (kPlaceShift + 8)) & 255u));
            ++o.count;
        }
    }
}
}  // namespace

void bucketPoints(const PillarGrid& grid, const PointsView& pts, const Eigen::Isometry3d& T,
                  ScanBuckets& out, bool keep_index)
{
    out.sensor = T.translation();
    out.world_to_sensor = T.linear().transpose();
    out.top_slope_sq = -std::numeric_limits<double>::infinity();
    out.tmp_m.resize(pts.size);
    out.tmp_n.resize(pts.size);
    out.tmp_z.resize(pts.size);
    // Each point's edge code (EdgeBits): with the gate, for its place in its pillar (where what
    // stands above the ground was seen, ScanBuckets::object_at); with Params::pillar_edge_margin,
    // for the edge cells too.
    const Params& prm = grid.params();
    const bool codes = !keep_index && prm.miss_needs_beam;
    const bool edges = codes && prm.pillar_edge_margin > 0.0;
    if (codes) out.tmp_edge.resize(pts.size);
    out.object_at.clear();
    out.edge_offsets.clear();
    out.edge_cells.clear();
    if (keep_index)
    {
        out.tmp_src.resize(pts.size);
        out.repeats.assign(pts.size, 0);
    }

    // Pass 1: transform, quantize (Eq. 1; as quantize(), without std::optional) and keep the
    // valid points that are not repeats, with the bounding box of their pillars and the top
    // beam's elevation. In fixed chunks (whatever the thread count, so the result is the
    // same; a chunk's first point is never a repeat), each compacted in place, then moved
    // together.
    constexpr std::size_t kChunk = 16384;
    const ChunkOutput chunk_out{out.tmp_m.data(),
                                out.tmp_n.data(),
                                out.tmp_z.data(),
                                keep_index ? out.tmp_src.data() : nullptr,
                                keep_index ? out.repeats.data() : nullptr,
                                codes ? out.tmp_edge.data() : nullptr,
                                edges ? prm.pillar_edge_margin / grid.geometry().pillar_size : 0.0};
    const std::size_t n_chunks = (pts.size + kChunk - 1) / kChunk;
    std::array<ChunkSummary, 64> small_chunks;  // up to 1M points without allocation
    std::vector<ChunkSummary> big_chunks(n_chunks > small_chunks.size() ? n_chunks : 0);
    ChunkSummary* chunks = big_chunks.empty() ? small_chunks.data() : big_chunks.data();
    forRanges(GridAccess::arena(grid), n_chunks, 1,
              [&](std::size_t c0, std::size_t c1)
              {
                  for (std::size_t c = c0; c < c1; ++c)
                  {
                      const std::size_t i0 = c * kChunk, i1 = std::min(pts.size, i0 + kChunk);
                      chunks[c] = quantizeChunk(T, grid.geometry(), grid.params().min_range, pts,
                                                i0, i1, chunk_out);
                  }
              });
    int32_t m_min = std::numeric_limits<int32_t>::max(),
            m_max = std::numeric_limits<int32_t>::min();
    int32_t n_min = m_min, n_max = m_max;
    std::size_t v = 0, valid = 0, near = 0;
    for (std::size_t c = 0; c < n_chunks; ++c)
    {
        const ChunkSummary& ch = chunks[c];
        const std::size_t from = c * kChunk;
        if (from != v && ch.kept > 0)  // close the gap left by invalid points and repeats
        {
            std::copy_n(out.tmp_m.begin() + from, ch.kept, out.tmp_m.begin() + v);
            std::copy_n(out.tmp_n.begin() + from, ch.kept, out.tmp_n.begin() + v);
            std::copy_n(out.tmp_z.begin() + from, ch.kept, out.tmp_z.begin() + v);
            if (keep_index)
                std::copy_n(out.tmp_src.begin() + from, ch.kept, out.tmp_src.begin() + v);
            if (codes) std::copy_n(out.tmp_edge.begin() + from, ch.kept, out.tmp_edge.begin() + v);
        }
        v += ch.kept;
        valid += ch.valid;
        near += ch.near;
        m_min = std::min(m_min, ch.m_min);
        m_max = std::max(m_max, ch.m_max);
        n_min = std::min(n_min, ch.n_min);
        n_max = std::max(n_max, ch.n_max);
        out.top_slope_sq = std::max(out.top_slope_sq, ch.top_slope_sq);
    }
    out.points_valid = valid;
    out.points_near = near;
    out.points_invalid = pts.size - valid - near;
    out.points_outside_grid = 0;
    if (out.points_invalid > 0)
    {
        // Rare (no point of a normal scan is invalid): which of them are finite, so outside
        // the grid rather than not numbers.
        std::size_t finite = 0;
        for (std::size_t i = 0; i < pts.size; ++i)
            finite += std::isfinite(pts.x[i]) && std::isfinite(pts.y[i]) && std::isfinite(pts.z[i]);
        out.points_outside_grid = finite - valid - near;
    }
    out.keys.clear();
    out.offsets.clear();
    out.cells.resize(v);
    out.index.resize(keep_index ? v : 0);
    out.tmp_code.resize(codes ? v : 0);
    if (v == 0)
    {
        out.offsets.push_back(0);
        return;
    }

    // Pass 2: group by pillar. Counting sort over the scan's bounding box of pillars when it
    // is small (always, for a LiDAR scan at 1 m pillars); else a comparison sort.
    // With edges, one more pillar on each side, so that the pillars beside every point's
    // have bins too.
    const int64_t g = edges ? 1 : 0;
    const int64_t m0 = int64_t{m_min} - g, n0 = int64_t{n_min} - g;
    const int64_t width = int64_t{m_max} - m0 + 1 + g, height = int64_t{n_max} - n0 + 1 + g;
    constexpr int64_t kMaxBins = int64_t{1} << 22;
    if (width * height <= kMaxBins)
    {
        const auto bins = static_cast<std::size_t>(width * height);
        auto& bin = out.tmp_bin;
        bin.resize(v);
        // counts[b], then after the prefix sum the next free slot of bin b; the non-empty
        // bins give the pillars and their offsets in the same pass.
        std::vector<uint32_t>& counts = out.tmp_counts;
        counts.assign(bins, 0);
        for (std::size_t k = 0; k < v; ++k)
        {
            const auto b = static_cast<uint32_t>((int64_t{out.tmp_m[k]} - m0) * height +
                                                 (int64_t{out.tmp_n[k]} - n0));
            bin[k] = b;
            ++counts[b];
        }
        uint32_t sum = 0;
        for (std::size_t b = 0; b < bins; ++b)
        {
            const uint32_t c = counts[b];
            if (c == 0) continue;
            counts[b] = sum;
            out.keys.push_back(
                packKey({static_cast<int32_t>(m0 + static_cast<int64_t>(b) / height),
                         static_cast<int32_t>(n0 + static_cast<int64_t>(b) % height)}));
            out.offsets.push_back(sum);
            sum += c;
        }
        out.offsets.push_back(sum);
        for (std::size_t k = 0; k < v; ++k)
        {
            const uint32_t slot = counts[bin[k]]++;
            out.cells[slot] = out.tmp_z[k];
            if (keep_index) out.index[slot] = out.tmp_src[k];
            if (codes) out.tmp_code[slot] = out.tmp_edge[k];
        }
        if (edges)
        {
            // Each bin's pillar index (none: kNone), for the pillars beside the points.
            std::vector<uint32_t>& pillar_of = out.tmp_pillar;
            pillar_of.assign(bins, std::numeric_limits<uint32_t>::max());
            for (std::size_t p = 0; p < out.keys.size(); ++p)
            {
                const PillarIndex idx = unpackKey(out.keys[p]);
                pillar_of[static_cast<std::size_t>((int64_t{idx.m} - m0) * height +
                                                   (int64_t{idx.n} - n0))] =
                    static_cast<uint32_t>(p);
            }
            // The bin offsets of the pillars beside, per edge code.
            std::array<std::array<int64_t, 3>, 16> delta{};
            for (std::size_t c = 0; c < 16; ++c)
                for (int i = 0; i < kBeside[c].count; ++i)
                    delta[c][static_cast<std::size_t>(i)] =
                        kBeside[c].dm[i] * height + kBeside[c].dn[i];
            bucketEdges(
                out, v,
                [&](std::size_t k, int32_t code, int i)
                {
                    return pillar_of[static_cast<std::size_t>(
                        bin[k] +
                        delta[static_cast<std::size_t>(code)][static_cast<std::size_t>(i)])];
                });
        }
    }
    else
    {
        auto& order = out.tmp_bin;
        order.resize(v);
        for (std::size_t k = 0; k < v; ++k) order[k] = static_cast<uint32_t>(k);
        auto keyOf = [&](uint32_t k) { return packKey({out.tmp_m[k], out.tmp_n[k]}); };
        std::sort(order.begin(), order.end(),
                  [&](uint32_t a, uint32_t b) { return keyOf(a) < keyOf(b); });
        for (std::size_t k = 0; k < v; ++k)
        {
            const uint32_t src = order[k];
            const uint64_t key = keyOf(src);
            if (out.keys.empty() || out.keys.back() != key)
            {
                out.keys.push_back(key);
                out.offsets.push_back(static_cast<uint32_t>(k));
            }
            out.cells[k] = out.tmp_z[src];
            if (keep_index) out.index[k] = out.tmp_src[src];
            if (codes) out.tmp_code[k] = out.tmp_edge[src];
        }
        out.offsets.push_back(static_cast<uint32_t>(v));
        if (edges)
            bucketEdges(out, v,
                        [&](std::size_t k, int32_t code, int i)
                        {
                            const Beside& b = kBeside[static_cast<std::size_t>(code)];
                            const int64_t m = int64_t{out.tmp_m[k]} + b.dm[i];
                            const int64_t n = int64_t{out.tmp_n[k]} + b.dn[i];
                            if (m < m_min || m > m_max || n < n_min || n > n_max)
                                return std::numeric_limits<uint32_t>::max();
                            const uint64_t key =
                                packKey({static_cast<int32_t>(m), static_cast<int32_t>(n)});
                            const auto it = std::lower_bound(out.keys.begin(), out.keys.end(), key);
                            return it != out.keys.end() && *it == key
                                       ? static_cast<uint32_t>(it - out.keys.begin())
                                       : std::numeric_limits<uint32_t>::max();
                        });
    }
    if (codes) objectSightings(grid, out);
}

}  // namespace hif::detail
