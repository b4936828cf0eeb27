// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ReadPcd.cpp
 * @brief  PCD reader (ascii, binary and PCL's binary_compressed) for the DynamicMap benchmark
 *         layout and the clouds other tools write.
 */
#include <lzf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "Scalars.h"
#include "WidePoints.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/FileError.h"
#include "hif/io/ParseNumber.h"

namespace hif::io
{
namespace
{
/** The body of a `DATA binary_compressed` PCD (PCL's), which `f` is at, `data_bytes` long: two
 *  little-endian uint32, the compressed and the uncompressed size, then that many bytes of
 *  LZF data. Uncompressed, it must be `expected` bytes long. */
std::vector<char> readCompressedBody(std::ifstream& f, const std::string& file,
                                     std::size_t data_bytes, std::size_t expected)
{
    unsigned char sizes[8];
    if (data_bytes < sizeof sizes || !f.read(reinterpret_cast<char*>(sizes), sizeof sizes))
        throwFileError(file, "is truncated: its compressed data has no sizes");
    const auto u32 = [&](int at)
    {
        return uint32_t{sizes[at]} | uint32_t{sizes[at + 1]} << 8 | uint32_t{sizes[at + 2]} << 16 |
               uint32_t{sizes[at + 3]} << 24;
    };
    const uint32_t compressed = u32(0), uncompressed = u32(4);
    if (uncompressed != expected)
        throwFileError(file, "says its data uncompress to " + std::to_string(uncompressed) +
                                 " bytes, but POINTS and its fields make " +
                                 std::to_string(expected));
    if (compressed > data_bytes - sizeof sizes)
        throwFileError(file, "is truncated: " + std::to_string(compressed) +
                                 " bytes of compressed data announced, " +
                                 std::to_string(data_bytes - sizeof sizes) + " follow");
    // A back-reference of LZF (three bytes) stands for 264 bytes at most.
    if (uncompressed > 88.0 * compressed)
        throwFileError(file, "has compressed data that cannot uncompress to " +
                                 std::to_string(uncompressed) + " bytes (corrupt sizes)");
    std::vector<char> packed(compressed);
    if (!f.read(packed.data(), static_cast<std::streamsize>(packed.size())))
        throwFileError(file, "is truncated in its compressed data");
    std::vector<char> body(expected);
    // lzf_decompress() checks its input's bounds: corrupt data gives 0 (or a short length).
    if (expected > 0 &&
        lzf_decompress(packed.data(), compressed, body.data(), uncompressed) != uncompressed)
        throwFileError(file, "has compressed data that do not uncompress (corrupt LZF data)");
    return body;
}
}  // namespace

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
    if (data != "ascii" && data != "binary" && data != "binary_compressed")
        throwFileError(
            file, "has DATA " + data + ", which is not read (ascii, binary or binary_compressed)");
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
    // binary_compressed: each field's values for all points, one field after the other, at
    // `packed[k]` times the points; padding fields ("_") left out.
    std::vector<std::size_t> packed(fields.size());
    std::size_t packed_stride = 0;
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
        offset[k] = stride;
        packed[k] = packed_stride;
        stride += static_cast<std::size_t>(sizes[k] * counts[k]);
        if (fields[k] != "_") packed_stride += static_cast<std::size_t>(sizes[k] * counts[k]);
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
    // Intensity of any number type (some drivers write it as uint8 or uint16), as float32.
    const Scalar intensity_type = ii >= 0 ? pcdScalar(types[ii], sizes[ii]) : Scalar::Float32;
    if (intensity_type == Scalar::None)
        throwFileError(file, std::string("has a field intensity of TYPE ") + types[ii] +
                                 " and SIZE " + std::to_string(sizes[ii]) +
                                 ", which is not a number (I, U or F)");
    const bool wide = sizes[ix] == 8 || sizes[iy] == 8 || sizes[iz] == 8;
    if (data == "binary_compressed")
    {
        // Refused before allocating for them: the uncompressed size is a uint32, and LZF
        // shrinks data 88 times at most (readCompressedBody()).
        if (points > std::numeric_limits<uint32_t>::max() / packed_stride ||
            static_cast<double>(points * packed_stride) > 88.0 * static_cast<double>(data_bytes))
            throwFileError(file, "is truncated: POINTS says " + std::to_string(points) +
                                     ", more than " + std::to_string(data_bytes) +
                                     " bytes of compressed data can hold");
    }
    else
    {
        // Binary points take `stride` bytes each; ascii ones at least two ("0\n").
        const std::size_t min_bytes = data == "binary" ? stride : 2;
        if (points > data_bytes / min_bytes)
            throwFileError(file, "is truncated: POINTS says " + std::to_string(points) + ", but " +
                                     std::to_string(data_bytes) + " bytes of data follow DATA");
    }
    out.x.resize(points);
    out.y.resize(points);
    out.z.resize(points);
    out.intensity.assign(points, 0.0f);
    WidePoints stored(out, wide);
    if (data == "binary_compressed")
    {
        const std::vector<char> body =
            readCompressedBody(f, file, data_bytes, points * packed_stride);
        // Field k's value of point p at packed[k] * points + p * (its size x count).
        const auto at = [&](int k, std::size_t p)
        {
            const auto kk = static_cast<std::size_t>(k);
            return body.data() + packed[kk] * points +
                   p * static_cast<std::size_t>(sizes[kk] * counts[kk]);
        };
        const Scalar tx = pcdScalar('F', sizes[ix]), ty = pcdScalar('F', sizes[iy]),
                     tz = pcdScalar('F', sizes[iz]);
        for (std::size_t p = 0; p < points; ++p)
        {
            stored.store(p, binaryValue(at(ix, p), tx), binaryValue(at(iy, p), ty),
                         binaryValue(at(iz, p), tz));
            if (ii >= 0)
                out.intensity[p] = static_cast<float>(binaryValue(at(ii, p), intensity_type));
        }
    }
    else if (data == "binary")
    {
        // The body read in chunks of records, the fields picked out of each: a buffer of a
        // few pages rather than a second copy of the cloud.
        constexpr std::size_t kChunkPoints = 4096;
        std::vector<char> chunk(std::min(points, kChunkPoints) * stride);
        const std::size_t ox = offset[ix], oy = offset[iy], oz = offset[iz];
        const std::size_t oi = ii >= 0 ? offset[ii] : 0;
        const auto intensity = [&](std::size_t p, const char* value)
        {
            if (ii >= 0) out.intensity[p] = static_cast<float>(binaryValue(value, intensity_type));
        };
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
            if (!wide && intensity_type == Scalar::Float32)
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
                // float64 coordinates (or an intensity other than float32).
                for (std::size_t p = first; p < first + n; ++p, rec += stride)
                {
                    stored.store(p, coord(rec + ox, sizes[ix]), coord(rec + oy, sizes[iy]),
                                 coord(rec + oz, sizes[iz]));
                    intensity(p, rec + oi);
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

void absorbOrigin(PcdCloud& pcd)
{
    if (pcd.origin.isZero(0.0)) return;
    for (std::size_t i = 0; i < pcd.size(); ++i)
    {
        const Eigen::Vector3d p = pcd.point(i);
        pcd.x[i] = static_cast<float>(p.x());
        pcd.y[i] = static_cast<float>(p.y());
        pcd.z[i] = static_cast<float>(p.z());
    }
    pcd.origin.setZero();
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
