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
    for (const auto& [idx, pillar] : grid_.sortedPillars())
    {
        const float x0 = static_cast<float>(g.origin_x + idx.m * g.pillar_size + inset);
        const float y0 = static_cast<float>(g.origin_y + idx.n * g.pillar_size + inset);
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
