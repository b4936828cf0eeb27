// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   TopView.cpp
 * @brief  The bird's-eye picture: a growing grid of cells, drawn with OpenCV.
 */
#include "hif/apps/TopView.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace hif::apps
{
namespace
{
constexpr float kNone = std::numeric_limits<float>::quiet_NaN();
// BGR
const cv::Scalar kBackground(24, 24, 24);
const cv::Scalar kText(235, 235, 235);

const char* const kName[4] = {"kept", "removed", "moving, missed (kept)",
                              "static, wrongly removed"};

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
}  // namespace

TopView::TopView(double resolution, std::size_t max_cells)
    : res_(resolution), inv_res_(1.0 / resolution), max_cells_(max_cells)
{
    if (!(resolution > 0)) throw std::invalid_argument("TopView: resolution must be > 0");
}

void TopView::rebuild(double x0, double y0, std::size_t cols, std::size_t rows, double res)
{
    std::vector<float> top(cols * rows, kNone);
    std::vector<uint8_t> marks(cols * rows, 0);
    for (std::size_t r = 0; r < rows_; ++r)
        for (std::size_t c = 0; c < cols_; ++c)
        {
            const std::size_t i = r * cols_ + c;
            if (std::isnan(top_[i]) && marks_[i] == 0) continue;
            const double x = x0_ + (double(c) + 0.5) * res_, y = y0_ + (double(r) + 0.5) * res_;
            const auto nc = static_cast<std::size_t>((x - x0) / res);
            const auto nr = static_cast<std::size_t>((y - y0) / res);
            const std::size_t j = nr * cols + nc;
            if (!std::isnan(top_[i]) && !(top_[i] <= top[j])) top[j] = top_[i];
            marks[j] |= marks_[i];
        }
    top_ = std::move(top);
    marks_ = std::move(marks);
    x0_ = x0;
    y0_ = y0;
    cols_ = cols;
    rows_ = rows;
    res_ = res;
    inv_res_ = 1.0 / res;
    x1_ = x0_ + double(cols_) * res_;
    y1_ = y0_ + double(rows_) * res_;
}

void TopView::resizeTo(double x0, double y0, double x1, double y1)
{
    double res = res_;
    while (std::ceil((x1 - x0) / res) * std::ceil((y1 - y0) / res) > double(max_cells_)) res *= 2;
    // Cell edges stay on multiples of the resolution.
    x0 = std::floor(x0 / res) * res;
    y0 = std::floor(y0 / res) * res;
    rebuild(x0, y0, static_cast<std::size_t>(std::ceil((x1 - x0) / res)),
            static_cast<std::size_t>(std::ceil((y1 - y0) / res)), res);
}

void TopView::cover(double x0, double y0, double x1, double y1, int pixels)
{
    if (!(x0 < x1 && y0 < y1)) return;
    if (cols_ == 0 && pixels > 0)
    {
        res_ = std::max(0.05, std::ceil(std::max(x1 - x0, y1 - y0) / pixels * 100.0) / 100.0);
        inv_res_ = 1.0 / res_;
    }
    else if (cols_ > 0)
    {
        x0 = std::min(x0, x0_);
        y0 = std::min(y0, y0_);
        x1 = std::max(x1, x1_);
        y1 = std::max(y1, y1_);
    }
    resizeTo(x0, y0, x1, y1);
}

void TopView::grow(float x, float y)
{
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    // The new area holds the old one and the point, with room to spare on the side it grew,
    // so that growing is rare.
    double nx0 = x0_, ny0 = y0_, nx1 = x1_, ny1 = y1_;
    if (cols_ == 0)
    {
        nx0 = x - 32;
        ny0 = y - 32;
        nx1 = x + 32;
        ny1 = y + 32;
    }
    const double w = std::max(nx1 - nx0, 64.0), h = std::max(ny1 - ny0, 64.0);
    if (x < nx0) nx0 = std::min<double>(x, nx0 - w / 2);
    if (x >= nx1) nx1 = std::max<double>(x + res_, nx1 + w / 2);
    if (y < ny0) ny0 = std::min<double>(y, ny0 - h / 2);
    if (y >= ny1) ny1 = std::max<double>(y + res_, ny1 + h / 2);
    resizeTo(nx0, ny0, nx1, ny1);
}

std::pair<int, int> TopView::write(const std::string& file, const std::string& title,
                                   bool with_truth, int min_width) const
{
    if (!any_) throw std::runtime_error("nothing to draw in '" + file + "': no point was added");
    // The cells that hold something.
    std::size_t c0 = cols_, c1 = 0, r0 = rows_, r1 = 0;
    std::vector<float> tops;
    for (std::size_t r = 0; r < rows_; ++r)
        for (std::size_t c = 0; c < cols_; ++c)
        {
            const std::size_t i = r * cols_ + c;
            if (std::isnan(top_[i]) && marks_[i] == 0) continue;
            c0 = std::min(c0, c);
            c1 = std::max(c1, c + 1);
            r0 = std::min(r0, r);
            r1 = std::max(r1, r + 1);
            if (!std::isnan(top_[i])) tops.push_back(top_[i]);
        }
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
    const int w = int(c1 - c0), h = int(r1 - r0);
    // At least min_width wide, whole pixels per cell, drawn straight into the picture below a
    // title band; a cell with a removed (or missed, or wrongly removed) point shows that, over
    // the grey.
    const int scale = std::max(1, (min_width + w - 1) / w);
    const int band = 40;
    cv::Mat out(h * scale + band, w * scale, CV_8UC3, kBackground);
    cv::Mat map = out(cv::Rect(0, band, w * scale, h * scale));
    const auto cell = [&](int r, int c)
    { return (r0 + std::size_t(r)) * cols_ + c0 + std::size_t(c); };
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c)
        {
            const float z = top_[cell(r, c)];
            if (std::isnan(z)) continue;
            const double t = std::clamp((z - zlo) / (zhi - zlo), 0.0f, 1.0f);
            const auto g = static_cast<uint8_t>(70 + 185 * t);
            const int row = (h - 1 - r) * scale;  // north up
            for (int dy = 0; dy < scale; ++dy)
                for (int dx = 0; dx < scale; ++dx)
                    map.at<cv::Vec3b>(row + dy, c * scale + dx) = {g, g, g};
        }
    for (int k = 1; k < 4; ++k)
        for (int r = 0; r < h; ++r)
            for (int c = 0; c < w; ++c)
                if (marks_[cell(r, c)] & (1u << k))
                {
                    const int row = (h - 1 - r) * scale;
                    const cv::Rect px =
                        cv::Rect(c * scale, row, scale, scale) & cv::Rect(0, 0, map.cols, map.rows);
                    map(px).setTo(bgr(k));
                }
    // Title above, legend and scale bar over the map.
    const auto font = cv::FONT_HERSHEY_SIMPLEX;
    cv::putText(out, title, {12, 27}, font, 0.7, kText, 1, cv::LINE_AA);
    const int n = with_truth ? 4 : 2;
    const cv::Rect legend(10, band + 10, 420, 30 + 26 * n);
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
    const double m_per_px = res_ / scale;
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
    return {out.cols, out.rows};
}

}  // namespace hif::apps
