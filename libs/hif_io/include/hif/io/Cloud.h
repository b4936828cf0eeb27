// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Cloud.h
 * @brief  A point cloud as four arrays (x, y, z, intensity), as the readers return it, and its
 *         rigid transformation.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace hif::io
{
struct Cloud
{
    std::vector<float> x, y, z, intensity;

    [[nodiscard]] std::size_t size() const { return x.size(); }
    void resize(std::size_t n)
    {
        x.resize(n);
        y.resize(n);
        z.resize(n);
        intensity.resize(n);
    }
};

/** Moves every point of `c` by `T` (in double precision, stored back in float). */
inline void transform(Cloud& c, const Eigen::Isometry3d& T)
{
    for (std::size_t i = 0; i < c.size(); ++i)
    {
        const Eigen::Vector3d p = T * Eigen::Vector3d(c.x[i], c.y[i], c.z[i]);
        c.x[i] = static_cast<float>(p.x());
        c.y[i] = static_cast<float>(p.y());
        c.z[i] = static_cast<float>(p.z());
    }
}

}  // namespace hif::io
