// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   QuantizePass.cpp
 * @brief  Pass 1 of bucketPoints(), scalar and AVX.
 */
#include "QuantizePass.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "Simd.h"
#include "hif/detail/Cpu.h"

namespace hif::detail
{
namespace
{
// Points closer than this (horizontally) to the sensor are ignored when measuring the top
// beam's elevation: there, range noise makes z / range unreliable.
constexpr double kMinRangeForElevation = 2.0;

/** The running state of pass 1 over one chunk: extremes of the valid points before floor()
 *  (which is monotone), counts, and the last point for the repeat test. */
struct PassState
{
    double m_lo = std::numeric_limits<double>::infinity();
    double m_hi = -std::numeric_limits<double>::infinity();
    double n_lo = std::numeric_limits<double>::infinity();
    double n_hi = -std::numeric_limits<double>::infinity();
    double top = -std::numeric_limits<double>::infinity();  ///< largest z |z| / r^2
    std::size_t v = 0;                                      ///< next output slot
    std::size_t valid = 0;
    std::size_t near = 0;    ///< finite points nearer the sensor than the minimum range
    bool have_prev = false;  ///< the input point before the next one is valid
    int32_t prev_m = 0, prev_n = 0, prev_z = 0;
};

#if HIF_X86_AVX
/** For each 4-bit mask of kept lanes, the pshufb control that moves those 32-bit lanes to the
 *  front, in order. */
struct CompactTable
{
    alignas(16) uint8_t shuffle[16][16];
    CompactTable() : shuffle()
    {
        for (unsigned mask = 0; mask < 16; ++mask)
        {
            unsigned out = 0;
            for (unsigned lane = 0; lane < 4; ++lane)
                if (mask & (1u << lane))
                {
                    for (unsigned b = 0; b < 4; ++b)
                        shuffle[mask][4 * out + b] = static_cast<uint8_t>(4 * lane + b);
                    ++out;
                }
            for (unsigned b = 4 * out; b < 16; ++b) shuffle[mask][b] = 0x80;  // zero
        }
    }
};
#endif

/** quantizeChunk() for one transform and grid (see QuantizePass.h). */
struct QuantizeChunk
{
    double r00, r01, r02, r10, r11, r12, r20, r21, r22;
    double tx, ty, tz;
    double ox, oy, inv_xy, inv_z;
    double min_range2;  ///< squared minimum range (0: none)
    /** Edge codes: a point whose offset in its pillar (a fraction of the pillar's size) is
     *  below edge_lo or above edge_hi along an axis lies near that edge. */
    double edge_lo, edge_hi;
    /** Whether there is an edge margin: without one, a point's edge bits are all 0. */
    bool edge_bits_on;

    QuantizeChunk(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const GridGeometry& p,
                  double min_range, double edge_fraction)
        : r00(R(0, 0)),
          r01(R(0, 1)),
          r02(R(0, 2)),
          r10(R(1, 0)),
          r11(R(1, 1)),
          r12(R(1, 2)),
          r20(R(2, 0)),
          r21(R(2, 1)),
          r22(R(2, 2)),
          tx(t.x()),
          ty(t.y()),
          tz(t.z()),
          ox(p.origin_x),
          oy(p.origin_y),
          inv_xy(1.0 / p.pillar_size),
          inv_z(1.0 / p.height_resolution),
          min_range2(min_range * min_range),
          edge_lo(edge_fraction),
          edge_hi(1.0 - edge_fraction),
          edge_bits_on(edge_fraction > 0.0)
    {
    }

    /** The edge code (EdgeBits) of a point at offsets (u, v) in its pillar, in [0, 1). */
    [[nodiscard]] int32_t edgeCode(double u, double v) const
    {
        return (u < edge_lo ? kEdgeLowM : 0) | (u > edge_hi ? kEdgeHighM : 0) |
               (v < edge_lo ? kEdgeLowN : 0) | (v > edge_hi ? kEdgeHighN : 0) |
               (static_cast<int32_t>(std::floor(u * 256.0)) << kPlaceShift) |
               (static_cast<int32_t>(std::floor(v * 256.0)) << (kPlaceShift + 8));
    }

    static constexpr double kMinR2 = kMinRangeForElevation * kMinRangeForElevation;

    /** Points [i, i1), one at a time. */
    template <bool kKeepIndex, bool kEdges>
    void runScalar(const PointsView& pts, std::size_t i, std::size_t i1, int32_t* m_out,
                   int32_t* n_out, int32_t* z_out, uint32_t* src_out, uint8_t* repeats,
                   int32_t* e_out, PassState& st) const
    {
        for (; i < i1; ++i)
        {
            const double sx = pts.x[i], sy = pts.y[i], sz = pts.z[i];
            const double fm = (r00 * sx + r01 * sy + r02 * sz + tx - ox) * inv_xy;
            const double fn = (r10 * sx + r11 * sy + r12 * sz + ty - oy) * inv_xy;
            const double fz = (r20 * sx + r21 * sy + r22 * sz + tz) * inv_z;
            int32_t m = 0, n = 0, zc = 0;
            if (!floorToInt32(fm, m) || !floorToInt32(fn, n) || !floorToInt32(fz, zc))
            {
                st.have_prev = false;
                continue;
            }
            if (sx * sx + sy * sy + sz * sz < min_range2)
            {
                ++st.near;
                st.have_prev = false;
                continue;
            }
            ++st.valid;
            st.m_lo = std::min(st.m_lo, fm);
            st.m_hi = std::max(st.m_hi, fm);
            st.n_lo = std::min(st.n_lo, fn);
            st.n_hi = std::max(st.n_hi, fn);
            const double r2 = sx * sx + sy * sy;
            if (r2 > kMinR2) st.top = std::max(st.top, sz * std::abs(sz) / r2);
            int32_t e = 0;
            if constexpr (kEdges)
                e = edgeCode(fm - static_cast<double>(m), fn - static_cast<double>(n));
            const bool repeat = st.have_prev && m == st.prev_m && n == st.prev_n && zc == st.prev_z;
            if constexpr (kKeepIndex) repeats[i] = repeat;
            st.have_prev = true;
            st.prev_m = m;
            st.prev_n = n;
            st.prev_z = zc;
            if (repeat)
            {
                if constexpr (kEdges) e_out[st.v - 1] |= e & kEdgeBits;  // the stored point's run
                continue;
            }
            m_out[st.v] = m;
            n_out[st.v] = n;
            z_out[st.v] = zc;
            if constexpr (kEdges) e_out[st.v] = e;
            if constexpr (kKeepIndex) src_out[st.v] = static_cast<uint32_t>(i);
            ++st.v;
        }
    }

#if HIF_X86_AVX
    /** Points [i0, i1) in groups of four; returns where it stopped (fewer than four left).
     *  Repeats are found by comparing each lane with the one before it, and the kept lanes
     *  are packed with one shuffle, without a branch per point. */
    template <bool kKeepIndex, bool kEdges>
    __attribute__((target("avx"))) std::size_t runAvx(const PointsView& pts, std::size_t i0,
                                                      std::size_t i1, int32_t* m_out,
                                                      int32_t* n_out, int32_t* z_out,
                                                      uint32_t* src_out, uint8_t* repeats,
                                                      int32_t* e_out, PassState& st) const
    {
        static const CompactTable table;
        const __m256d a00 = _mm256_set1_pd(r00), a01 = _mm256_set1_pd(r01),
                      a02 = _mm256_set1_pd(r02), a10 = _mm256_set1_pd(r10),
                      a11 = _mm256_set1_pd(r11), a12 = _mm256_set1_pd(r12),
                      a20 = _mm256_set1_pd(r20), a21 = _mm256_set1_pd(r21),
                      a22 = _mm256_set1_pd(r22);
        const __m256d vtx = _mm256_set1_pd(tx), vty = _mm256_set1_pd(ty), vtz = _mm256_set1_pd(tz),
                      vox = _mm256_set1_pd(ox), voy = _mm256_set1_pd(oy),
                      vinv_xy = _mm256_set1_pd(inv_xy), vinv_z = _mm256_set1_pd(inv_z);
        // floor(v) fits in int32 iff -2^31 <= v < 2^31 (false for NaN).
        const __m256d lo = _mm256_set1_pd(-2147483648.0), hi = _mm256_set1_pd(2147483648.0);
        const __m256d inf = _mm256_set1_pd(std::numeric_limits<double>::infinity());
        const __m256d ninf = _mm256_set1_pd(-std::numeric_limits<double>::infinity());
        const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
        const __m256d min_r2 = _mm256_set1_pd(kMinR2);
        const __m256d rel_slack = _mm256_set1_pd(1e-12);
        const __m128i lane_index = _mm_setr_epi32(0, 1, 2, 3);
        __m256d m_lo = inf, m_hi = ninf, n_lo = inf, n_hi = ninf, top = ninf;
        // The previous point in lane 3 of these, and whether it is valid.
        __m128i prev_m = _mm_set1_epi32(st.prev_m), prev_n = _mm_set1_epi32(st.prev_n),
                prev_z = _mm_set1_epi32(st.prev_z);
        const __m256d vedge_lo = _mm256_set1_pd(edge_lo), vedge_hi = _mm256_set1_pd(edge_hi);
        unsigned prev_ok = st.have_prev ? 1u : 0u;
        const __m256d vmin_range2 = _mm256_set1_pd(min_range2);
        std::size_t v = st.v, valid = 0, near = 0, j = i0;
        for (; j + 4 <= i1; j += 4)
        {
            const __m256d sx = _mm256_cvtps_pd(_mm_loadu_ps(pts.x + j));
            const __m256d sy = _mm256_cvtps_pd(_mm_loadu_ps(pts.y + j));
            const __m256d sz = _mm256_cvtps_pd(_mm_loadu_ps(pts.z + j));
            // ((r0 sx + r1 sy) + r2 sz) + t, as the scalar expression.
            const __m256d wx = _mm256_add_pd(
                _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a00, sx), _mm256_mul_pd(a01, sy)),
                              _mm256_mul_pd(a02, sz)),
                vtx);
            const __m256d wy = _mm256_add_pd(
                _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a10, sx), _mm256_mul_pd(a11, sy)),
                              _mm256_mul_pd(a12, sz)),
                vty);
            const __m256d wz = _mm256_add_pd(
                _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(a20, sx), _mm256_mul_pd(a21, sy)),
                              _mm256_mul_pd(a22, sz)),
                vtz);
            const __m256d fm = _mm256_mul_pd(_mm256_sub_pd(wx, vox), vinv_xy);
            const __m256d fn = _mm256_mul_pd(_mm256_sub_pd(wy, voy), vinv_xy);
            const __m256d fz = _mm256_mul_pd(wz, vinv_z);
            const __m256d in_range =
                _mm256_and_pd(_mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(fm, lo, _CMP_GE_OQ),
                                                          _mm256_cmp_pd(fm, hi, _CMP_LT_OQ)),
                                            _mm256_and_pd(_mm256_cmp_pd(fn, lo, _CMP_GE_OQ),
                                                          _mm256_cmp_pd(fn, hi, _CMP_LT_OQ))),
                              _mm256_and_pd(_mm256_cmp_pd(fz, lo, _CMP_GE_OQ),
                                            _mm256_cmp_pd(fz, hi, _CMP_LT_OQ)));
            // Points nearer than the minimum range are dropped (never, when it is 0).
            const __m256d r2s = _mm256_add_pd(
                _mm256_add_pd(_mm256_mul_pd(sx, sx), _mm256_mul_pd(sy, sy)), _mm256_mul_pd(sz, sz));
            const __m256d nearm =
                _mm256_and_pd(in_range, _mm256_cmp_pd(r2s, vmin_range2, _CMP_LT_OQ));
            const __m256d okm = _mm256_andnot_pd(nearm, in_range);
            near += static_cast<std::size_t>(
                __builtin_popcount(static_cast<unsigned>(_mm256_movemask_pd(nearm))));
            // Invalid lanes become 0 before the conversion.
            const __m256d fm_floor = _mm256_floor_pd(_mm256_and_pd(fm, okm));
            const __m256d fn_floor = _mm256_floor_pd(_mm256_and_pd(fn, okm));
            const __m128i m = _mm256_cvttpd_epi32(fm_floor);
            const __m128i n = _mm256_cvttpd_epi32(fn_floor);
            const __m128i z = _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_and_pd(fz, okm)));
            // Edge codes (edgeCode(), as doubles 0 to 15; those of invalid lanes are not kept).
            __m128i e = _mm_setzero_si128();
            if constexpr (kEdges)
            {
                const __m256d u = _mm256_sub_pd(fm, fm_floor), w = _mm256_sub_pd(fn, fn_floor);
                // Where in the pillar (edgeCode()): floor(256 u) 2^8 + floor(256 w) 2^16.
                const __m256d place = _mm256_add_pd(
                    _mm256_mul_pd(_mm256_floor_pd(_mm256_mul_pd(u, _mm256_set1_pd(256.0))),
                                  _mm256_set1_pd(256.0)),
                    _mm256_mul_pd(_mm256_floor_pd(_mm256_mul_pd(w, _mm256_set1_pd(256.0))),
                                  _mm256_set1_pd(65536.0)));
                if (!edge_bits_on)
                    e = _mm256_cvttpd_epi32(place);
                else
                {
                    const __m256d code = _mm256_add_pd(
                        _mm256_add_pd(_mm256_and_pd(_mm256_cmp_pd(u, vedge_lo, _CMP_LT_OQ),
                                                    _mm256_set1_pd(1.0)),
                                      _mm256_and_pd(_mm256_cmp_pd(u, vedge_hi, _CMP_GT_OQ),
                                                    _mm256_set1_pd(2.0))),
                        _mm256_add_pd(_mm256_and_pd(_mm256_cmp_pd(w, vedge_lo, _CMP_LT_OQ),
                                                    _mm256_set1_pd(4.0)),
                                      _mm256_and_pd(_mm256_cmp_pd(w, vedge_hi, _CMP_GT_OQ),
                                                    _mm256_set1_pd(8.0))));
                    e = _mm256_cvttpd_epi32(_mm256_add_pd(code, place));
                }
            }
            const auto ok = static_cast<unsigned>(_mm256_movemask_pd(okm));
            valid += static_cast<std::size_t>(__builtin_popcount(ok));

            // Lane k repeats lane k - 1 (lane 0: the previous group's lane 3).
            const __m128i same =
                _mm_and_si128(_mm_and_si128(_mm_cmpeq_epi32(m, _mm_alignr_epi8(m, prev_m, 12)),
                                            _mm_cmpeq_epi32(n, _mm_alignr_epi8(n, prev_n, 12))),
                              _mm_cmpeq_epi32(z, _mm_alignr_epi8(z, prev_z, 12)));
            const auto same_bits = static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(same)));
            const unsigned repeat = same_bits & ok & ((ok << 1) | prev_ok);
            const unsigned keep = ok & ~repeat;
            const __m128i shuffle =
                _mm_load_si128(reinterpret_cast<const __m128i*>(table.shuffle[keep]));
            // Four lanes are written, the kept ones first; v + 4 <= j + 4 <= i1.
            _mm_storeu_si128(reinterpret_cast<__m128i*>(m_out + v), _mm_shuffle_epi8(m, shuffle));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(n_out + v), _mm_shuffle_epi8(n, shuffle));
            _mm_storeu_si128(reinterpret_cast<__m128i*>(z_out + v), _mm_shuffle_epi8(z, shuffle));
            if constexpr (kEdges)
                if (!edge_bits_on)  // no edge bits to join: each stored point's own place
                    _mm_storeu_si128(reinterpret_cast<__m128i*>(e_out + v),
                                     _mm_shuffle_epi8(e, shuffle));
            if constexpr (kEdges)
                if (edge_bits_on)
                {
                    // A repeat's edge code joins that of the stored point of its run: each lane
                    // takes the codes of the repeats after it in the group (a suffix OR over runs,
                    // in two steps), and a run that began before the group adds its first lanes'
                    // to the last point stored.
                    const __m128i bits = _mm_setr_epi32(1, 2, 4, 8);
                    const __m128i rep = _mm_cmpeq_epi32(
                        _mm_and_si128(_mm_set1_epi32(static_cast<int>(repeat)), bits), bits);
                    const __m128i next1 = _mm_srli_si128(rep, 4);  // lane k + 1 repeats lane k
                    // Only the edge bits join; each stored point keeps its own place.
                    const __m128i edge_bits = _mm_set1_epi32(kEdgeBits);
                    const __m128i eb = _mm_and_si128(e, edge_bits);
                    __m128i run = _mm_or_si128(eb, _mm_and_si128(_mm_srli_si128(eb, 4), next1));
                    run = _mm_or_si128(
                        run, _mm_and_si128(_mm_srli_si128(run, 8),
                                           _mm_and_si128(next1, _mm_srli_si128(next1, 4))));
                    if (repeat & 1u) e_out[v - 1] |= _mm_cvtsi128_si32(run);
                    run = _mm_or_si128(run, _mm_andnot_si128(edge_bits, e));
                    _mm_storeu_si128(reinterpret_cast<__m128i*>(e_out + v),
                                     _mm_shuffle_epi8(run, shuffle));
                }
            if constexpr (kKeepIndex)
            {
                const __m128i idx = _mm_add_epi32(_mm_set1_epi32(static_cast<int>(j)), lane_index);
                _mm_storeu_si128(reinterpret_cast<__m128i*>(src_out + v),
                                 _mm_shuffle_epi8(idx, shuffle));
                for (unsigned k = 0; k < 4; ++k)
                    repeats[j + k] = static_cast<uint8_t>((repeat >> k) & 1u);
            }
            v += static_cast<std::size_t>(__builtin_popcount(keep));
            prev_m = m;
            prev_n = n;
            prev_z = z;
            prev_ok = ok >> 3;

            m_lo = _mm256_min_pd(m_lo, _mm256_blendv_pd(inf, fm, okm));
            m_hi = _mm256_max_pd(m_hi, _mm256_blendv_pd(ninf, fm, okm));
            n_lo = _mm256_min_pd(n_lo, _mm256_blendv_pd(inf, fn, okm));
            n_hi = _mm256_max_pd(n_hi, _mm256_blendv_pd(ninf, fn, okm));
            // Top beam: z |z| / r^2 is divided out only where it may beat the lane's maximum
            // (z |z| >= top r^2, less a relative 1e-12 so that rounding cannot hide one); the
            // others cannot change it. A division per point cost 0.1 ms per scan.
            const __m256d r2 = _mm256_add_pd(_mm256_mul_pd(sx, sx), _mm256_mul_pd(sy, sy));
            const __m256d num = _mm256_mul_pd(sz, _mm256_and_pd(sz, abs_mask));
            const __m256d bound = _mm256_mul_pd(top, r2);
            const __m256d slack = _mm256_mul_pd(_mm256_and_pd(bound, abs_mask), rel_slack);
            const __m256d far =
                _mm256_and_pd(_mm256_and_pd(okm, _mm256_cmp_pd(r2, min_r2, _CMP_GT_OQ)),
                              _mm256_cmp_pd(num, _mm256_sub_pd(bound, slack), _CMP_GE_OQ));
            if (_mm256_movemask_pd(far) != 0)
            {
                const __m256d q = _mm256_div_pd(num, _mm256_max_pd(r2, min_r2));
                top = _mm256_max_pd(top, _mm256_blendv_pd(ninf, q, far));
            }
        }
        alignas(32) double lanes[5][4];
        _mm256_store_pd(lanes[0], m_lo);
        _mm256_store_pd(lanes[1], m_hi);
        _mm256_store_pd(lanes[2], n_lo);
        _mm256_store_pd(lanes[3], n_hi);
        _mm256_store_pd(lanes[4], top);
        for (int k = 0; k < 4; ++k)
        {
            st.m_lo = std::min(st.m_lo, lanes[0][k]);
            st.m_hi = std::max(st.m_hi, lanes[1][k]);
            st.n_lo = std::min(st.n_lo, lanes[2][k]);
            st.n_hi = std::max(st.n_hi, lanes[3][k]);
            st.top = std::max(st.top, lanes[4][k]);
        }
        st.v = v;
        st.valid += valid;
        st.near += near;
        st.have_prev = prev_ok != 0;
        st.prev_m = _mm_extract_epi32(prev_m, 3);
        st.prev_n = _mm_extract_epi32(prev_n, 3);
        st.prev_z = _mm_extract_epi32(prev_z, 3);
        return j;
    }
#endif

    template <bool kKeepIndex, bool kEdges>
    ChunkSummary run(const PointsView& pts, std::size_t i0, std::size_t i1, int32_t* m_out,
                     int32_t* n_out, int32_t* z_out, uint32_t* src_out, uint8_t* repeats,
                     int32_t* e_out) const
    {
        PassState st;
        st.v = i0;
        std::size_t i = i0;
#if HIF_X86_AVX
        if (useAvx())
            i = runAvx<kKeepIndex, kEdges>(pts, i0, i1, m_out, n_out, z_out, src_out, repeats,
                                           e_out, st);
#endif
        runScalar<kKeepIndex, kEdges>(pts, i, i1, m_out, n_out, z_out, src_out, repeats, e_out, st);
        ChunkSummary ch;
        ch.valid = st.valid;
        ch.near = st.near;
        ch.kept = st.v - i0;
        ch.top_slope_sq = st.top;
        // floor() is monotone, so these are the extremes of the valid points' indices (and
        // they fit, as each of those points did).
        if (st.valid > 0)
        {
            const bool fit = floorToInt32(st.m_lo, ch.m_min) && floorToInt32(st.m_hi, ch.m_max) &&
                             floorToInt32(st.n_lo, ch.n_min) && floorToInt32(st.n_hi, ch.n_max);
            assert(fit);
            static_cast<void>(fit);
        }
        return ch;
    }
};
}  // namespace

ChunkSummary quantizeChunk(const Eigen::Isometry3d& T, const GridGeometry& geometry,
                           double min_range, const PointsView& pts, std::size_t i0, std::size_t i1,
                           const ChunkOutput& out)
{
    const QuantizeChunk quant{T.linear(), T.translation(), geometry, min_range,
                              out.edge ? out.edge_fraction : 0.0};
    if (out.src)  // classification: no edge codes
        return quant.run<true, false>(pts, i0, i1, out.m, out.n, out.z, out.src, out.repeats,
                                      nullptr);
    return out.edge ? quant.run<false, true>(pts, i0, i1, out.m, out.n, out.z, nullptr, nullptr,
                                             out.edge)
                    : quant.run<false, false>(pts, i0, i1, out.m, out.n, out.z, nullptr, nullptr,
                                              nullptr);
}

}  // namespace hif::detail
