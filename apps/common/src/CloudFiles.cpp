// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CloudFiles.cpp
 * @brief  Streaming PLY/PCD writer and PCD reader.
 */
#include "hif/apps/CloudFiles.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace hif::apps
{
namespace
{
[[noreturn]] void fail(const std::string& file, const std::string& what)
{
    throw std::runtime_error("'" + file + "': " + what);
}

bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

CloudWriter::CloudWriter(std::vector<std::string> files) : files_(std::move(files))
{
    if (files_.empty()) throw std::invalid_argument("CloudWriter: no output file");
    for (const std::string& file : files_)
        if (!endsWith(file, ".pcd") && !endsWith(file, ".ply"))
            fail(file, "unknown point-cloud extension (use .ply or .pcd)");
    part_ = files_.front() + ".part";
    f_ = std::fopen(part_.c_str(), "wb");
    if (!f_) fail(part_, std::string("cannot create: ") + std::strerror(errno));
    buf_.reserve(4 * 8192);
}

CloudWriter::~CloudWriter()
{
    if (f_)
    {
        std::fclose(f_);
        std::remove(part_.c_str());
    }
}

void CloudWriter::add(float x, float y, float z, float intensity)
{
    buf_.insert(buf_.end(), {x, y, z, intensity});
    ++count_;
    if (buf_.size() >= 4 * 8192)
    {
        if (std::fwrite(buf_.data(), sizeof(float), buf_.size(), f_) != buf_.size())
            fail(part_, "write error (disk full?)");
        buf_.clear();
    }
}

void CloudWriter::close()
{
    if (!f_) return;
    if (!buf_.empty() && std::fwrite(buf_.data(), sizeof(float), buf_.size(), f_) != buf_.size())
        fail(part_, "write error (disk full?)");
    buf_.clear();
    if (std::fclose(f_) != 0) fail(part_, "error closing");
    f_ = nullptr;

    for (const std::string& file : files_)
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        if (!out) fail(file, "cannot create");
        if (endsWith(file, ".ply"))
            out << "ply\nformat binary_little_endian 1.0\ncomment written by hif\nelement vertex "
                << count_
                << "\nproperty float x\nproperty float y\nproperty float z\nproperty float "
                   "intensity\nend_header\n";
        else
            out << "# .PCD v0.7 - Point Cloud Data file format (written by hif)\nVERSION 0.7\n"
                   "FIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH "
                << count_ << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << count_
                << "\nDATA binary\n";
        std::ifstream body(part_, std::ios::binary);
        if (count_ > 0) out << body.rdbuf();
        out.close();
        if (!out) fail(file, "write error (disk full?)");
    }
    std::remove(part_.c_str());
}

PcdCloud readPcd(const std::string& file)
{
    std::ifstream f(file, std::ios::binary);
    if (!f) fail(file, "cannot open");
    std::vector<std::string> fields;
    std::vector<int> sizes, counts;
    std::vector<char> types;
    std::size_t points = 0;
    bool have_points = false;
    std::string data;
    PcdCloud out;
    for (std::string line; std::getline(f, line);)
    {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.empty() || line[0] == '#') continue;
        std::istringstream is(line);
        std::string key;
        is >> key;
        if (key == "FIELDS")
            for (std::string s; is >> s;) fields.push_back(s);
        else if (key == "SIZE")
            for (int s; is >> s;) sizes.push_back(s);
        else if (key == "TYPE")
            for (char s; is >> s;) types.push_back(s);
        else if (key == "COUNT")
            for (int s; is >> s;) counts.push_back(s);
        else if (key == "POINTS")
            have_points = static_cast<bool>(is >> points);
        else if (key == "VIEWPOINT")
        {
            double v[7];
            for (double& d : v)
                if (!(is >> d) || !std::isfinite(d)) fail(file, "malformed VIEWPOINT line");
            Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
            if (std::abs(q.norm() - 1.0) > 1e-3) fail(file, "VIEWPOINT quaternion is not unit");
            out.viewpoint = Eigen::Isometry3d::Identity();
            out.viewpoint.linear() = q.normalized().toRotationMatrix();
            out.viewpoint.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
        }
        else if (key == "DATA")
        {
            is >> data;
            break;
        }
    }
    if (data.empty()) fail(file, "no DATA line: not a PCD file?");
    if (data != "ascii" && data != "binary")
        fail(file, "DATA " + data + " is not supported (use ascii or binary)");
    if (!have_points) fail(file, "no POINTS line");
    if (counts.empty()) counts.assign(fields.size(), 1);
    if (sizes.size() != fields.size() || types.size() != fields.size() ||
        counts.size() != fields.size())
        fail(file, "FIELDS, SIZE, TYPE and COUNT do not have the same length");
    int ix = -1, iy = -1, iz = -1, ii = -1;
    std::vector<std::size_t> offset(fields.size());
    std::size_t stride = 0;
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
        offset[k] = stride;
        stride += static_cast<std::size_t>(sizes[k] * counts[k]);
        const int kk = static_cast<int>(k);
        if (fields[k] == "x") ix = kk;
        if (fields[k] == "y") iy = kk;
        if (fields[k] == "z") iz = kk;
        if (fields[k] == "intensity") ii = kk;
    }
    if (ix < 0 || iy < 0 || iz < 0) fail(file, "no x, y and z fields");
    for (int k : {ix, iy, iz, ii})
        if (k >= 0 && (types[k] != 'F' || sizes[k] != 4))
            fail(file, "field " + fields[k] + " is not float32 (TYPE F, SIZE 4)");
    out.x.resize(points);
    out.y.resize(points);
    out.z.resize(points);
    out.intensity.assign(points, 0.0f);
    if (data == "binary")
    {
        std::vector<char> rec(stride);
        for (std::size_t p = 0; p < points; ++p)
        {
            if (!f.read(rec.data(), static_cast<std::streamsize>(stride)))
                fail(file, "truncated: POINTS says " + std::to_string(points) + ", found " +
                               std::to_string(p));
            std::memcpy(&out.x[p], rec.data() + offset[ix], 4);
            std::memcpy(&out.y[p], rec.data() + offset[iy], 4);
            std::memcpy(&out.z[p], rec.data() + offset[iz], 4);
            if (ii >= 0) std::memcpy(&out.intensity[p], rec.data() + offset[ii], 4);
        }
    }
    else
    {
        std::vector<double> vals;
        for (std::size_t p = 0; p < points; ++p)
        {
            std::string line;
            if (!std::getline(f, line))
                fail(file, "truncated: POINTS says " + std::to_string(points) + ", found " +
                               std::to_string(p));
            std::istringstream is(line);
            vals.clear();
            for (double v; is >> v;) vals.push_back(v);
            std::size_t col = 0;
            std::vector<double> first(fields.size());
            for (std::size_t k = 0; k < fields.size(); ++k)
            {
                if (col >= vals.size()) fail(file, "short line " + std::to_string(p + 1));
                first[k] = vals[col];
                col += static_cast<std::size_t>(counts[k]);
            }
            out.x[p] = static_cast<float>(first[ix]);
            out.y[p] = static_cast<float>(first[iy]);
            out.z[p] = static_cast<float>(first[iz]);
            if (ii >= 0) out.intensity[p] = static_cast<float>(first[ii]);
        }
    }
    return out;
}

}  // namespace hif::apps
