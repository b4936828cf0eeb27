// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   TopView.h
 * @brief  A bird's-eye picture of a cleaned map (OpenCV): kept points in grey by height, removed
 *         points in red and, with ground truth, missed moving points and wrongly removed static
 *         ones in their own colours; a legend and a scale bar.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hif::apps
{
class TopView
{
public:
    /** What became of a point. */
    enum Outcome : uint8_t
    {
        kKept = 0,            ///< kept (static, or not known)
        kRemoved = 1,         ///< removed (moving, or not known)
        kMissedMoving = 2,    ///< a moving point that was kept (ground truth given)
        kWronglyRemoved = 3,  ///< a static point that was removed (ground truth given)
    };

    /** The colour of each outcome (red, green, blue), as the picture's legend shows it (kept
     *  points are drawn in grey by height there, light grey elsewhere). */
    static constexpr uint8_t kRgb[4][3] = {
        {200, 200, 200}, {230, 40, 40}, {255, 215, 0}, {0, 160, 255}};

    /** Cells of `resolution` metres; coarser (twice, as often as needed) when the area would
     *  need more than `max_cells`. */
    explicit TopView(double resolution = 0.2, std::size_t max_cells = std::size_t{1} << 23);

    /** Makes room for [x0, x1) x [y0, y1) at once (the extent of a map known beforehand), so
     *  that the cells are not grown point by point. Before any point, it also sets the cells'
     *  size so that the longer side spans about `pixels` cells (5 cm at the finest): the
     *  picture then needs no scaling up. */
    void cover(double x0, double y0, double x1, double y1, int pixels = 1300);

    void add(float x, float y, float z, Outcome outcome)
    {
        if (!(x >= x0_ && x < x1_ && y >= y0_ && y < y1_)) grow(x, y);
        if (!(x >= x0_ && x < x1_ && y >= y0_ && y < y1_)) return;  // not finite
        const auto c = static_cast<std::size_t>((x - x0_) * inv_res_);
        const auto r = static_cast<std::size_t>((y - y0_) * inv_res_);
        const std::size_t i = r * cols_ + c;
        if (outcome == kKept)
        {
            if (!(z <= top_[i])) top_[i] = z;  // top_ starts NaN
        }
        else
            marks_[i] |= static_cast<uint8_t>(1u << outcome);
        any_ = true;
    }

    /** Writes the picture (PNG) of what was added, at least `min_width` pixels wide, with
     *  `title` above; `with_truth` puts the two ground-truth outcomes in the legend. Returns
     *  {width, height}. Throws std::runtime_error naming the file when nothing was added or it
     *  cannot be written. */
    std::pair<int, int> write(const std::string& file, const std::string& title, bool with_truth,
                              int min_width = 1200) const;

    [[nodiscard]] double resolution() const { return res_; }

private:
    void grow(float x, float y);
    /** The cells cover [x0, x1) x [y0, y1), coarser (twice, as often as needed) if that would
     *  take more than max_cells_, edges on multiples of the cell size. */
    void resizeTo(double x0, double y0, double x1, double y1);
    void rebuild(double x0, double y0, std::size_t cols, std::size_t rows, double res);

    double res_, inv_res_;
    std::size_t max_cells_;
    double x0_ = 0, y0_ = 0, x1_ = 0, y1_ = 0;  ///< the cells cover [x0, x1) x [y0, y1)
    std::size_t cols_ = 0, rows_ = 0;
    std::vector<float> top_;      ///< highest kept point of each cell, NaN for none
    std::vector<uint8_t> marks_;  ///< bit per outcome other than kept
    bool any_ = false;
};

}  // namespace hif::apps
