// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ReadPly.cpp
 * @brief  PLY point-cloud reader (ASCII and binary little-endian): the vertices' x y z and
 *         intensity, as LiDAR SLAM systems and hif-clean write them.
 */
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "Scalars.h"
#include "WidePoints.h"
#include "hif/io/CloudFiles.h"
#include "hif/io/FileError.h"
#include "hif/io/ParseNumber.h"

namespace hif::io
{
namespace
{
/** A PLY scalar type from its name (two for each: PLY's first and its sized alias). */
Scalar scalarOf(const std::string& t)
{
    if (t == "char" || t == "int8") return Scalar::Int8;
    if (t == "uchar" || t == "uint8") return Scalar::Uint8;
    if (t == "short" || t == "int16") return Scalar::Int16;
    if (t == "ushort" || t == "uint16") return Scalar::Uint16;
    if (t == "int" || t == "int32") return Scalar::Int32;
    if (t == "uint" || t == "uint32") return Scalar::Uint32;
    if (t == "float" || t == "float32") return Scalar::Float32;
    if (t == "double" || t == "float64") return Scalar::Float64;
    return Scalar::None;
}

struct Property
{
    std::string type, name;
    Scalar scalar = Scalar::None;
    std::size_t offset = 0;
};
}  // namespace

PcdCloud readPly(const std::string& file)
{
    std::ifstream f(file, std::ios::binary);
    if (!f) throwFileError(file, "cannot be opened");
    std::string line;
    if (!std::getline(f, line) || line.rfind("ply", 0) != 0)
        throwFileError(file, "does not start with 'ply': not a PLY file");
    std::string format;
    std::size_t vertices = 0;
    bool in_vertex = false, have_vertex = false, header_end = false;
    std::vector<Property> props;
    std::size_t stride = 0;
    while (std::getline(f, line))
    {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream is(line);
        std::string key;
        is >> key;
        if (key == "end_header")
        {
            header_end = true;
            break;
        }
        if (key == "format")
            is >> format;
        else if (key == "element")
        {
            std::string name;
            is >> name;
            if (have_vertex)
            {
                in_vertex = false;  // elements after the vertices (faces) are not read
                continue;
            }
            if (name != "vertex")
                throwFileError(file, "has the element '" + name +
                                         "' before its vertices (only a point cloud, vertices "
                                         "first, is read)");
            if (!(is >> vertices)) throwFileError(file, "has a malformed 'element vertex' line");
            in_vertex = have_vertex = true;
        }
        else if (key == "property" && in_vertex)
        {
            Property p;
            is >> p.type >> p.name;
            if (p.type == "list")
                throwFileError(file, "has a list property in its vertices (not a point cloud)");
            p.scalar = scalarOf(p.type);
            const std::size_t bytes = bytesOf(p.scalar);
            if (bytes == 0)
                throwFileError(file, "has the property type '" + p.type + "' (for " + p.name +
                                         "), which is not a PLY scalar type");
            p.offset = stride;
            stride += bytes;
            props.push_back(p);
        }
    }
    if (!header_end) throwFileError(file, "has no end_header line: truncated header?");
    if (format != "ascii" && format != "binary_little_endian")
        throwFileError(
            file, "has format '" + format + "', which is not read (ascii or binary_little_endian)");
    if (!have_vertex) throwFileError(file, "has no vertex element");
    int ix = -1, iy = -1, iz = -1, ii = -1;
    for (std::size_t k = 0; k < props.size(); ++k)
    {
        const int kk = static_cast<int>(k);
        if (props[k].name == "x") ix = kk;
        if (props[k].name == "y") iy = kk;
        if (props[k].name == "z") iz = kk;
        if (props[k].name == "intensity" || (ii < 0 && props[k].name == "scalar_intensity"))
            ii = kk;
    }
    if (ix < 0 || iy < 0 || iz < 0) throwFileError(file, "has no x, y and z vertex properties");
    const bool wide = props[ix].scalar == Scalar::Float64 || props[iy].scalar == Scalar::Float64 ||
                      props[iz].scalar == Scalar::Float64;
    const auto data_start = f.tellg();
    f.seekg(0, std::ios::end);
    const auto data_bytes = static_cast<std::size_t>(f.tellg() - data_start);
    f.seekg(data_start);
    const bool binary = format == "binary_little_endian";
    if (vertices > data_bytes / (binary ? stride : 2))
        throwFileError(file, "is truncated: it says " + std::to_string(vertices) +
                                 " vertices, but " + std::to_string(data_bytes) +
                                 " bytes of data follow its header");
    PcdCloud out;
    out.resize(vertices);
    std::fill(out.intensity.begin(), out.intensity.end(), 0.0f);
    WidePoints stored(out, wide);
    if (binary)
    {
        std::vector<char> body(vertices * stride);
        if (!f.read(body.data(), static_cast<std::streamsize>(body.size())))
            throwFileError(file, "is truncated: it says " + std::to_string(vertices) +
                                     " vertices, found " + std::to_string(f.gcount() / stride));
        const char* rec = body.data();
        for (std::size_t p = 0; p < vertices; ++p, rec += stride)
        {
            stored.store(p, binaryValue(rec + props[ix].offset, props[ix].scalar),
                         binaryValue(rec + props[iy].offset, props[iy].scalar),
                         binaryValue(rec + props[iz].offset, props[iz].scalar));
            if (ii >= 0)
                out.intensity[p] =
                    static_cast<float>(binaryValue(rec + props[ii].offset, props[ii].scalar));
        }
        return out;
    }
    std::vector<double> vals(props.size());
    std::string token;
    for (std::size_t p = 0; p < vertices; ++p)
    {
        if (!std::getline(f, line))
            throwFileError(file, "is truncated: it says " + std::to_string(vertices) +
                                     " vertices, found " + std::to_string(p));
        std::istringstream is(line);
        for (std::size_t k = 0; k < props.size(); ++k)
        {
            if (!(is >> token))
                throwFileError(file, "has a short vertex line " + std::to_string(p + 1) + " (" +
                                         std::to_string(k) + " values for " +
                                         std::to_string(props.size()) + ")");
            const auto v = parseNumber(token);
            if (!v)
                throwFileError(file, "vertex line " + std::to_string(p + 1) + ": '" + token +
                                         "' is not a number");
            vals[k] = *v;
        }
        stored.store(p, vals[ix], vals[iy], vals[iz]);
        if (ii >= 0) out.intensity[p] = static_cast<float>(vals[ii]);
    }
    return out;
}

}  // namespace hif::io
