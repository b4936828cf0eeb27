// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   PillarGrid.cpp
 * @brief  Scan integration into the global pillar dictionary, and point queries.
 */
#include "hif/PillarGrid.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

// The per-point passes (bucketScan()'s first pass, the see-through range image) have an AVX
// version, chosen at run time (cpuHasAvx()), on x86-64 with GCC or Clang.
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define HIF_X86_AVX 1
#include <immintrin.h>
#else
#define HIF_X86_AVX 0
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <cassert>
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

#if HIF_X86_AVX
/** True when the CPU runs AVX (asked once). */
bool cpuHasAvx()
{
    static const bool has_avx = __builtin_cpu_supports("avx");
    return has_avx;
}
#endif

/** floor(v) for v >= -2^31, saturated at INT32_MAX (a gap or padding wider than any map). */
int32_t floorCells(double v)
{
    int32_t c = std::numeric_limits<int32_t>::max();
    return floorToInt32(v, c) ? c : std::numeric_limits<int32_t>::max();
}

/** ceil(v) for v > -1, saturated at INT32_MAX. */
int32_t ceilCells(double v)
{
    int32_t c = 0;
    return floorToInt32(-v, c) && c > std::numeric_limits<int32_t>::min()
               ? -c
               : std::numeric_limits<int32_t>::max();
}

/** Sorts cells[0, n) ascending and removes duplicates in place; returns the distinct count.
 *  Pillars near the sensor hold hundreds of points in a few height cells: for those, a bitmap
 *  over the pillar's height range is O(n + range / 64) instead of a comparison sort. */
std::size_t sortDistinct(int32_t* cells, std::size_t n)
{
    constexpr std::size_t kSmall = 24;         // below this, insertion sort is fastest
    constexpr int64_t kBitmapCells = 64 * 64;  // bitmap of at most 64 words on the stack
    if (n > kSmall)
    {
        const auto [lo_it, hi_it] = std::minmax_element(cells, cells + n);
        const int64_t lo = *lo_it, range = int64_t{*hi_it} - lo + 1;
        if (range <= kBitmapCells)
        {
            uint64_t bits[kBitmapCells / 64] = {};
            for (std::size_t k = 0; k < n; ++k)
            {
                const auto o = static_cast<uint64_t>(cells[k] - lo);
                bits[o >> 6] |= uint64_t{1} << (o & 63);
            }
            std::size_t m = 0;
            const auto words = static_cast<std::size_t>((range + 63) / 64);
            for (std::size_t w = 0; w < words; ++w)
                for (uint64_t b = bits[w]; b != 0; b &= b - 1)
                    cells[m++] = static_cast<int32_t>(
                        lo +
                        static_cast<int64_t>(w * 64 + static_cast<unsigned>(__builtin_ctzll(b))));
            return m;
        }
        std::sort(cells, cells + n);
    }
    else
    {
        // Insertion sort that drops duplicates as it goes: cells[0, m) is sorted and distinct.
        std::size_t m = n > 0 ? 1 : 0;
        for (std::size_t k = 1; k < n; ++k)
        {
            const int32_t c = cells[k];
            std::size_t j = m;
            while (j > 0 && cells[j - 1] > c) --j;
            if (j > 0 && cells[j - 1] == c) continue;  // already there
            for (std::size_t q = m; q > j; --q) cells[q] = cells[q - 1];
            cells[j] = c;
            ++m;
        }
        return m;
    }
    return static_cast<std::size_t>(std::unique(cells, cells + n) - cells);
}
}  // namespace

PillarGrid::PillarGrid(const Params& params) : params_(params)
{
    params_.validate();
    model_ = LogOddsModel::fromParams(params_);
    static_logodds_ = logit(params_.static_threshold);
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
    static_logodds_ = logit(params_.static_threshold);
}

struct PillarGrid::Arena
{
    // No more threads than TBB will run (it warns and ignores the rest).
    explicit Arena(std::size_t threads)
        : arena(std::min(static_cast<int>(std::min<std::size_t>(threads, 1024)),
                         tbb::info::default_concurrency()))
    {
    }
    tbb::task_arena arena;
};

void PillarGrid::setThreads(std::size_t threads)
{
    if (threads == 0)
        throw std::invalid_argument("hif::PillarGrid::setThreads: the thread count must be >= 1");
    threads_ = threads;
    arena_ = threads > 1 ? std::make_shared<Arena>(threads) : nullptr;
}

template <typename F>
void PillarGrid::forRanges(std::size_t n, std::size_t grain, F&& f) const
{
    if (threads_ <= 1 || n <= grain)
    {
        f(std::size_t{0}, n);
        return;
    }
    arena_->arena.execute(
        [&]
        {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                              [&](const tbb::blocked_range<std::size_t>& r)
                              { f(r.begin(), r.end()); });
        });
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
    bucketScan(pts, T, scan_);
    buildIntervals(scan_);
    const InsertStats st = mergeScan(scan_);
    if (params_.see_through_range > 0.0) seeThroughMisses(pts, T, scan_);
    return st;
}

namespace
{
/** A monotone stand-in for the azimuth of (x, y), in [0, 4) ("diamond angle"): one division
 *  instead of an atan2. Range-image columns are uniform in it, 0.2 degree wide on average. */
inline double pseudoAzimuth(double x, double y)
{
    const double s = std::abs(x) + std::abs(y);
    if (s == 0.0) return 0.0;
    const double a = y / s;
    return x >= 0.0 ? (y >= 0.0 ? a : 4.0 + a) : 2.0 - a;
}

// Range image of the see-through misses: columns uniform in pseudoAzimuth(), rows uniform in
// tan(elevation) for elevations in [-30, +15) degrees, 0.2 degree at the horizon.
constexpr int kImageCols = 1800;
constexpr double kTanMin = -0.57735026918962576;  // tan(-30 degrees)
constexpr double kTanMax = 0.26794919243112270;   // tan(15 degrees)
constexpr double kTanRes = 0.2 * M_PI / 180.0;
constexpr int kImageRows = static_cast<int>((kTanMax - kTanMin) / kTanRes) + 1;

/** Cell of the range image for (pseudo-azimuth, tan(elevation)), or -1 outside its rows. */
inline int imageCell(double paz, double tan_el)
{
    if (!(tan_el >= kTanMin && tan_el < kTanMax)) return -1;
    const int c = std::min(kImageCols - 1, static_cast<int>(paz * (kImageCols / 4.0)));
    const int r = std::min(kImageRows - 1, static_cast<int>((tan_el - kTanMin) / kTanRes));
    return r * kImageCols + c;
}
/** Range-image cell (imageCell(), or -1 if none) and range of points [0, n) of x/y/z. */
void imageCellsScalar(const float* x, const float* y, const float* z, std::size_t n, int32_t* cells,
                      float* ranges)
{
    for (std::size_t j = 0; j < n; ++j)
    {
        cells[j] = -1;
        const double sx = x[j], sy = y[j], sz = z[j];
        if (!std::isfinite(sx) || !std::isfinite(sy) || !std::isfinite(sz)) continue;
        const double rxy = std::sqrt(sx * sx + sy * sy);
        if (rxy == 0.0) continue;
        cells[j] = imageCell(pseudoAzimuth(sx, sy), sz / rxy);
        ranges[j] = static_cast<float>(std::sqrt(rxy * rxy + sz * sz));
    }
}

#if HIF_X86_AVX
/** imageCellsScalar() four points at a time: the same operations, so the same bits. */
__attribute__((target("avx"))) void imageCellsAvx(const float* x, const float* y, const float* z,
                                                  std::size_t n, int32_t* cells, float* ranges)
{
    const __m256d inf = _mm256_set1_pd(std::numeric_limits<double>::infinity());
    const __m256d zero = _mm256_setzero_pd();
    const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    const __m256d tan_min = _mm256_set1_pd(kTanMin), tan_max = _mm256_set1_pd(kTanMax);
    const __m256d tan_res = _mm256_set1_pd(kTanRes);
    const __m256d col_scale = _mm256_set1_pd(kImageCols / 4.0);
    const __m256d last_col = _mm256_set1_pd(kImageCols - 1),
                  last_row = _mm256_set1_pd(kImageRows - 1);
    const __m256d cols = _mm256_set1_pd(kImageCols);
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
        const __m256d range =
            _mm256_sqrt_pd(_mm256_add_pd(_mm256_mul_pd(rxy, rxy), _mm256_mul_pd(sz, sz)));
        _mm_storeu_ps(ranges + j, _mm256_cvtpd_ps(range));
    }
    imageCellsScalar(x + j, y + j, z + j, n - j, cells + j, ranges + j);
}
#endif

/** imageCellsScalar(), with AVX when the CPU has it. */
void imageCells(const float* x, const float* y, const float* z, std::size_t n, int32_t* cells,
                float* ranges)
{
#if HIF_X86_AVX
    if (cpuHasAvx())
    {
        imageCellsAvx(x, y, z, n, cells, ranges);
        return;
    }
#endif
    imageCellsScalar(x, y, z, n, cells, ranges);
}
}  // namespace

void PillarGrid::seeThroughMisses(const PointsView& pts, const Eigen::Isometry3d& T,
                                  const ScanPillars& scan)
{
    // Nearest return of the scan in every cell of a range image (sensor frame).
    auto& img = see_through_image_;
    img.assign(static_cast<std::size_t>(kImageCols) * kImageRows,
               std::numeric_limits<float>::infinity());
    constexpr std::size_t kBlock = 256;
    alignas(64) int32_t cells[kBlock];
    alignas(64) float ranges[kBlock];
    for (std::size_t b0 = 0; b0 < pts.size; b0 += kBlock)
    {
        const std::size_t nb = std::min(kBlock, pts.size - b0);
        imageCells(pts.x + b0, pts.y + b0, pts.z + b0, nb, cells, ranges);
        for (std::size_t j = 0; j < nb; ++j)
            if (cells[j] >= 0)
            {
                float& cell = img[static_cast<std::size_t>(cells[j])];
                cell = std::min(cell, ranges[j]);
            }
    }

    // The map's pillars within see_through_range of the sensor that the scan did not hit.
    const double ps = params_.pillar_size;
    const double range = params_.see_through_range, margin = params_.see_through_margin;
    const Eigen::Vector3d t = T.translation();
    const Eigen::Matrix3d Rt = T.linear().transpose();
    int32_t cm = 0, cn = 0;
    if (!floorToInt32((t.x() - params_.origin_x) / ps, cm) ||
        !floorToInt32((t.y() - params_.origin_y) / ps, cn))
        return;
    const int64_t w = static_cast<int64_t>(std::ceil(range / ps));
    const int64_t side = 2 * w + 1;
    auto& hit = see_through_hit_;
    hit.assign(static_cast<std::size_t>(side * side), 0);
    for (uint64_t key : scan.keys)
    {
        const PillarIndex idx = unpackKey(key);
        const int64_t a = int64_t{idx.m} - cm + w, b = int64_t{idx.n} - cn + w;
        if (a >= 0 && a < side && b >= 0 && b < side)
            hit[static_cast<std::size_t>(a * side + b)] = 1;
    }
    // Rows of the window are independent (each pillar is in one row): split them over threads.
    const Eigen::Vector3d up = Rt.col(2);  // world z axis in the sensor frame
    forRanges(static_cast<std::size_t>(side), 8,
              [&](std::size_t a0, std::size_t a1)
              {
                  for (auto a = static_cast<int64_t>(a0); a < static_cast<int64_t>(a1); ++a)
                      for (int64_t b = 0; b < side; ++b)
                      {
                          const int64_t m = cm + a - w, n = cn + b - w;
                          if (hit[static_cast<std::size_t>(a * side + b)] || m < INT32_MIN ||
                              m > INT32_MAX || n < INT32_MIN || n > INT32_MAX)
                              continue;
                          const PillarIndex idx{static_cast<int32_t>(m), static_cast<int32_t>(n)};
                          const auto it = pillars_.find(packKey(idx));
                          if (it == pillars_.end()) continue;
                          const double cx = params_.origin_x + (idx.m + 0.5) * ps;
                          const double cy = params_.origin_y + (idx.n + 0.5) * ps;
                          const double dx = cx - t.x(), dy = cy - t.y();
                          if (dx * dx + dy * dy > range * range) continue;
                          // The pillar's axis in the sensor frame: base + up * z.
                          const Eigen::Vector3d base = Rt * Eigen::Vector3d(dx, dy, -t.z());
                          seeThroughPillar(it->second, base, up, img, margin);
                      }
              });
}

void PillarGrid::seeThroughPillar(Pillar& pil, const Eigen::Vector3d& base,
                                  const Eigen::Vector3d& up, const std::vector<float>& img,
                                  double margin) const
{
    const double res = params_.height_resolution;
    bool changed = false;
    for (Interval& iv : pil.intervals)
    {
        // The beams in the pillar centre's direction between the interval's bottom and top:
        // one that returned beyond it (by more than the margin) passed through it; one that
        // returned near it vetoes (something is there).
        const Eigen::Vector3d lo = base + up * (iv.lo * res);
        const double hi_z = base.z() + up.z() * (iv.hi * res);
        const double d = std::sqrt(lo.x() * lo.x() + lo.y() * lo.y());
        if (d == 0.0) continue;
        const double paz = pseudoAzimuth(lo.x(), lo.y());
        const int k0 = imageCell(paz, std::max(lo.z() / d, kTanMin));
        const int k1 = imageCell(paz, std::min(hi_z / d, kTanMax - 1e-12));
        if (k0 < 0 || k1 < 0) continue;
        bool through = false, veto = false;
        for (int k = k0; k <= k1 && !veto; k += kImageCols)
        {
            const float r = img[static_cast<std::size_t>(k)];
            if (!std::isfinite(r)) continue;  // no return: no evidence
            const double tan_el = kTanMin + (k / kImageCols + 0.5) * kTanRes;
            const double dist = d * std::sqrt(1.0 + tan_el * tan_el);  // to the pillar's axis
            if (r > dist + margin)
                through = true;
            else if (r > dist - margin)
                veto = true;
            // else: occluded by something closer, no evidence
        }
        if (through && !veto)
        {
            iv.logodds = model_.clamp(iv.logodds + model_.miss);  // Eq. 13
            changed = true;
        }
    }
    if (changed)
        pil.intervals.resize(joinEqualNeighbours(pil.intervals.data(), pil.intervals.size()));
}

namespace
{
/** What pass 1 of bucketScan() found in one chunk of input points. */
struct ChunkSummary
{
    std::size_t valid = 0;  ///< valid points, repeats included
    std::size_t kept = 0;   ///< valid points that are not repeats
    int32_t m_min = std::numeric_limits<int32_t>::max();
    int32_t m_max = std::numeric_limits<int32_t>::min();
    int32_t n_min = std::numeric_limits<int32_t>::max();
    int32_t n_max = std::numeric_limits<int32_t>::min();
    double top_slope_sq = -std::numeric_limits<double>::infinity();  ///< see ScanPillars
};

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

/** Pass 1 of bucketScan() over input points [i0, i1): transform, quantize (Eq. 1, as
 *  quantize() without std::optional) and write the valid points that are not repeats to
 *  m/n/z[i0...] (and their input index to src), with their bounding box and the top beam's
 *  elevation. Four points at a time with AVX when the CPU has it (chosen at run time; the
 *  same operations in the same order, without fused multiply-add, so the same bits), one at a
 *  time otherwise and for the last 1-3 points of a chunk. */
struct QuantizeChunk
{
    double r00, r01, r02, r10, r11, r12, r20, r21, r22;
    double tx, ty, tz;
    double ox, oy, inv_xy, inv_z;

    QuantizeChunk(const Eigen::Matrix3d& R, const Eigen::Vector3d& t, const Params& p)
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
          inv_z(1.0 / p.height_resolution)
    {
    }

    static constexpr double kMinR2 = kMinRangeForElevation * kMinRangeForElevation;

    /** Points [i, i1), one at a time. */
    template <bool kKeepIndex>
    void runScalar(const PointsView& pts, std::size_t i, std::size_t i1, int32_t* m_out,
                   int32_t* n_out, int32_t* z_out, uint32_t* src_out, uint8_t* repeats,
                   PassState& st) const
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
            ++st.valid;
            st.m_lo = std::min(st.m_lo, fm);
            st.m_hi = std::max(st.m_hi, fm);
            st.n_lo = std::min(st.n_lo, fn);
            st.n_hi = std::max(st.n_hi, fn);
            const double r2 = sx * sx + sy * sy;
            if (r2 > kMinR2) st.top = std::max(st.top, sz * std::abs(sz) / r2);
            const bool repeat = st.have_prev && m == st.prev_m && n == st.prev_n && zc == st.prev_z;
            if constexpr (kKeepIndex) repeats[i] = repeat;
            st.have_prev = true;
            st.prev_m = m;
            st.prev_n = n;
            st.prev_z = zc;
            if (repeat) continue;
            m_out[st.v] = m;
            n_out[st.v] = n;
            z_out[st.v] = zc;
            if constexpr (kKeepIndex) src_out[st.v] = static_cast<uint32_t>(i);
            ++st.v;
        }
    }

#if HIF_X86_AVX
    /** Points [i0, i1) in groups of four; returns where it stopped (fewer than four left).
     *  Repeats are found by comparing each lane with the one before it, and the kept lanes
     *  are packed with one shuffle, without a branch per point. */
    template <bool kKeepIndex>
    __attribute__((target("avx"))) std::size_t runAvx(const PointsView& pts, std::size_t i0,
                                                      std::size_t i1, int32_t* m_out,
                                                      int32_t* n_out, int32_t* z_out,
                                                      uint32_t* src_out, uint8_t* repeats,
                                                      PassState& st) const
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
        unsigned prev_ok = st.have_prev ? 1u : 0u;
        std::size_t v = st.v, valid = 0, j = i0;
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
            const __m256d okm =
                _mm256_and_pd(_mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(fm, lo, _CMP_GE_OQ),
                                                          _mm256_cmp_pd(fm, hi, _CMP_LT_OQ)),
                                            _mm256_and_pd(_mm256_cmp_pd(fn, lo, _CMP_GE_OQ),
                                                          _mm256_cmp_pd(fn, hi, _CMP_LT_OQ))),
                              _mm256_and_pd(_mm256_cmp_pd(fz, lo, _CMP_GE_OQ),
                                            _mm256_cmp_pd(fz, hi, _CMP_LT_OQ)));
            // Invalid lanes become 0 before the conversion.
            const __m128i m = _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_and_pd(fm, okm)));
            const __m128i n = _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_and_pd(fn, okm)));
            const __m128i z = _mm256_cvttpd_epi32(_mm256_floor_pd(_mm256_and_pd(fz, okm)));
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
        st.have_prev = prev_ok != 0;
        st.prev_m = _mm_extract_epi32(prev_m, 3);
        st.prev_n = _mm_extract_epi32(prev_n, 3);
        st.prev_z = _mm_extract_epi32(prev_z, 3);
        return j;
    }
#endif

    template <bool kKeepIndex>
    ChunkSummary run(const PointsView& pts, std::size_t i0, std::size_t i1, int32_t* m_out,
                     int32_t* n_out, int32_t* z_out, uint32_t* src_out, uint8_t* repeats) const
    {
        PassState st;
        st.v = i0;
        std::size_t i = i0;
#if HIF_X86_AVX
        if (cpuHasAvx())
            i = runAvx<kKeepIndex>(pts, i0, i1, m_out, n_out, z_out, src_out, repeats, st);
#endif
        runScalar<kKeepIndex>(pts, i, i1, m_out, n_out, z_out, src_out, repeats, st);
        ChunkSummary ch;
        ch.valid = st.valid;
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

void PillarGrid::bucketScan(const PointsView& pts, const Eigen::Isometry3d& T, ScanPillars& out,
                            bool keep_index) const
{
    const Eigen::Matrix3d R = T.linear();
    const Eigen::Vector3d t = T.translation();
    out.sensor = t;
    out.top_slope_sq = -std::numeric_limits<double>::infinity();
    out.tmp_m.resize(pts.size);
    out.tmp_n.resize(pts.size);
    out.tmp_z.resize(pts.size);
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
    const QuantizeChunk quant{R, t, params_};
    const std::size_t n_chunks = (pts.size + kChunk - 1) / kChunk;
    std::array<ChunkSummary, 64> small_chunks;  // up to 1M points without allocation
    std::vector<ChunkSummary> big_chunks(n_chunks > small_chunks.size() ? n_chunks : 0);
    ChunkSummary* chunks = big_chunks.empty() ? small_chunks.data() : big_chunks.data();
    forRanges(n_chunks, 1,
              [&](std::size_t c0, std::size_t c1)
              {
                  for (std::size_t c = c0; c < c1; ++c)
                  {
                      const std::size_t i0 = c * kChunk, i1 = std::min(pts.size, i0 + kChunk);
                      chunks[c] =
                          keep_index
                              ? quant.run<true>(pts, i0, i1, out.tmp_m.data(), out.tmp_n.data(),
                                                out.tmp_z.data(), out.tmp_src.data(),
                                                out.repeats.data())
                              : quant.run<false>(pts, i0, i1, out.tmp_m.data(), out.tmp_n.data(),
                                                 out.tmp_z.data(), nullptr, nullptr);
                  }
              });
    int32_t m_min = std::numeric_limits<int32_t>::max(),
            m_max = std::numeric_limits<int32_t>::min();
    int32_t n_min = m_min, n_max = m_max;
    std::size_t v = 0, valid = 0;
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
        }
        v += ch.kept;
        valid += ch.valid;
        m_min = std::min(m_min, ch.m_min);
        m_max = std::max(m_max, ch.m_max);
        n_min = std::min(n_min, ch.n_min);
        n_max = std::max(n_max, ch.n_max);
        out.top_slope_sq = std::max(out.top_slope_sq, ch.top_slope_sq);
    }
    out.points_valid = valid;
    out.points_invalid = pts.size - valid;
    out.keys.clear();
    out.offsets.clear();
    out.cells.resize(v);
    out.index.resize(keep_index ? v : 0);
    if (v == 0)
    {
        out.offsets.push_back(0);
        return;
    }

    // Pass 2: group by pillar. Counting sort over the scan's bounding box of pillars when it
    // is small (always, for a LiDAR scan at 1 m pillars); else a comparison sort.
    const int64_t width = int64_t{m_max} - m_min + 1, height = int64_t{n_max} - n_min + 1;
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
            const auto b = static_cast<uint32_t>(int64_t{out.tmp_m[k] - m_min} * height +
                                                 (out.tmp_n[k] - n_min));
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
                packKey({static_cast<int32_t>(m_min + static_cast<int64_t>(b) / height),
                         static_cast<int32_t>(n_min + static_cast<int64_t>(b) % height)}));
            out.offsets.push_back(sum);
            sum += c;
        }
        out.offsets.push_back(sum);
        for (std::size_t k = 0; k < v; ++k)
        {
            const uint32_t slot = counts[bin[k]]++;
            out.cells[slot] = out.tmp_z[k];
            if (keep_index) out.index[slot] = out.tmp_src[k];
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
        }
        out.offsets.push_back(static_cast<uint32_t>(v));
    }
}

void PillarGrid::buildIntervals(ScanPillars& scan) const
{
    const std::size_t np = scan.pillarCount();
    scan.ceilings.resize(np);
    scan.span_counts.resize(np);
    scan.spans.resize(scan.entryCount());
    const double res = params_.height_resolution;
    const double inv_res = 1.0 / res;
    const double beam_slope = std::tan(params_.beam_spacing_deg * M_PI / 180.0);
    const bool need_ceiling = (params_.high_height_preservation || params_.unseen_height_prior) &&
                              std::isfinite(scan.top_slope_sq);
    // tan(top beam elevation) from its signed square.
    const double top_slope =
        need_ceiling ? std::copysign(std::sqrt(std::abs(scan.top_slope_sq)), scan.top_slope_sq)
                     : 0.0;
    const Eigen::Vector3d& t = scan.sensor;
    forRanges(np, 256,
              [&](std::size_t p0, std::size_t p1)
              {
                  for (std::size_t p = p0; p < p1; ++p)
                  {
                      const uint32_t b = scan.offsets[p], e = scan.offsets[p + 1];
                      int32_t* cells = scan.cells.data() + b;
                      const std::size_t distinct = sortDistinct(cells, e - b);

                      // Horizontal distance from the sensor to the pillar's centre.
                      const PillarIndex idx = unpackKey(scan.keys[p]);
                      const double cx = params_.origin_x + (idx.m + 0.5) * params_.pillar_size;
                      const double cy = params_.origin_y + (idx.n + 0.5) * params_.pillar_size;
                      const double dx = cx - t.x(), dy = cy - t.y();
                      const double d = std::sqrt(dx * dx + dy * dy);
                      const double beam_gap = d * beam_slope;  // vertical beam spacing at d
                      const int32_t gap_cells =
                          floorCells(std::max(params_.merge_gap, beam_gap) * inv_res + 1e-9);
                      const int32_t pad_cells = ceilCells(
                          std::max(params_.interval_padding, 0.5 * beam_gap) * inv_res - 1e-9);
                      scan.span_counts[p] = static_cast<uint32_t>(
                          buildSpans(cells, distinct, gap_cells, pad_cells, scan.spans.data() + b));

                      int32_t ceiling = kAllHeights;
                      if (need_ceiling)
                      {
                          const double top = (t.z() + d * top_slope) / res;
                          if (top < static_cast<double>(kAllHeights))
                              ceiling = static_cast<int32_t>(std::max<double>(
                                  std::ceil(top), std::numeric_limits<int32_t>::min() + 1.0));
                      }
                      scan.ceilings[p] = ceiling;
                  }
              });
}

InsertStats PillarGrid::mergeScan(const ScanPillars& scan)
{
    InsertStats st;
    st.points_used = scan.points_valid;
    st.points_invalid = scan.points_invalid;
    const std::size_t np = scan.pillarCount();

    // Pillars already in the map are found and updated in parallel (finds are read-only and
    // pillars independent); the new ones are then created and updated in scan order.
    targets_.resize(np);
    const std::size_t cap = params_.max_intervals_per_pillar;
    // A software pipeline, as the table and the intervals are far bigger than the cache: the
    // slot of pillar p + 2D is prefetched, pillar p + D is found and its intervals prefetched,
    // pillar p is updated.
    constexpr std::size_t kAhead = 8;  // D
    auto updateExisting = [&](std::size_t p0, std::size_t p1, std::vector<Interval>& scratch)
    {
        auto find = [&](std::size_t p)
        {
            const auto it = pillars_.find(scan.keys[p]);
            targets_[p] = it == pillars_.end() ? nullptr : &it->second;
            if (targets_[p]) __builtin_prefetch(targets_[p]->intervals.data());
        };
        for (std::size_t p = p0; p < std::min(p1, p0 + 2 * kAhead); ++p)
            pillars_.prefetch(scan.keys[p]);
        for (std::size_t p = p0; p < std::min(p1, p0 + kAhead); ++p) find(p);
        for (std::size_t p = p0; p < p1; ++p)
        {
            if (p + 2 * kAhead < p1) pillars_.prefetch(scan.keys[p + 2 * kAhead]);
            if (p + kAhead < p1) find(p + kAhead);
            if (targets_[p])
                updatePillar(*targets_[p], scan.spans.data() + scan.offsets[p], scan.span_counts[p],
                             model_, cap, scratch, scan.ceilings[p]);
        }
    };
    if (threads_ <= 1)
        updateExisting(0, np, scratch_);
    else
        forRanges(np, 256,
                  [&](std::size_t p0, std::size_t p1)
                  {
                      std::vector<Interval> scratch;
                      updateExisting(p0, p1, scratch);
                  });
    for (std::size_t p = 0; p < np; ++p)
    {
        if (targets_[p]) continue;
        // A new pillar is an empty one with the prior p_empty: the general update then gives
        // its intervals Bayesfilter(p_empty_init, alpha, beta) (Eq. 14).
        Pillar& pil = pillars_[scan.keys[p]];
        pil.logodds_empty = model_.clamp(model_.empty_init);
        ++st.pillars_created;
        updatePillar(pil, scan.spans.data() + scan.offsets[p], scan.span_counts[p], model_, cap,
                     scratch_, scan.ceilings[p]);
    }
    st.pillars_updated = np - st.pillars_created;
    return st;
}

double PillarGrid::logOddsAt(double x, double y, double z) const
{
    const auto idx = pillarOf(x, y);
    const auto zc = heightCellOf(z);
    const Pillar* p = idx && zc ? findPillar(*idx) : nullptr;
    if (!p) return logit(params_.p_empty_init);
    if (const Interval* iv = findInterval(*p, *zc)) return iv->logodds;
    return p->logodds_empty;
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
    return logOddsAt(x, y, z) >= static_logodds_;
}

ClassifyStats PillarGrid::classify(const PointsView& pts, std::vector<uint8_t>& is_dynamic,
                                   const Eigen::Isometry3d& T) const
{
    // Reused by later calls on this thread. Worker threads must use this thread's object, so
    // the lambda below captures a reference, never the thread_local name.
    thread_local ScanPillars scan_buffer;
    ScanPillars& scan = scan_buffer;
    bucketScan(pts, T, scan, true);
    constexpr uint8_t kUnset = 2;
    is_dynamic.assign(pts.size, kUnset);

    const bool prior_static = logit(params_.p_empty_init) >= static_logodds_;
    std::atomic<std::size_t> n_static{0};
    forRanges(scan.pillarCount(), 256,
              [&](std::size_t p0, std::size_t p1)
              {
                  std::size_t local_static = 0;
                  for (std::size_t p = p0; p < p1; ++p)
                  {
                      const uint32_t b = scan.offsets[p], e = scan.offsets[p + 1];
                      const Pillar* pil = findPillar(unpackKey(scan.keys[p]));
                      for (uint32_t k = b; k < e; ++k)
                      {
                          bool stat = prior_static;
                          if (pil)
                          {
                              const Interval* iv = findInterval(*pil, scan.cells[k]);
                              stat = (iv ? iv->logodds : pil->logodds_empty) >= static_logodds_;
                          }
                          is_dynamic[scan.index[k]] = stat ? 0 : 1;
                          local_static += stat;
                      }
                  }
                  n_static += local_static;
              });
    ClassifyStats st;
    st.static_points = n_static;
    // A repeat has the pillar and height cell of the point before it, hence its class.
    for (std::size_t i = 1; i < pts.size; ++i)
        if (scan.repeats[i])
        {
            is_dynamic[i] = is_dynamic[i - 1];
            st.static_points += is_dynamic[i] == 0;
        }
    // Points that bucketScan() skipped: non-finite ones are invalid (dynamic); finite ones
    // beyond the int32 index range lie in unknown space, which has the prior.
    if (scan.points_invalid > 0)
        for (std::size_t i = 0; i < pts.size; ++i)
        {
            if (is_dynamic[i] != kUnset) continue;
            const bool finite =
                std::isfinite(pts.x[i]) && std::isfinite(pts.y[i]) && std::isfinite(pts.z[i]);
            st.invalid_points += !finite;
            const bool stat = finite && prior_static;
            is_dynamic[i] = stat ? 0 : 1;
            st.static_points += stat;
        }
    st.dynamic_points = pts.size - st.static_points;
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

std::size_t PillarGrid::memoryBytes() const
{
    // absl's flat table: one slot and one control byte per bucket (plus a group of control
    // bytes); the intervals live in each pillar's own vector.
    std::size_t bytes = pillars_.capacity() * (sizeof(std::pair<const uint64_t, Pillar>) + 1) + 16;
    for (const auto& kv : pillars_) bytes += kv.second.intervals.capacity() * sizeof(Interval);
    return bytes;
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
