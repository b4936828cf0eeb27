// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   TopView.cpp
 * @brief  The bird's-eye picture: tiles of cells where points fell, the main area, drawn with
 *         OpenCV.
 */
#include "hif/apps/TopView.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <unordered_map>

namespace hif::apps
{
namespace
{
constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
// BGR
const cv::Scalar kBackground(24, 24, 24);
const cv::Scalar kText(235, 235, 235);

const char* const kName[5] = {"kept", "removed", "moving, missed (kept)", "static, wrongly removed",
                              "unlabelled, removed (not scored)"};

cv::Scalar bgr(int outcome)
{
    const uint8_t* c = TopView::kRgb[outcome];
    return {double(c[2]), double(c[1]), double(c[0])};
}

/** 1, 2 or 5 times a power of ten, about a fifth of `span`. */
double niceLength(double span)
{
    const double target = span / 5.0;
    const double p = std::pow(10.0, std::floor(std::log10(target)));
    for (const double m : {5.0, 2.0, 1.0})
        if (m * p <= target) return m * p;
    return p;
}

uint64_t packBlock(int64_t bx, int64_t by)
{
    return (static_cast<uint64_t>(static_cast<uint32_t>(bx)) << 32) |
           static_cast<uint64_t>(static_cast<uint32_t>(by));
}
}  // namespace

std::vector<bool> mainArea(const std::vector<WeightedBlock>& blocks, int64_t reach)
{
    std::unordered_map<uint64_t, std::size_t> at;
    at.reserve(blocks.size());
    for (std::size_t k = 0; k < blocks.size(); ++k)
        at.emplace(packBlock(blocks[k].bx, blocks[k].by), k);
    std::vector<int> group(blocks.size(), -1);
    std::vector<std::size_t> weight;
    std::deque<std::size_t> queue;
    for (std::size_t k = 0; k < blocks.size(); ++k)
    {
        if (group[k] >= 0) continue;
        const int g = static_cast<int>(weight.size());
        weight.push_back(0);
        group[k] = g;
        queue.push_back(k);
        while (!queue.empty())
        {
            const WeightedBlock& b = blocks[queue.front()];
            queue.pop_front();
            weight[static_cast<std::size_t>(g)] += b.weight;
            for (int64_t dy = -reach; dy <= reach; ++dy)
                for (int64_t dx = -reach; dx <= reach; ++dx)
                {
                    const auto it = at.find(packBlock(b.bx + dx, b.by + dy));
                    if (it == at.end() || group[it->second] >= 0) continue;
                    group[it->second] = g;
                    queue.push_back(it->second);
                }
        }
    }
    const auto main = std::max_element(weight.begin(), weight.end()) - weight.begin();
    std::vector<bool> in(blocks.size());
    for (std::size_t k = 0; k < blocks.size(); ++k) in[k] = group[k] == main;
    return in;
}

TopView::TopView(double resolution, std::size_t max_cells)
    : res_(resolution), inv_res_(1.0 / resolution), max_cells_(max_cells)
{
    if (!(resolution > 0)) throw std::invalid_argument("TopView: resolution must be > 0");
}

void TopView::cover(double x0, double y0, double x1, double y1, int pixels)
{
    if (!(x0 < x1 && y0 < y1) || pixels <= 0 || !tiles_.empty() || far_ > 0) return;
    res_ = std::max(0.05, std::ceil(std::max(x1 - x0, y1 - y0) / pixels * 100.0) / 100.0);
    inv_res_ = 1.0 / res_;
}

void TopView::addToTile(double fx, double fy, float z, Outcome outcome)
{
    if (!(fx > -kMaxCell && fx < kMaxCell && fy > -kMaxCell && fy < kMaxCell))
    {
        far_ += (fx == fx && fy == fy) ? 1 : 0;  // NaN: not a point, not counted
        return;
    }
    const auto cx = static_cast<int64_t>(std::floor(fx)), cy = static_cast<int64_t>(std::floor(fy));
    Tile* t = findOrAdd(cx >> kTileBits, cy >> kTileBits);
    if (t == nullptr)  // the cells grew: again, at their new size
    {
        addToTile(fx * 0.5, fy * 0.5, z, outcome);
        return;
    }
    mark(*t, static_cast<std::size_t>(((cy & kTileMask) << kTileBits) | (cx & kTileMask)), z,
         outcome);
}

TopView::Tile* TopView::findOrAdd(int64_t tx, int64_t ty)
{
    const uint64_t key = packBlock(tx, ty);
    const auto it = index_.find(key);
    if (it != index_.end()) return setLast(&tiles_[it->second]);
    if ((tiles_.size() + 1) * kTileCells > max_cells_ && !tiles_.empty())
    {
        coarsen();
        return nullptr;  // the caller's cell is another one now
    }
    Tile t;
    t.tx = tx;
    t.ty = ty;
    t.top.assign(kTileCells, kNone);
    t.marks.assign(kTileCells, 0);
    index_.emplace(key, tiles_.size());
    tiles_.push_back(std::move(t));
    return setLast(&tiles_.back());
}

void TopView::coarsen()
{
    std::vector<Tile> old = std::move(tiles_);
    tiles_.clear();
    index_.clear();
    setLast(nullptr);
    res_ *= 2;
    inv_res_ = 1.0 / res_;
    const std::size_t max_cells = max_cells_;
    max_cells_ = std::numeric_limits<std::size_t>::max();  // the merge never coarsens again
    for (const Tile& o : old)
    {
        // Cell (cx, cy) becomes (cx >> 1, cy >> 1); a tile's cells all land in one new tile.
        Tile& t = *findOrAdd(o.tx >> 1, o.ty >> 1);
        t.points += o.points;
        for (int64_t ly = 0; ly < kTileSide; ++ly)
            for (int64_t lx = 0; lx < kTileSide; ++lx)
            {
                const auto i = static_cast<std::size_t>((ly << kTileBits) | lx);
                if (std::isnan(o.top[i]) && o.marks[i] == 0) continue;
                const int64_t cx = (o.tx * kTileSide + lx) >> 1;
                const int64_t cy = (o.ty * kTileSide + ly) >> 1;
                const auto j =
                    static_cast<std::size_t>(((cy & kTileMask) << kTileBits) | (cx & kTileMask));
                if (!std::isnan(o.top[i]) && !(o.top[i] <= t.top[j])) t.top[j] = o.top[i];
                t.marks[j] |= o.marks[i];
            }
    }
    max_cells_ = max_cells;
    if (tiles_.size() * kTileCells > max_cells_) coarsen();
}

template <typename Fn>
void TopView::forEachCell(const std::vector<bool>& in, Fn&& fn) const
{
    for (std::size_t k = 0; k < tiles_.size(); ++k)
    {
        if (!in[k]) continue;
        const Tile& t = tiles_[k];
        for (int64_t ly = 0; ly < kTileSide; ++ly)
            for (int64_t lx = 0; lx < kTileSide; ++lx)
            {
                const auto i = static_cast<std::size_t>((ly << kTileBits) | lx);
                if (std::isnan(t.top[i]) && t.marks[i] == 0) continue;
                fn(t, i, t.tx * kTileSide + lx, t.ty * kTileSide + ly);
            }
    }
}

TopView::Picture TopView::write(const std::string& file, const std::string& title, bool with_truth,
                                int min_width) const
{
    Picture pic;
    pic.points = far_;
    for (const Tile& t : tiles_) pic.points += t.points;
    if (tiles_.empty())
        throw std::runtime_error("nothing to draw in '" + file + "': no point was added");

    // The main area: tiles linked within kAreaLinkMetres of one another, the heaviest group.
    std::vector<WeightedBlock> blocks;
    for (const Tile& t : tiles_) blocks.push_back({t.tx, t.ty, t.points});
    const double tile_m = res_ * double(kTileSide);
    const auto reach = static_cast<int64_t>(std::ceil(kAreaLinkMetres / tile_m));
    const std::vector<bool> in = mainArea(blocks, reach);
    pic.points_outside = far_;
    for (std::size_t k = 0; k < tiles_.size(); ++k)
        if (!in[k]) pic.points_outside += tiles_[k].points;

    // The cells that hold something, in the main area.
    int64_t c0 = std::numeric_limits<int64_t>::max(), c1 = std::numeric_limits<int64_t>::min();
    int64_t r0 = c0, r1 = c1;
    forEachCell(in,
                [&](const Tile&, std::size_t, int64_t cx, int64_t cy)
                {
                    c0 = std::min(c0, cx);
                    c1 = std::max(c1, cx + 1);
                    r0 = std::min(r0, cy);
                    r1 = std::max(r1, cy + 1);
                });
    // At most kMaxSide cells a side, and 2^24 in all: a larger area is drawn coarser (each
    // picture cell the highest kept point and every outcome of the f x f cells it covers).
    int64_t f = 1;
    const auto cells = [&](int64_t span, int64_t k) { return (span + k - 1) / k; };
    while (cells(c1 - c0, f) > kMaxSide || cells(r1 - r0, f) > kMaxSide ||
           cells(c1 - c0, f) * cells(r1 - r0, f) > (int64_t{1} << 24))
        ++f;
    const int w = int(cells(c1 - c0, f)), h = int(cells(r1 - r0, f));
    std::vector<float> top(std::size_t(w) * std::size_t(h), kNone);
    std::vector<uint8_t> marks(top.size(), 0);
    forEachCell(in,
                [&](const Tile& t, std::size_t i, int64_t cx, int64_t cy)
                {
                    const auto j =
                        std::size_t((cy - r0) / f) * std::size_t(w) + std::size_t((cx - c0) / f);
                    if (!std::isnan(t.top[i]) && !(t.top[i] <= top[j])) top[j] = t.top[i];
                    marks[j] |= t.marks[i];
                });
    std::vector<float> tops;
    for (const float z : top)
        if (!std::isnan(z)) tops.push_back(z);
    // Grey from the 2nd to the 98th percentile of the heights.
    float zlo = 0, zhi = 1;
    if (!tops.empty())
    {
        const auto at = [&tops](std::size_t percent)
        {
            const auto k = tops.begin() + std::ptrdiff_t(tops.size() * percent / 100);
            std::nth_element(tops.begin(), k, tops.end());
            return *k;
        };
        zlo = at(2);
        zhi = std::max(at(98), zlo + 0.1f);
    }
    // At least min_width wide (never more than kMaxSide), whole pixels per cell, drawn straight
    // into the picture below a title band; a cell with a removed (or missed, or wrongly
    // removed) point shows that, over the grey. The canvas holds the legend whatever the map's
    // shape.
    const int scale = std::max(1, std::min((min_width + w - 1) / w, kMaxSide / std::max(w, h)));
    const int band = 40;
    const int n = with_truth ? 5 : 2;
    const cv::Rect legend(10, band + 10, 420, 30 + 26 * n);
    const int canvas_w = std::max(w * scale, legend.x + legend.width + 10);
    const int canvas_h = std::max(h * scale + band, legend.y + legend.height + 60);
    cv::Mat out(canvas_h, canvas_w, CV_8UC3, kBackground);
    cv::Mat map = out(cv::Rect(0, band, w * scale, h * scale));
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
        {
            const float z = top[std::size_t(r) * std::size_t(w) + std::size_t(c)];
            if (std::isnan(z)) continue;
            const double t = std::clamp((z - zlo) / (zhi - zlo), 0.0f, 1.0f);
            const auto g = static_cast<uint8_t>(70 + 185 * t);
            const int row = (h - 1 - r) * scale;  // north up
            for (int dy = 0; dy < scale; ++dy)
                for (int dx = 0; dx < scale; ++dx)
                    map.at<cv::Vec3b>(row + dy, c * scale + dx) = {g, g, g};
        }
    // Unlabelled points first: a cell that also holds a scored outcome shows that one.
    for (const int k : {4, 1, 2, 3})
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c)
                if (marks[std::size_t(r) * std::size_t(w) + std::size_t(c)] & (1u << k))
                {
                    const int row = (h - 1 - r) * scale;
                    const cv::Rect px =
                        cv::Rect(c * scale, row, scale, scale) & cv::Rect(0, 0, map.cols, map.rows);
                    map(px).setTo(bgr(k));
                }
    // Title above, legend and scale bar over the map.
    const auto font = cv::FONT_HERSHEY_SIMPLEX;
    cv::putText(out, title, {12, 27}, font, 0.7, kText, 1, cv::LINE_AA);
    out(legend) *= 0.35;
    char heights[96];
    std::snprintf(heights, sizeof heights, "kept: grey by height, %.1f m (dark) to %.1f m",
                  double(zlo), double(zhi));
    for (int k = 0; k < n; ++k)
    {
        const int y = legend.y + 24 + 26 * k;
        const cv::Scalar col = bgr(k);
        cv::rectangle(out, cv::Rect(legend.x + 10, y - 13, 16, 16), col, cv::FILLED);
        cv::putText(out, k == 0 ? heights : kName[k], {legend.x + 36, y}, font, 0.5, kText, 1,
                    cv::LINE_AA);
    }
    pic.cell_metres = res_ * double(f);
    const double m_per_px = pic.cell_metres / scale;
    const double len = niceLength(map.cols * m_per_px);
    const int px = int(std::lround(len / m_per_px));
    const cv::Point a(20, out.rows - 25), b(20 + px, out.rows - 25);
    cv::line(out, a, b, kText, 3);
    cv::line(out, a + cv::Point(0, -6), a + cv::Point(0, 6), kText, 2);
    cv::line(out, b + cv::Point(0, -6), b + cv::Point(0, 6), kText, 2);
    char label[32];
    std::snprintf(label, sizeof label, "%g m", len);
    cv::putText(out, label, {20 + px + 10, out.rows - 19}, font, 0.6, kText, 1, cv::LINE_AA);
    if (!cv::imwrite(file, out,
                     {cv::IMWRITE_PNG_COMPRESSION, 1, cv::IMWRITE_PNG_STRATEGY,
                      cv::IMWRITE_PNG_STRATEGY_RLE}))
        throw std::runtime_error("cannot write '" + file + "'");
    pic.width = out.cols;
    pic.height = out.rows;
    return pic;
}

}  // namespace hif::apps
