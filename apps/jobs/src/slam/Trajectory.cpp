// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Trajectory.cpp
 * @brief  KITTI poses file and trajectory error.
 */
#include "Trajectory.h"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

namespace hif::slam
{
void writeKittiPoses(const std::string& file, const std::vector<mrpt::poses::CPose3D>& poses)
{
    std::ofstream f(file);
    if (!f) throw std::runtime_error("cannot create '" + file + "'");
    f << std::setprecision(9);
    for (const auto& p : poses)
    {
        const auto m = p.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>();
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) f << m(r, c) << (r == 2 && c == 3 ? '\n' : ' ');
    }
    if (!f) throw std::runtime_error("could not write '" + file + "' (disk full?)");
}

std::optional<double> trajectoryRmse(const std::vector<mrpt::poses::CPose3D>& estimated,
                                     const std::vector<mrpt::poses::CPose3D>& truth)
{
    const std::size_t n = std::min(estimated.size(), truth.size());
    if (n < 2) return std::nullopt;
    const mrpt::poses::CPose3D e0 = -estimated[0], t0 = -truth[0];
    double sum = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
        const auto d = (e0 + estimated[i]).translation() - (t0 + truth[i]).translation();
        sum += d.sqrNorm();
    }
    return std::sqrt(sum / double(n));
}

}  // namespace hif::slam
