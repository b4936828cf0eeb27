// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap_render.cpp
 * @brief  What the map keeps, as 3D boxes (mrpt::opengl): one per static interval, coloured by
 *         height.
 */
#include <mrpt/img/color_maps.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "hif/CHeightIntervalMap.h"

using namespace hif;

namespace
{
/** The colour of a kept box whose top is at `t` of the height range (0 lowest, 1 highest): blue,
 *  cyan, green, yellow; never red, which the views keep for what is removed. */
mrpt::img::TColor heightColour(double t)
{
    return mrpt::img::colormap(mrpt::img::cmJET,
                               static_cast<float>(0.1 + 0.5 * std::clamp(t, 0.0, 1.0)));
}
}  // namespace

void CHeightIntervalMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const
{
    if (!genericMapParams.enableSaveAs3DObject) return;
    const GridGeometry& g = geometry();
    auto tris = mrpt::opengl::CSetOfTriangles::Create();
    tris->setName("hif::CHeightIntervalMap");
    const double inset = 0.05 * g.pillar_size;  // a small gap shows pillar borders
    // What the map keeps: the static intervals. The others (seen through, or never confirmed)
    // hold the points it removes, or none, and are not drawn.
    std::vector<std::pair<PillarIndex, Interval>> kept;
    for (const auto& [idx, pillar] : grid_.sortedPillars())
        for (const Interval& iv : pillar->intervals)
            if (grid_.isStaticLogOdds(iv.logodds)) kept.emplace_back(idx, iv);
    if (kept.empty())
    {
        o.insert(tris);
        return;
    }
    // Triangles hold float32 vertices, which keep millimetres only below about 8 km: a map in
    // world coordinates (UTM) is drawn from its south-west corner, placed by the object's (double)
    // pose.
    constexpr double kFloatLimit = 8192.0;
    int32_t m0 = kept.front().first.m, m1 = m0, n0 = kept.front().first.n, n1 = n0;
    std::vector<int32_t> tops;
    tops.reserve(kept.size());
    for (const auto& [idx, iv] : kept)
    {
        m0 = std::min(m0, idx.m);
        m1 = std::max(m1, idx.m);
        n0 = std::min(n0, idx.n);
        n1 = std::max(n1, idx.n);
        tops.push_back(iv.hi);
    }
    double ax = 0, ay = 0;
    const double far = std::max({std::abs(g.origin_x + m0 * g.pillar_size),
                                 std::abs(g.origin_x + (m1 + 1.0) * g.pillar_size),
                                 std::abs(g.origin_y + n0 * g.pillar_size),
                                 std::abs(g.origin_y + (n1 + 1.0) * g.pillar_size)});
    if (far >= kFloatLimit)
    {
        ax = g.origin_x + m0 * g.pillar_size;
        ay = g.origin_y + n0 * g.pillar_size;
        tris->setLocation(ax, ay, 0.0);
    }
    // The colours span the tops of the kept boxes from the 2nd to the 98th percentile: a few
    // stray boxes far up or down do not wash out the rest.
    const auto percentile = [&tops](double q)
    {
        const auto it = tops.begin() + static_cast<std::ptrdiff_t>(q * double(tops.size() - 1));
        std::nth_element(tops.begin(), it, tops.end());
        return double(*it);
    };
    const double low = percentile(0.02), high = percentile(0.98);
    const double span = std::max(high - low, 1.0);
    for (const auto& [idx, iv] : kept)
    {
        const float x0 = static_cast<float>(g.origin_x + idx.m * g.pillar_size - ax + inset);
        const float y0 = static_cast<float>(g.origin_y + idx.n * g.pillar_size - ay + inset);
        const float x1 = static_cast<float>(x0 + g.pillar_size - 2 * inset);
        const float y1 = static_cast<float>(y0 + g.pillar_size - 2 * inset);
        const float z0 = static_cast<float>(g.cellBottom(iv.lo));
        const float z1 = static_cast<float>(g.cellBottom(iv.hi));
        const mrpt::img::TColor colour = heightColour((double(iv.hi) - low) / span);
        const mrpt::math::TPoint3D c[8] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0},
                                           {x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}};
        // The top and the four sides: the bottom faces the ground and is hidden from above.
        static const int faces[5][4] = {
            {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
        for (const auto& f : faces)
            for (const auto& tri :
                 {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}})
            {
                mrpt::opengl::TTriangle t3(c[tri[0]], c[tri[1]], c[tri[2]]);
                t3.setColor(colour);
                tris->insertTriangle(t3);
            }
    }
    o.insert(tris);
}
