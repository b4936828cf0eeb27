// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   KittiSequence.cpp
 * @brief  Validation and reading of a KITTI odometry sequence folder.
 */
#include "hif/io/KittiSequence.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "hif/io/FileError.h"
#include "hif/io/ParseNumber.h"

namespace fs = std::filesystem;

namespace hif::io
{
namespace
{
std::vector<std::string> readLines(const std::string& file, std::size_t max_lines)
{
    std::ifstream f(file);
    if (!f) throwFileError(file, "cannot be opened");
    std::vector<std::string> lines;
    for (std::string line; lines.size() < max_lines && std::getline(f, line);)
    {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        lines.push_back(line);
    }
    return lines;
}
}  // namespace

std::string frameName(std::size_t i)
{
    char buf[32];
    std::snprintf(buf, sizeof(buf), "%06zu", i);
    return buf;
}

Eigen::Isometry3d parseRow34(const std::string& line, const std::string& file,
                             const std::string& where)
{
    std::istringstream is(line);
    std::vector<std::string> tokens;
    for (std::string t; is >> t;) tokens.push_back(t);
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (std::size_t k = 0; k < tokens.size() && k < 12; ++k)
    {
        const auto v = parseNumber(tokens[k]);
        const std::string which = "number " + std::to_string(k + 1) + " of 12, '" + tokens[k] + "'";
        if (!v) throwFileError(file, where + ": " + which + ", is not a number");
        if (!std::isfinite(*v)) throwFileError(file, where + ": " + which + ", is not finite");
        T(int(k / 4), int(k % 4)) = *v;
    }
    if (tokens.size() < 12)
        throwFileError(file, where + ": expected 12 numbers (a 3x4 row-major matrix), found " +
                                 std::to_string(tokens.size()));
    if (tokens.size() > 12)
        throwFileError(
            file, where + ": '" + tokens[12] + "' after the 12 numbers of a 3x4 row-major matrix");
    // A pose is a rigid motion: its rotation part orthonormal (as printed, to about 6 digits)
    // and not a reflection.
    const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
    const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
    if (!(off <= kRotationTolerance) || R.determinant() <= 0)
    {
        std::ostringstream msg;
        msg << where << ": not a rigid motion: the rotation part is ";
        if (R.determinant() <= 0 && off <= kRotationTolerance)
            msg << "a reflection (determinant " << R.determinant() << ")";
        else
            msg << "not orthonormal (R^T R differs from the identity by up to " << off
                << "; tolerance " << kRotationTolerance << ")";
        throwFileError(file, msg.str());
    }
    Eigen::Isometry3d iso;
    iso.matrix() = T;
    return iso;
}

KittiSequence::KittiSequence(const std::string& dir) : dir_(dir)
{
    if (!fs::is_directory(dir))
        throwFileError(dir, fs::exists(dir) ? "is not a folder (expected a KITTI sequence folder)"
                                            : "does not exist (expected a KITTI sequence folder)");
    const fs::path velo = fs::path(dir) / "velodyne";
    if (!fs::is_directory(velo)) throwFileError(velo.string(), "does not exist (no scans)");

    // Scans: 000000.bin, 000001.bin, ... without gaps.
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(velo))
        if (e.path().extension() == ".bin") names.push_back(e.path().stem().string());
    if (names.empty()) throwFileError(velo.string(), "holds no .bin scans");
    std::sort(names.begin(), names.end());
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] != frameName(i))
            throwFileError(velo.string(), "should hold scan " + frameName(i) + ".bin, found " +
                                              names[i] +
                                              ".bin (scans must be numbered from 000000 without "
                                              "gaps)");
    scan_count_ = names.size();

    // calib.txt: the Tr line (LiDAR -> camera 0).
    const std::string calib = (fs::path(dir) / "calib.txt").string();
    std::size_t tr_line = 0;
    const auto calib_lines = readLines(calib, 1000);
    for (std::size_t k = 0; k < calib_lines.size(); ++k)
        if (calib_lines[k].rfind("Tr:", 0) == 0)
        {
            if (tr_line > 0)
                throwFileError(calib, "has two 'Tr:' lines (" + std::to_string(tr_line) + " and " +
                                          std::to_string(k + 1) +
                                          "): which LiDAR to camera calibration is meant?");
            tr_line = k + 1;
            Tr_ = parseRow34(calib_lines[k].substr(3), calib,
                             "line " + std::to_string(tr_line) + " (Tr)");
        }
    if (tr_line == 0) throwFileError(calib, "has no 'Tr:' line (LiDAR to camera calibration)");

    // poses.txt: at least one camera-0 pose per scan (the full sequence may have more).
    const std::string posef = (fs::path(dir) / "poses.txt").string();
    const auto pose_lines = readLines(posef, scan_count_);
    if (pose_lines.size() < scan_count_)
        throwFileError(posef, "has " + std::to_string(pose_lines.size()) + " poses for " +
                                  std::to_string(scan_count_) + " scans");
    const Eigen::Isometry3d Tr_inv = Tr_.inverse();
    for (std::size_t i = 0; i < scan_count_; ++i)
    {
        const auto P = parseRow34(pose_lines[i], posef, "line " + std::to_string(i + 1));
        // Camera-0 poses to LiDAR poses: T_world_velo = inv(Tr) * P * Tr.
        poses_.push_back(Tr_inv * P * Tr_);
    }

    // times.txt: one time stamp per scan.
    const std::string timef = (fs::path(dir) / "times.txt").string();
    const auto time_lines = readLines(timef, scan_count_);
    if (time_lines.size() < scan_count_)
        throwFileError(timef, "has " + std::to_string(time_lines.size()) + " time stamps for " +
                                  std::to_string(scan_count_) + " scans");
    for (std::size_t i = 0; i < scan_count_; ++i)
    {
        std::istringstream is(time_lines[i]);
        std::string token, extra;
        is >> token >> extra;
        const auto t = parseNumber(token);
        if (!t || !std::isfinite(*t) || !extra.empty())
            throwFileError(timef, "line " + std::to_string(i + 1) +
                                      ": expected one finite number (seconds), found '" +
                                      time_lines[i] + "'");
        times_.push_back(*t);
    }

    has_labels_ = fs::is_directory(fs::path(dir) / "labels");
}

std::string KittiSequence::scanFile(std::size_t i) const
{
    return (fs::path(dir_) / "velodyne" / (frameName(i) + ".bin")).string();
}

std::string KittiSequence::labelFile(std::size_t i) const
{
    return (fs::path(dir_) / "labels" / (frameName(i) + ".label")).string();
}

std::size_t kittiBinPointCount(const std::string& f)
{
    std::error_code ec;
    const auto bytes = fs::file_size(f, ec);
    if (ec) throwFileError(f, "has a size that cannot be read: " + ec.message());
    if (bytes == 0) throwFileError(f, "is empty (0 bytes): truncated? (a scan has points)");
    if (bytes % 16 != 0)
        throwFileError(f, "is " + std::to_string(bytes) +
                              " bytes, not a multiple of 16 (x y z intensity as float32): "
                              "truncated?");
    return static_cast<std::size_t>(bytes / 16);
}

Cloud readKittiBin(const std::string& f)
{
    const std::size_t n = kittiBinPointCount(f);
    std::ifstream in(f, std::ios::binary);
    if (!in) throwFileError(f, "cannot be opened");
    Cloud c;
    c.resize(n);
    // In chunks: no second copy of the whole scan.
    constexpr std::size_t kChunk = 4096;  // points
    std::vector<float> raw(4 * std::min(n, kChunk));
    for (std::size_t first = 0; first < n; first += kChunk)
    {
        const std::size_t m = std::min(kChunk, n - first);
        if (!in.read(reinterpret_cast<char*>(raw.data()),
                     static_cast<std::streamsize>(4 * m * sizeof(float))))
            throwFileError(f, "could not be read whole");
        for (std::size_t k = 0; k < m; ++k)
        {
            c.x[first + k] = raw[4 * k];
            c.y[first + k] = raw[4 * k + 1];
            c.z[first + k] = raw[4 * k + 2];
            c.intensity[first + k] = raw[4 * k + 3];
        }
    }
    return c;
}

std::size_t KittiSequence::pointCount(std::size_t i) const
{
    return kittiBinPointCount(scanFile(i));
}

Cloud KittiSequence::readScan(std::size_t i) const { return readKittiBin(scanFile(i)); }

}  // namespace hif::io
