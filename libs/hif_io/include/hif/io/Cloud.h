// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Cloud.h
 * @brief  A point cloud as four arrays (x, y, z, intensity), as the readers return it.
 */
#pragma once

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

}  // namespace hif::io
