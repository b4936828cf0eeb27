// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   RangeImage.cpp
 * @brief  The range image of a scan, scalar and AVX.
 */
#include "RangeImage.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "Simd.h"
#include "hif/detail/Cpu.h"

namespace hif::detail
{
namespace
{
/** Range-image cell (imageCell(), or -1 if none), range and tan(elevation) of points [0, n)
 *  of x/y/z; with `by_col`, also the cell's index in the image stored column by column
 *  (col * rows + row). */
void imageCellsScalar(const RangeImageLayout& l, const float* x, const float* y, const float* z,
                      std::size_t n, int32_t* cells, float* ranges, float* tans, int32_t* by_col)
{
    for (std::size_t j = 0; j < n; ++j)
    {
        cells[j] = -1;
        ranges[j] = tans[j] = 0.0f;  // read, unused, by the next pass's vector code
        const double sx = x[j], sy = y[j], sz = z[j];
        if (!std::isfinite(sx) || !std::isfinite(sy) || !std::isfinite(sz)) continue;
        const double rxy = std::sqrt(sx * sx + sy * sy);
        if (rxy == 0.0) continue;
        cells[j] = imageCell(l, pseudoAzimuth(sx, sy), sz / rxy);
        if (by_col && cells[j] >= 0) by_col[j] = cells[j] % l.cols * l.rows + cells[j] / l.cols;
        ranges[j] = static_cast<float>(std::sqrt(rxy * rxy + sz * sz));
        tans[j] = static_cast<float>(sz / rxy);
    }
}

#if HIF_X86_AVX
/** imageCellsScalar() four points at a time: the same operations, so the same bits. */
__attribute__((target("avx"))) void imageCellsAvx(const RangeImageLayout& l, const float* x,
                                                  const float* y, const float* z, std::size_t n,
                                                  int32_t* cells, float* ranges, float* tans,
                                                  int32_t* by_col)
{
    const __m256d inf = _mm256_set1_pd(std::numeric_limits<double>::infinity());
    const __m256d zero = _mm256_setzero_pd();
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    const __m256d tan_min = _mm256_set1_pd(l.tan_min), tan_max = _mm256_set1_pd(l.tan_max);
    const __m256d tan_res = _mm256_set1_pd(l.tan_res);
    const __m256d col_scale = _mm256_set1_pd(l.cols / 4.0);
    const __m256d last_col = _mm256_set1_pd(l.cols - 1), last_row = _mm256_set1_pd(l.rows - 1);
    const __m256d cols = _mm256_set1_pd(l.cols), rows = _mm256_set1_pd(l.rows);
    const __m256d none = _mm256_set1_pd(-1.0);
    const __m256d two = _mm256_set1_pd(2.0), four = _mm256_set1_pd(4.0);
    std::size_t j = 0;
    for (; j + 4 <= n; j += 4)
    {
        const __m256d sx = _mm256_cvtps_pd(_mm_loadu_ps(x + j));
        const __m256d sy = _mm256_cvtps_pd(_mm_loadu_ps(y + j));
        const __m256d sz = _mm256_cvtps_pd(_mm_loadu_ps(z + j));
        const __m256d ax = _mm256_and_pd(sx, abs_mask), ay = _mm256_and_pd(sy, abs_mask);
        const __m256d finite = _mm256_and_pd(
            _mm256_and_pd(_mm256_cmp_pd(ax, inf, _CMP_LT_OQ), _mm256_cmp_pd(ay, inf, _CMP_LT_OQ)),
            _mm256_cmp_pd(_mm256_and_pd(sz, abs_mask), inf, _CMP_LT_OQ));
        const __m256d rxy =
            _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(sx, sx), _mm256_mul_pd(sy, sy)));
        // pseudoAzimuth(): y / (|x| + |y|), then by quadrant.
        const __m256d a = _mm256_div_pd(sy, _mm256_add_pd(ax, ay));
        const __m256d right =
            _mm256_blendv_pd(_mm256_add_pd(four, a), a, _mm256_cmp_pd(sy, zero, _CMP_GE_OQ));
        const __m256d paz =
            _mm256_blendv_pd(_mm256_sub_pd(two, a), right, _mm256_cmp_pd(sx, zero, _CMP_GE_OQ));
        const __m256d tan_el = _mm256_div_pd(sz, rxy);
        const __m256d ok =
            _mm256_and_pd(_mm256_and_pd(finite, _mm256_cmp_pd(rxy, zero, _CMP_NEQ_OQ)),
                          _mm256_and_pd(_mm256_cmp_pd(tan_el, tan_min, _CMP_GE_OQ),
                                        _mm256_cmp_pd(tan_el, tan_max, _CMP_LT_OQ)));
        // imageCell(): truncated column and row, each capped at the last one.
        const __m256d col = _mm256_round_pd(_mm256_min_pd(_mm256_mul_pd(paz, col_scale), last_col),
                                            _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
        const __m256d row = _mm256_round_pd(
            _mm256_min_pd(_mm256_div_pd(_mm256_sub_pd(tan_el, tan_min), tan_res), last_row),
            _MM_FROUND_TO_ZERO | _MM_FROUND_NO_EXC);
        const __m256d k = _mm256_add_pd(_mm256_mul_pd(row, cols), col);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(cells + j),
                         _mm256_cvttpd_epi32(_mm256_blendv_pd(none, k, ok)));
        if (by_col)
        {
            const __m256d kc = _mm256_add_pd(_mm256_mul_pd(col, rows), row);
            _mm_storeu_si128(reinterpret_cast<__m128i*>(by_col + j),
                             _mm256_cvttpd_epi32(_mm256_blendv_pd(none, kc, ok)));
        }
        const __m256d range =
            _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(rxy, rxy), _mm256_mul_pd(sz, sz)));
        _mm_storeu_ps(ranges + j, _mm256_cvtpd_ps(range));
        _mm_storeu_ps(tans + j, _mm256_cvtpd_ps(tan_el));
    }
    imageCellsScalar(l, x + j, y + j, z + j, n - j, cells + j, ranges + j, tans + j,
                     by_col ? by_col + j : nullptr);
}
#endif

/** imageCellsScalar(), with AVX when the CPU has it. */
void imageCells(const RangeImageLayout& l, const float* x, const float* y, const float* z,
                std::size_t n, int32_t* cells, float* ranges, float* tans, int32_t* by_col)
{
#if HIF_X86_AVX
    if (useAvx())
    {
        imageCellsAvx(l, x, y, z, n, cells, ranges, tans, by_col);
        return;
    }
#endif
    imageCellsScalar(l, x, y, z, n, cells, ranges, tans, by_col);
}
}  // namespace

namespace
{
/** BeamReturn::of() for the points [0, n) of ranges and tans whose cell is not -1, into `out`,
 *  and `farthest` raised to the largest of their ranges that a cell can hold (kMaxCellRange). */
void beamReturnsScalar(const int32_t* cells, const float* ranges, const float* tans, std::size_t n,
                       BeamReturn* out, float& farthest)
{
    for (std::size_t j = 0; j < n; ++j)
    {
        if (cells[j] < 0) continue;
        out[j] = BeamReturn::of(ranges[j], tans[j]);
        if (ranges[j] < kMaxCellRange) farthest = std::max(farthest, ranges[j]);
    }
}

/** The centimetres of the points [0, n) of `ranges` (rounded; kNoReturnCm from kMaxCellRange
 *  on), into `out`. */
void rangesCmScalar(const int32_t* cells, const float* ranges, std::size_t n, uint16_t* out)
{
    for (std::size_t j = 0; j < n; ++j)
        if (cells[j] >= 0)
            out[j] = ranges[j] < kMaxCellRange ? static_cast<uint16_t>(ranges[j] * 100.0f + 0.5f)
                                               : kNoReturnCm;
}

#if HIF_X86_AVX
/** beamReturnsScalar() four points at a time: the same operations, so the same bits. */
__attribute__((target("avx"))) void beamReturnsAvx(const int32_t* cells, const float* ranges,
                                                   const float* tans, std::size_t n,
                                                   BeamReturn* out, float& farthest)
{
    static_assert(sizeof(BeamReturn) == 4 && offsetof(BeamReturn, range_cm) == 0,
                  "a cell's range is the low half of its four bytes");
    const __m128 hundred = _mm_set1_ps(100.0f), half = _mm_set1_ps(0.5f);
    const __m128 minus_half = _mm_set1_ps(-0.5f), zero = _mm_setzero_ps();
    const __m128 none = _mm_set1_ps(static_cast<float>(BeamReturn::kNone));
    const __m128 steps = _mm_set1_ps(static_cast<float>(1.0 / BeamReturn::kTanStep));
    const __m128 q_min = _mm_set1_ps(-32767.0f), q_max = _mm_set1_ps(32767.0f);
    const __m128 reach = _mm_set1_ps(kMaxCellRange);
    const __m128i low16 = _mm_set1_epi32(0xFFFF);
    __m128 far = _mm_set1_ps(farthest);
    std::size_t j = 0;
    for (; j + 4 <= n; j += 4)
    {
        const __m128 used = _mm_castsi128_ps(_mm_cmpgt_epi32(
            _mm_loadu_si128(reinterpret_cast<const __m128i*>(cells + j)), _mm_set1_epi32(-1)));
        const __m128 r = _mm_loadu_ps(ranges + j);
        const __m128 cm = _mm_add_ps(_mm_mul_ps(r, hundred), half);
        const __m128 held = _mm_cmplt_ps(r, reach);  // false for NaN
        // std::clamp(): for the finite tangents of the cells used, max then min is the same.
        const __m128 q =
            _mm_min_ps(_mm_max_ps(_mm_mul_ps(_mm_loadu_ps(tans + j), steps), q_min), q_max);
        const __m128 rounded =
            _mm_add_ps(q, _mm_blendv_ps(minus_half, half, _mm_cmpge_ps(q, zero)));
        const __m128i range_cm = _mm_cvttps_epi32(_mm_blendv_ps(none, cm, held));
        // No return: all bits set, as BeamReturn{}.
        const __m128i tan_q = _mm_or_si128(
            _mm_cvttps_epi32(rounded),
            _mm_castps_si128(_mm_andnot_ps(held, _mm_castsi128_ps(_mm_set1_epi32(-1)))));
        const __m128i packed =
            _mm_or_si128(_mm_and_si128(range_cm, low16), _mm_slli_epi32(tan_q, 16));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(out + j), packed);
        far = _mm_blendv_ps(far, _mm_max_ps(far, r), _mm_and_ps(used, _mm_cmplt_ps(r, reach)));
    }
    alignas(16) float lanes[4];
    _mm_store_ps(lanes, far);
    farthest = std::max(std::max(lanes[0], lanes[1]), std::max(lanes[2], lanes[3]));
    beamReturnsScalar(cells + j, ranges + j, tans + j, n - j, out + j, farthest);
}

/** rangesCmScalar() four points at a time: the same operations, so the same bits. */
__attribute__((target("avx"))) void rangesCmAvx(const int32_t* cells, const float* ranges,
                                                std::size_t n, uint16_t* out)
{
    const __m128 hundred = _mm_set1_ps(100.0f), half = _mm_set1_ps(0.5f);
    const __m128 reach = _mm_set1_ps(kMaxCellRange);
    const __m128 none = _mm_set1_ps(static_cast<float>(kNoReturnCm));
    std::size_t j = 0;
    for (; j + 4 <= n; j += 4)
    {
        const __m128 r = _mm_loadu_ps(ranges + j);
        const __m128 cm =
            _mm_blendv_ps(none, _mm_add_ps(_mm_mul_ps(r, hundred), half), _mm_cmplt_ps(r, reach));
        const __m128i v = _mm_cvttps_epi32(cm);  // 0 .. 65535: packed to 16 bits as they are
        _mm_storel_epi64(reinterpret_cast<__m128i*>(out + j), _mm_packus_epi32(v, v));
    }
    rangesCmScalar(cells + j, ranges + j, n - j, out + j);
}
#endif

/** The nearest return of `pts` in every cell of `img` (layout `l`; row by row, or with
 *  `by_column` column by column): `prepare(cells, ranges, tans, n, values)` turns the points'
 *  ranges and tangents into the image's values, `keep(cell, value)` keeps the nearer of the
 *  cell's and the point's; `none` where no return. */
template <typename T, typename Prepare, typename Keep>
void fillImage(const RangeImageLayout& l, const PointsView& pts, std::vector<T>& img, T none,
               Prepare prepare, Keep keep, std::vector<uint8_t>* blocks = nullptr,
               bool by_column = false)
{
    // Blocks of the flattened image: one may end a row and start the next (at the seam of
    // the azimuth), which the sky test's "a return nearby" does not mind.
    if (blocks) blocks->assign(l.cells() / kBlockCols + 1, 0);
    img.resize(l.cells());
    // A "no return" whose bytes are all alike (all of ours) is a memset; a loop otherwise.
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &none, sizeof(T));
    if (std::all_of(bytes, bytes + sizeof(T), [&](unsigned char b) { return b == bytes[0]; }))
        std::memset(static_cast<void*>(img.data()), bytes[0], img.size() * sizeof(T));
    else
        std::fill(img.begin(), img.end(), none);
    constexpr std::size_t kBlock = 256;
    alignas(64) int32_t cells[kBlock];
    alignas(64) float ranges[kBlock];
    alignas(64) float tans[kBlock];
    alignas(64) int32_t stored[kBlock];  // by_column: where each cell is stored
    alignas(64) T values[kBlock];
    int32_t* const at = by_column ? stored : cells;
    for (std::size_t b0 = 0; b0 < pts.size; b0 += kBlock)
    {
        const std::size_t nb = std::min(kBlock, pts.size - b0);
        imageCells(l, pts.x + b0, pts.y + b0, pts.z + b0, nb, cells, ranges, tans,
                   by_column ? stored : nullptr);
        prepare(cells, ranges, tans, nb, values);
        for (std::size_t j = 0; j < nb; ++j)
            if (cells[j] >= 0)
            {
                keep(img[static_cast<std::size_t>(at[j])], values[j]);
                if (blocks) (*blocks)[static_cast<std::size_t>(cells[j]) / kBlockCols] = 1;
            }
    }
}
}  // namespace

namespace
{
uint64_t passedRowsScalar(const RangeImageLayout& l, const BeamReturn* column, int row_lo, int n,
                          double d, double margin)
{
    uint64_t mask = 0;
    for (int k = 0; k < n; ++k)
    {
        const BeamReturn& ret = column[row_lo + k];
        if (ret.range_cm != BeamReturn::kNone &&
            passesBeyond(ret.range(), rowDist2(l, d, row_lo + k), margin))
            mask |= uint64_t{1} << k;
    }
    return mask;
}

#if HIF_X86_AVX
/** passedRowsScalar() four rows at a time: the same operations, so the same bits. */
__attribute__((target("avx"))) uint64_t passedRowsAvx(const RangeImageLayout& l,
                                                      const BeamReturn* column, int row_lo, int n,
                                                      double d, double margin)
{
    static_assert(sizeof(BeamReturn) == 4 && offsetof(BeamReturn, range_cm) == 0,
                  "a cell's range is the low half of its four bytes");
    const __m128i low16 = _mm_set1_epi32(0xFFFF);
    const __m128 metres_per_cm = _mm_set1_ps(0.01f);
    const __m256d dd = _mm256_set1_pd(d * d), one = _mm256_set1_pd(1.0);
    const __m256d half = _mm256_set1_pd(0.5), four = _mm256_set1_pd(4.0);
    const __m256d tan_min = _mm256_set1_pd(l.tan_min), tan_res = _mm256_set1_pd(l.tan_res);
    const __m256d mrg = _mm256_set1_pd(margin), zero = _mm256_setzero_pd();
    __m256d rows = _mm256_set_pd(row_lo + 3, row_lo + 2, row_lo + 1, row_lo);
    uint64_t mask = 0;
    int k = 0;
    for (; k + 4 <= n; k += 4)
    {
        const __m128i raw = _mm_loadu_si128(reinterpret_cast<const __m128i*>(column + row_lo + k));
        const __m128i range_cm = _mm_and_si128(raw, low16);
        const __m128i none = _mm_cmpeq_epi32(range_cm, low16);
        // BeamReturn::range(), then rowDist2() and passesBeyond().
        const __m256d r = _mm256_cvtps_pd(_mm_mul_ps(_mm_cvtepi32_ps(range_cm), metres_per_cm));
        const __m256d tan_el =
            _mm256_add_pd(tan_min, _mm256_mul_pd(_mm256_add_pd(rows, half), tan_res));
        const __m256d dist2 = _mm256_mul_pd(dd, _mm256_add_pd(one, _mm256_mul_pd(tan_el, tan_el)));
        const __m256d beyond = _mm256_sub_pd(r, mrg);
        const __m256d ok =
            _mm256_and_pd(_mm256_cmp_pd(beyond, zero, _CMP_GT_OQ),
                          _mm256_cmp_pd(_mm256_mul_pd(beyond, beyond), dist2, _CMP_GT_OQ));
        const int bits = _mm256_movemask_pd(ok) & ~_mm_movemask_ps(_mm_castsi128_ps(none));
        mask |= static_cast<uint64_t>(bits) << k;
        rows = _mm256_add_pd(rows, four);
    }
    if (k < n) mask |= passedRowsScalar(l, column, row_lo + k, n - k, d, margin) << k;
    return mask;
}
#endif
}  // namespace

std::vector<uint16_t> nextBeamRowsTable(const RangeImageLayout& l,
                                        const std::vector<double>& ring_tan)
{
    std::vector<uint16_t> table(2 * static_cast<std::size_t>(std::max(l.rows, 0)), 0);
    const auto n = static_cast<std::ptrdiff_t>(ring_tan.size());
    if (n < 2) return table;
    for (int row = 0; row < l.rows; ++row)
    {
        const double t = l.tan_min + (row + 0.5) * l.tan_res;
        // The beam nearest the row, and the next one each way.
        auto i = static_cast<std::ptrdiff_t>(std::lower_bound(ring_tan.begin(), ring_tan.end(), t) -
                                             ring_tan.begin());
        if (i == n || (i > 0 && t - ring_tan[i - 1] < ring_tan[i] - t)) --i;
        for (const int dir : {-1, 1})
        {
            const std::ptrdiff_t next = i + dir;
            if (next < 0 || next >= n) continue;
            // Beams at most one and a half median spacings (three rows) apart: the usual rows
            // reach the next.
            const double gap = std::abs(ring_tan[next] - ring_tan[i]);
            if (gap <= 3.0 * l.tan_res) continue;
            const double rows = std::min(std::ceil(1.5 * gap / l.tan_res), double(l.rows));
            table[2 * static_cast<std::size_t>(row) + (dir > 0)] = static_cast<uint16_t>(rows);
        }
    }
    return table;
}

uint64_t passedRows(const RangeImageLayout& l, const BeamReturn* column, int row_lo, int n,
                    double d, double margin)
{
#if HIF_X86_AVX
    if (useAvx()) return passedRowsAvx(l, column, row_lo, n, d, margin);
#endif
    return passedRowsScalar(l, column, row_lo, n, d, margin);
}

float buildReturnImage(const RangeImageLayout& l, const PointsView& pts,
                       std::vector<BeamReturn>& img, std::vector<uint8_t>& blocks)
{
    float farthest = 0.0f;
    fillImage(
        l, pts, img, BeamReturn{},
        [&farthest](const int32_t* cells, const float* ranges, const float* tans, std::size_t n,
                    BeamReturn* out)
        {
#if HIF_X86_AVX
            if (useAvx())
            {
                beamReturnsAvx(cells, ranges, tans, n, out, farthest);
                return;
            }
#endif
            beamReturnsScalar(cells, ranges, tans, n, out, farthest);
        },
        [](BeamReturn& cell, const BeamReturn& b) { cell.keepNearer(b); }, &blocks, true);
    return farthest;
}

void buildRangeImageCm(const RangeImageLayout& l, const PointsView& pts, std::vector<uint16_t>& img,
                       std::vector<uint8_t>& blocks)
{
    // Ranges from 655.34 m on read as "no return" (no LiDAR of interest reaches them).
    fillImage(
        l, pts, img, kNoReturnCm,
        [](const int32_t* cells, const float* ranges, const float* /*tans*/, std::size_t n,
           uint16_t* out)
        {
#if HIF_X86_AVX
            if (useAvx())
            {
                rangesCmAvx(cells, ranges, n, out);
                return;
            }
#endif
            rangesCmScalar(cells, ranges, n, out);
        },
        [](uint16_t& cell, uint16_t v) { cell = std::min(cell, v); }, &blocks);
}

void BeamGate::withoutEdges(std::vector<Span>& spans) const
{
    // The pieces are appended after the spans, which are then dropped.
    const std::size_t n = spans.size();
    std::size_t e = 0;
    for (std::size_t k = 0; k < n; ++k)
    {
        int32_t at = spans[k].lo;
        const int32_t end = spans[k].hi;
        while (e < edge_count && edge_spans[e].hi <= at) ++e;
        for (std::size_t f = e; f < edge_count && edge_spans[f].lo < end; ++f)
        {
            if (edge_spans[f].lo > at) spans.push_back({at, edge_spans[f].lo});
            at = std::max(at, edge_spans[f].hi);
        }
        if (at < end) spans.push_back({at, end});
    }
    spans.erase(spans.begin(), spans.begin() + static_cast<std::ptrdiff_t>(n));
}

}  // namespace hif::detail
