// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CHeightIntervalMap_render.cpp
 * @brief  The map as 3D boxes (mrpt::opengl), one per interval, coloured by P(static).
 */
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "hif/CHeightIntervalMap.h"

using namespace hif;

void CHeightIntervalMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const
{
    if (!genericMapParams.enableSaveAs3DObject) return;
    const GridGeometry& g = geometry();
    const Params& p = params();
    auto tris = mrpt::opengl::CSetOfTriangles::Create();
    tris->setName("hif::CHeightIntervalMap");
    const double inset = 0.05 * g.pillar_size;  // a small gap shows pillar borders
    const auto pillars = grid_.sortedPillars();
    // Triangles hold float32 vertices, which keep millimetres only below about 8 km: a map in
    // world coordinates (UTM) is drawn from its south-west corner, placed by the object's (double)
    // pose.
    constexpr double kFloatLimit = 8192.0;
    double ax = 0, ay = 0;
    if (!pillars.empty())
    {
        int32_t m0 = pillars.front().first.m, m1 = m0, n0 = pillars.front().first.n, n1 = n0;
        for (const auto& [idx, pillar] : pillars)
        {
            m0 = std::min(m0, idx.m);
            m1 = std::max(m1, idx.m);
            n0 = std::min(n0, idx.n);
            n1 = std::max(n1, idx.n);
        }
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
    }
    for (const auto& [idx, pillar] : pillars)
    {
        const float x0 = static_cast<float>(g.origin_x + idx.m * g.pillar_size - ax + inset);
        const float y0 = static_cast<float>(g.origin_y + idx.n * g.pillar_size - ay + inset);
        const float x1 = static_cast<float>(x0 + g.pillar_size - 2 * inset);
        const float y1 = static_cast<float>(y0 + g.pillar_size - 2 * inset);
        for (const Interval& iv : pillar->intervals)
        {
            const float z0 = static_cast<float>(g.cellBottom(iv.lo));
            const float z1 = static_cast<float>(g.cellBottom(iv.hi));
            const double t = (logistic(iv.logodds) - p.p_min) / (p.p_max - p.p_min);
            const auto g8 = static_cast<uint8_t>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
            const mrpt::img::TColor color(static_cast<uint8_t>(255 - g8), g8, 0);
            const mrpt::math::TPoint3D c[8] = {{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0},
                                               {x0, y1, z0}, {x0, y0, z1}, {x1, y0, z1},
                                               {x1, y1, z1}, {x0, y1, z1}};
            static const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4},
                                            {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
            for (const auto& f : faces)
                for (const auto& tri :
                     {std::array<int, 3>{f[0], f[1], f[2]}, std::array<int, 3>{f[0], f[2], f[3]}})
                {
                    mrpt::opengl::TTriangle t3(c[tri[0]], c[tri[1]], c[tri[2]]);
                    t3.setColor(color);
                    tris->insertTriangle(t3);
                }
        }
    }
    o.insert(tris);
}
