// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Trajectory.cpp
 * @brief  KITTI- and TUM-format trajectory files.
 */
#include "hif/io/Trajectory.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "hif/io/FileError.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/ParseNumber.h"

namespace hif::io
{
namespace
{
/** A TUM line's pose; `time` receives its first number. */
Eigen::Isometry3d parseTum(const std::vector<std::string>& tokens, const std::string& file,
                           const std::string& where, double& time)
{
    double v[8];
    for (std::size_t k = 0; k < 8; ++k)
    {
        const auto n = parseNumber(tokens[k]);
        const std::string which = "number " + std::to_string(k + 1) + " of 8, '" + tokens[k] + "'";
        if (!n) throwFileError(file, where + ": " + which + ", is not a number");
        if (!std::isfinite(*n)) throwFileError(file, where + ": " + which + ", is not finite");
        v[k] = *n;
    }
    time = v[0];
    const Eigen::Quaterniond q(v[7], v[4], v[5], v[6]);  // w x y z
    if (!(std::abs(q.norm() - 1.0) <= kRotationTolerance))
    {
        std::ostringstream msg;
        msg << where << ": the quaternion (qx qy qz qw) has norm " << q.norm()
            << ", not 1 (tolerance " << kRotationTolerance << ")";
        throwFileError(file, msg.str());
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[1], v[2], v[3]);
    return T;
}
}  // namespace

Trajectory readTrajectory(const std::string& file)
{
    std::ifstream f(file);
    if (!f) throwFileError(file, "cannot be opened");
    Trajectory out;
    std::size_t expected = 0;  // numbers a line, from the first pose line
    std::size_t line_no = 0;
    for (std::string line; std::getline(f, line);)
    {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream is(line);
        std::vector<std::string> tokens;
        for (std::string t; is >> t;) tokens.push_back(t);
        if (tokens.empty() || tokens[0][0] == '#') continue;
        const std::string where = "line " + std::to_string(line_no);
        if (expected == 0)
        {
            if (tokens.size() != 12 && tokens.size() != 8)
                throwFileError(file, where + " has " + std::to_string(tokens.size()) +
                                         " numbers: neither a KITTI pose (12: a 3x4 matrix) nor "
                                         "a TUM pose (8: time x y z qx qy qz qw)");
            expected = tokens.size();
            out.format = expected == 12 ? Trajectory::Format::Kitti : Trajectory::Format::Tum;
        }
        if (tokens.size() != expected)
            throwFileError(file, where + " has " + std::to_string(tokens.size()) +
                                     " numbers where the lines before have " +
                                     std::to_string(expected) + " (" + out.formatName() + ")");
        if (out.format == Trajectory::Format::Kitti)
        {
            out.poses.push_back(parseRow34(line, file, where));
            continue;
        }
        double time = 0;
        out.poses.push_back(parseTum(tokens, file, where, time));
        if (!out.times.empty() && !(time > out.times.back()))
            throwFileError(file, where + ": time " + tokens[0] +
                                     " does not come after the line before's (a TUM trajectory "
                                     "is in time order)");
        out.times.push_back(time);
    }
    if (out.poses.empty()) throwFileError(file, "holds no pose");
    return out;
}

}  // namespace hif::io
