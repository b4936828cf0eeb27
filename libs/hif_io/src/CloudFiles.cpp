// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CloudFiles.cpp
 * @brief  Streaming PLY/PCD writer and PCD reader.
 */
#include "hif/io/CloudFiles.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "hif/io/FileError.h"

namespace hif::io
{
namespace
{
bool endsWith(const std::string& s, const std::string& suffix)
{
    return s.size() >= suffix.size() &&
           s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
/** Writes `header` then the whole of file `body` into `file`, the copy done by the kernel
 *  (copy_file_range) where it can, else through a large buffer. */
void writeHeaderAndBody(const std::string& file, const std::string& header, const std::string& body)
{
    const int in = ::open(body.c_str(), O_RDONLY | O_CLOEXEC);
    if (in < 0) throwFileError(body, std::string("cannot be read: ") + std::strerror(errno));
    const int out = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (out < 0)
    {
        ::close(in);
        throwFileError(file, std::string("cannot be created: ") + std::strerror(errno));
    }
    const auto fail = [&](const std::string& what)
    {
        const std::string why = std::strerror(errno);
        ::close(in);
        ::close(out);
        throwFileError(file, what + ": " + why);
    };
    const auto writeAll = [&](const char* p, std::size_t n)
    {
        while (n > 0)
        {
            const ssize_t w = ::write(out, p, n);
            if (w < 0 && errno == EINTR) continue;
            if (w <= 0) fail("could not be written (disk full?)");
            p += w;
            n -= static_cast<std::size_t>(w);
        }
    };
    writeAll(header.data(), header.size());
    bool kernel_copy = true;
    std::vector<char> buf;
    for (;;)
    {
        ssize_t n = 0;
        if (kernel_copy)
        {
            n = ::copy_file_range(in, nullptr, out, nullptr, std::size_t{1} << 30, 0);
            // Not supported here (another file system, an old kernel): copy through memory.
            if (n < 0 &&
                (errno == EXDEV || errno == ENOSYS || errno == EINVAL || errno == EOPNOTSUPP))
            {
                kernel_copy = false;
                continue;
            }
            if (n < 0 && errno != EINTR) fail("could not be written (disk full?)");
        }
        else
        {
            buf.resize(std::size_t{1} << 22);
            n = ::read(in, buf.data(), buf.size());
            if (n < 0 && errno != EINTR) fail("could not be written: its body cannot be read");
            if (n > 0) writeAll(buf.data(), static_cast<std::size_t>(n));
        }
        if (n == 0) break;
    }
    ::close(in);
    if (::close(out) != 0) throwFileError(file, "could not be written (disk full?)");
}

}  // namespace

CloudWriter::CloudWriter(std::vector<std::string> files) : files_(std::move(files))
{
    if (files_.empty()) throw std::invalid_argument("CloudWriter: no output file");
    for (const std::string& file : files_)
        if (!endsWith(file, ".pcd") && !endsWith(file, ".ply"))
            throwFileError(file, "has an unknown point-cloud extension (use .ply or .pcd)");
    part_ = files_.front() + ".part";
    f_ = std::fopen(part_.c_str(), "wb");
    if (!f_) throwFileError(part_, std::string("cannot be created: ") + std::strerror(errno));
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
            throwFileError(part_, "could not be written (disk full?)");
        buf_.clear();
    }
}

std::string CloudWriter::viewpointText() const
{
    if (viewpoint_.matrix() == Eigen::Matrix4d::Identity()) return "0 0 0 1 0 0 0";
    const Eigen::Quaterniond q(viewpoint_.linear());
    const Eigen::Vector3d& t = viewpoint_.translation();
    std::ostringstream s;
    s << std::setprecision(17) << t.x() << ' ' << t.y() << ' ' << t.z() << ' ' << q.w() << ' '
      << q.x() << ' ' << q.y() << ' ' << q.z();
    return s.str();
}

void CloudWriter::close()
{
    if (!f_) return;
    if (!buf_.empty() && std::fwrite(buf_.data(), sizeof(float), buf_.size(), f_) != buf_.size())
        throwFileError(part_, "could not be written (disk full?)");
    buf_.clear();
    if (std::fclose(f_) != 0) throwFileError(part_, "could not be closed (disk full?)");
    f_ = nullptr;

    for (const std::string& file : files_)
    {
        std::string header;
        if (endsWith(file, ".ply"))
            header =
                "ply\nformat binary_little_endian 1.0\ncomment written by hif\nelement vertex " +
                std::to_string(count_) +
                "\nproperty float x\nproperty float y\nproperty float z\nproperty float "
                "intensity\nend_header\n";
        else
            header =
                "# .PCD v0.7 - Point Cloud Data file format (written by hif)\nVERSION 0.7\n"
                "FIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH " +
                std::to_string(count_) + "\nHEIGHT 1\nVIEWPOINT " + viewpointText() + "\nPOINTS " +
                std::to_string(count_) + "\nDATA binary\n";
        writeHeaderAndBody(file, header, part_);
    }
    std::remove(part_.c_str());
}

PcdCloud readPcd(const std::string& file)
{
    std::ifstream f(file, std::ios::binary);
    if (!f) throwFileError(file, "cannot be opened");
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
                if (!(is >> d) || !std::isfinite(d))
                    throwFileError(file, "has a malformed VIEWPOINT line");
            Eigen::Quaterniond q(v[3], v[4], v[5], v[6]);
            if (std::abs(q.norm() - 1.0) > 1e-3)
                throwFileError(file, "has a VIEWPOINT quaternion that is not unit");
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
    if (data.empty()) throwFileError(file, "has no DATA line: not a PCD file?");
    if (data != "ascii" && data != "binary")
        throwFileError(file, "has DATA " + data + ", which is not supported (use ascii or binary)");
    if (!have_points) throwFileError(file, "has no POINTS line");
    if (counts.empty()) counts.assign(fields.size(), 1);
    if (sizes.size() != fields.size() || types.size() != fields.size() ||
        counts.size() != fields.size())
        throwFileError(file, "has FIELDS, SIZE, TYPE and COUNT of different lengths");
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
        if (sizes[k] != 1 && sizes[k] != 2 && sizes[k] != 4 && sizes[k] != 8)
            throwFileError(file, "has SIZE " + std::to_string(sizes[k]) + " for field " +
                                     fields[k] + " (expected 1, 2, 4 or 8)");
        if (counts[k] < 1 || counts[k] > (1 << 20))
            throwFileError(file, "has COUNT " + std::to_string(counts[k]) + " for field " +
                                     fields[k] + " (expected 1 to 1048576)");
    }
    // Refuse a POINTS that the rest of the file cannot hold before allocating for it.
    const auto data_start = f.tellg();
    f.seekg(0, std::ios::end);
    const auto data_bytes = static_cast<std::size_t>(f.tellg() - data_start);
    f.seekg(data_start);
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
    if (ix < 0 || iy < 0 || iz < 0) throwFileError(file, "has no x, y and z fields");
    for (int k : {ix, iy, iz, ii})
        if (k >= 0 && (types[k] != 'F' || sizes[k] != 4))
            throwFileError(file,
                           "has a field " + fields[k] + " that is not float32 (TYPE F, SIZE 4)");
    // Binary points take `stride` bytes each; ascii ones at least two ("0\n").
    const std::size_t min_bytes = data == "binary" ? stride : 2;
    if (points > data_bytes / min_bytes)
        throwFileError(file, "is truncated: POINTS says " + std::to_string(points) + ", but " +
                                 std::to_string(data_bytes) + " bytes of data follow DATA");
    out.x.resize(points);
    out.y.resize(points);
    out.z.resize(points);
    out.intensity.assign(points, 0.0f);
    if (data == "binary")
    {
        // One read of the whole body, then the fields picked out of each record.
        const std::size_t bytes = points * stride;
        const std::unique_ptr<char[]> body(new char[bytes]);  // not zeroed: read over
        if (!f.read(body.get(), static_cast<std::streamsize>(bytes)))
            throwFileError(file, "is truncated: POINTS says " + std::to_string(points) +
                                     ", found " + std::to_string(f.gcount() / stride));
        const auto pick = [&](int field, std::vector<float>& to)
        {
            const char* src = body.get() + offset[field];
            for (std::size_t p = 0; p < points; ++p, src += stride) std::memcpy(&to[p], src, 4);
        };
        pick(ix, out.x);
        pick(iy, out.y);
        pick(iz, out.z);
        if (ii >= 0) pick(ii, out.intensity);
    }
    else
    {
        std::vector<double> vals;
        for (std::size_t p = 0; p < points; ++p)
        {
            std::string line;
            if (!std::getline(f, line))
                throwFileError(file, "is truncated: POINTS says " + std::to_string(points) +
                                         ", found " + std::to_string(p));
            std::istringstream is(line);
            vals.clear();
            for (double v; is >> v;) vals.push_back(v);
            std::size_t col = 0;
            std::vector<double> first(fields.size());
            for (std::size_t k = 0; k < fields.size(); ++k)
            {
                if (col >= vals.size())
                    throwFileError(file, "has a short line " + std::to_string(p + 1));
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

}  // namespace hif::io
