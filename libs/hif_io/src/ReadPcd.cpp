// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ReadPcd.cpp
 * @brief  PCD reader (ASCII and binary) for the DynamicMap benchmark layout.
 */
#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "WidePoints.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/FileError.h"
#include "hif/io/ParseNumber.h"

namespace hif::io
{
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
            out.has_viewpoint = true;
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
    std::size_t stride = 0, stride_values = 0;
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
        offset[k] = stride;
        stride += static_cast<std::size_t>(sizes[k] * counts[k]);
        stride_values += static_cast<std::size_t>(counts[k]);
        const int kk = static_cast<int>(k);
        if (fields[k] == "x") ix = kk;
        if (fields[k] == "y") iy = kk;
        if (fields[k] == "z") iz = kk;
        if (fields[k] == "intensity") ii = kk;
    }
    if (ix < 0 || iy < 0 || iz < 0) throwFileError(file, "has no x, y and z fields");
    for (int k : {ix, iy, iz})
        if (types[k] != 'F' || (sizes[k] != 4 && sizes[k] != 8))
            throwFileError(file, "has a field " + fields[k] +
                                     " that is neither float32 nor float64 (TYPE F, SIZE 4 or 8)");
    if (ii >= 0 && (types[ii] != 'F' || sizes[ii] != 4))
        throwFileError(file, "has a field intensity that is not float32 (TYPE F, SIZE 4)");
    const bool wide = sizes[ix] == 8 || sizes[iy] == 8 || sizes[iz] == 8;
    // Binary points take `stride` bytes each; ascii ones at least two ("0\n").
    const std::size_t min_bytes = data == "binary" ? stride : 2;
    if (points > data_bytes / min_bytes)
        throwFileError(file, "is truncated: POINTS says " + std::to_string(points) + ", but " +
                                 std::to_string(data_bytes) + " bytes of data follow DATA");
    out.x.resize(points);
    out.y.resize(points);
    out.z.resize(points);
    out.intensity.assign(points, 0.0f);
    WidePoints stored(out, wide);
    if (data == "binary")
    {
        // The body read in chunks of records, the fields picked out of each: a buffer of a
        // few pages rather than a second copy of the cloud.
        constexpr std::size_t kChunkPoints = 4096;
        std::vector<char> chunk(std::min(points, kChunkPoints) * stride);
        const std::size_t ox = offset[ix], oy = offset[iy], oz = offset[iz];
        const std::size_t oi = ii >= 0 ? offset[ii] : 0;
        const auto coord = [](const char* at, int size)
        {
            if (size == 8)
            {
                double d;
                std::memcpy(&d, at, 8);
                return d;
            }
            float v;
            std::memcpy(&v, at, 4);
            return double(v);
        };
        for (std::size_t first = 0; first < points; first += kChunkPoints)
        {
            const std::size_t n = std::min(kChunkPoints, points - first);
            if (!f.read(chunk.data(), static_cast<std::streamsize>(n * stride)))
                throwFileError(file, "is truncated: POINTS says " + std::to_string(points) +
                                         ", found " + std::to_string(first + f.gcount() / stride));
            const char* rec = chunk.data();
            if (!wide)
            {
                // One pass over the records (the usual x y z intensity at 0, 4, 8, 12
                // vectorizes).
                for (std::size_t p = first; p < first + n; ++p, rec += stride)
                {
                    std::memcpy(&out.x[p], rec + ox, 4);
                    std::memcpy(&out.y[p], rec + oy, 4);
                    std::memcpy(&out.z[p], rec + oz, 4);
                    if (ii >= 0) std::memcpy(&out.intensity[p], rec + oi, 4);
                }
            }
            else
            {
                for (std::size_t p = first; p < first + n; ++p, rec += stride)
                {
                    stored.store(p, coord(rec + ox, sizes[ix]), coord(rec + oy, sizes[iy]),
                                 coord(rec + oz, sizes[iz]));
                    if (ii >= 0) std::memcpy(&out.intensity[p], rec + oi, 4);
                }
            }
        }
    }
    else
    {
        std::vector<double> vals;
        std::vector<double> first(fields.size());
        std::string line, token;
        for (std::size_t p = 0; p < points; ++p)
        {
            if (!std::getline(f, line))
                throwFileError(file, "is truncated: POINTS says " + std::to_string(points) +
                                         ", found " + std::to_string(p));
            // Tokens one by one: strtod reads "nan" (PCL's invalid point) and "inf", which
            // operator>> does not.
            std::istringstream is(line);
            vals.clear();
            while (is >> token)
            {
                const auto v = parseNumber(token);
                if (!v)
                    throwFileError(file, "line " + std::to_string(p + 1) + " of the data: '" +
                                             token + "' is not a number");
                vals.push_back(*v);
            }
            std::size_t col = 0;
            for (std::size_t k = 0; k < fields.size(); ++k)
            {
                if (col >= vals.size())
                    throwFileError(file, "has a short line " + std::to_string(p + 1) +
                                             " of the data (" + std::to_string(vals.size()) +
                                             " values for " + std::to_string(stride_values) + ")");
                first[k] = vals[col];
                col += static_cast<std::size_t>(counts[k]);
            }
            if (wide)
                stored.store(p, first[ix], first[iy], first[iz]);
            else
            {
                out.x[p] = static_cast<float>(first[ix]);
                out.y[p] = static_cast<float>(first[iy]);
                out.z[p] = static_cast<float>(first[iz]);
            }
            if (ii >= 0) out.intensity[p] = static_cast<float>(first[ii]);
        }
    }
    return out;
}

void toViewpointFrame(PcdCloud& pcd)
{
    // inv * point(i), in double (a wide file's origin added back first: UTM keeps its
    // millimetres), with the sums in the order of Eigen's product, over the three arrays at
    // once: the compiler vectorizes the loop (a point at a time through Eigen it did not).
    const Eigen::Matrix4d m = pcd.viewpoint.inverse().matrix();
    const double r00 = m(0, 0), r01 = m(0, 1), r02 = m(0, 2), t0 = m(0, 3);
    const double r10 = m(1, 0), r11 = m(1, 1), r12 = m(1, 2), t1 = m(1, 3);
    const double r20 = m(2, 0), r21 = m(2, 1), r22 = m(2, 2), t2 = m(2, 3);
    // Without an origin, -0.0 is added: the one addition that leaves every value as it is,
    // the sign of a zero included (the file's float32 points as they are).
    const Eigen::Vector3d o = pcd.origin.isZero(0.0) ? Eigen::Vector3d::Constant(-0.0) : pcd.origin;
    const double ox = o.x(), oy = o.y(), oz = o.z();
    float* x = pcd.x.data();
    float* y = pcd.y.data();
    float* z = pcd.z.data();
    for (std::size_t i = 0, n = pcd.size(); i < n; ++i)
    {
        const double px = double(x[i]) + ox, py = double(y[i]) + oy, pz = double(z[i]) + oz;
        x[i] = static_cast<float>(r00 * px + r01 * py + r02 * pz + t0);
        y[i] = static_cast<float>(r10 * px + r11 * py + r12 * pz + t1);
        z[i] = static_cast<float>(r20 * px + r21 * py + r22 * pz + t2);
    }
    pcd.origin.setZero();
}

}  // namespace hif::io
