// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Trajectory.cpp
 * @brief  KITTI- and TUM-format trajectory files.
 */
#include "hif/io/Trajectory.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "hif/io/FileError.h"
#include "hif/io/KittiSequence.h"
#include "hif/io/ParseNumber.h"

namespace hif::io
{
namespace
{
/** A TUM pose from `tokens`: x y z qx qy qz qw, after a time when `time` is set (which
 *  receives it). */
Eigen::Isometry3d parseTum(const std::vector<std::string>& tokens, const std::string& file,
                           const std::string& where, double* time)
{
    const std::size_t n = time ? 8 : 7, o = time ? 1 : 0;
    double v[8];
    for (std::size_t k = 0; k < n; ++k)
    {
        const auto num = parseNumber(tokens[k]);
        const std::string which = "number " + std::to_string(k + 1) + " of " + std::to_string(n) +
                                  ", '" + tokens[k] + "'";
        if (!num) throwFileError(file, where + ": " + which + ", is not a number");
        if (!std::isfinite(*num)) throwFileError(file, where + ": " + which + ", is not finite");
        v[k] = *num;
    }
    if (time) *time = v[0];
    const Eigen::Quaterniond q(v[o + 6], v[o + 3], v[o + 4], v[o + 5]);  // w x y z
    if (!(std::abs(q.norm() - 1.0) <= kRotationTolerance))
    {
        std::ostringstream msg;
        msg << where << ": the quaternion (qx qy qz qw) has norm " << q.norm()
            << ", not 1 (tolerance " << kRotationTolerance << ")";
        throwFileError(file, msg.str());
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = q.normalized().toRotationMatrix();
    T.translation() = Eigen::Vector3d(v[o], v[o + 1], v[o + 2]);
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
        out.poses.push_back(parseTum(tokens, file, where, &time));
        if (!out.times.empty() && !(time > out.times.back()))
            throwFileError(file, where + ": time " + tokens[0] +
                                     " does not come after the line before's (a TUM trajectory "
                                     "is in time order)");
        out.times.push_back(time);
    }
    if (out.poses.empty()) throwFileError(file, "holds no pose");
    return out;
}

Eigen::Isometry3d parseExtrinsic(const std::string& text)
{
    std::istringstream is(text);
    std::vector<std::string> tokens;
    for (std::string t; is >> t;) tokens.push_back(t);
    const std::string what = "--extrinsic";
    const std::string where = "'" + text + "'";
    if (tokens.size() == 12) return parseRow34(text, what, where);
    if (tokens.size() != 7)
        throwFileError(what, where +
                                 ": expected 7 numbers (x y z qx qy qz qw) or 12 (the 3x4 "
                                 "matrix row by row), found " +
                                 std::to_string(tokens.size()));
    return parseTum(tokens, what, where, nullptr);
}

std::array<double, 7> xyzQxyzw(const Eigen::Isometry3d& pose)
{
    const Eigen::Quaterniond q(pose.linear());
    const Eigen::Vector3d& t = pose.translation();
    return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

std::optional<Eigen::Isometry3d> poseAt(const Trajectory& tr, double t, double max_gap)
{
    const std::vector<double>& times = tr.times;
    if (times.empty() || !std::isfinite(t)) return std::nullopt;
    // The first pose after t - kSameTime: the pose at t, or the one after it.
    const auto after = std::upper_bound(times.begin(), times.end(), t - kSameTime);
    if (after == times.end()) return std::nullopt;  // after the last pose
    const auto k = static_cast<std::size_t>(after - times.begin());
    if (std::abs(times[k] - t) <= kSameTime) return tr.poses[k];
    if (k == 0 || times[k] - times[k - 1] > max_gap) return std::nullopt;  // before, or a gap
    const double s = (t - times[k - 1]) / (times[k] - times[k - 1]);
    const Eigen::Isometry3d& a = tr.poses[k - 1];
    const Eigen::Isometry3d& b = tr.poses[k];
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.linear() = Eigen::Quaterniond(a.linear())
                        .slerp(s, Eigen::Quaterniond(b.linear()))
                        .normalized()
                        .toRotationMatrix();
    pose.translation() = (1.0 - s) * a.translation() + s * b.translation();
    return pose;
}

double medianSpacing(const Trajectory& tr)
{
    if (tr.times.size() < 2) return 0.0;
    std::vector<double> gaps(tr.times.size() - 1);
    for (std::size_t k = 1; k < tr.times.size(); ++k) gaps[k - 1] = tr.times[k] - tr.times[k - 1];
    const auto mid = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
    std::nth_element(gaps.begin(), mid, gaps.end());
    return *mid;
}

std::string describeTimes(const Trajectory& tr)
{
    if (tr.times.empty()) return "it has no times";
    char text[128];
    std::snprintf(text, sizeof text, "its poses run from %.6f to %.6f s, %.3f s apart (median)",
                  tr.times.front(), tr.times.back(), medianSpacing(tr));
    return text;
}

}  // namespace hif::io
