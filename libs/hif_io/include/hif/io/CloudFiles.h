// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CloudFiles.h
 * @brief  Point-cloud files written point by point (binary PLY and PCD with x y z intensity),
 *         so that a map of any length is written without holding it in memory; and a PCD
 *         reader for the DynamicMap benchmark layout.
 */
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "hif/io/Cloud.h"

namespace hif::io
{
/** Writes the same points to one or more files, each a binary little-endian PLY or a binary PCD
 *  chosen by its extension (.ply or .pcd). A point is x y z intensity (float32 each), or, for a
 *  writer made with Record::XyzRgb (PLY only), x y z (float32) and a colour (red, green, blue:
 *  uchar). All files have the same body, so it is written once: into the first file, after the
 *  room for its header, when expectCount() says how many digits the count will have; otherwise
 *  into "<first file>.part". close() writes each header (which needs the count) and copies the
 *  body behind the other headers. Throws std::runtime_error naming the file on any I/O failure;
 *  the files are complete only after close(), and a writer destroyed before removes its body. */
class CloudWriter
{
public:
    enum class Record
    {
        XyzIntensity,
        XyzRgb
    };

    explicit CloudWriter(std::vector<std::string> files, Record record = Record::XyzIntensity);
    ~CloudWriter();
    CloudWriter(const CloudWriter&) = delete;
    CloudWriter& operator=(const CloudWriter&) = delete;

    /** The sensor pose a .pcd file states in its VIEWPOINT line (default: identity); set it
     *  before the first point. */
    void setViewpoint(const Eigen::Isometry3d& viewpoint) { viewpoint_ = viewpoint; }
    /** A guess of the final count, before the first point: right to the number of digits, it
     *  saves a copy of the body (wrong, it costs the copy it would have saved). */
    void expectCount(std::size_t count);
    /** A point of a Record::XyzIntensity writer. */
    void add(float x, float y, float z, float intensity)
    {
        const float v[4] = {x, y, z, intensity};
        append(v, sizeof v);
    }
    /** A point of a Record::XyzRgb writer. */
    void add(float x, float y, float z, uint8_t red, uint8_t green, uint8_t blue)
    {
        char v[15];
        const float xyz[3] = {x, y, z};
        std::memcpy(v, xyz, 12);
        v[12] = static_cast<char>(red);
        v[13] = static_cast<char>(green);
        v[14] = static_cast<char>(blue);
        append(v, sizeof v);
    }
    /** Writes the files; they are complete only after this. */
    void close();
    [[nodiscard]] std::size_t count() const { return count_; }

private:
    void append(const void* record, std::size_t bytes)
    {
        if (used_ + bytes > buf_.size()) flush();
        std::memcpy(buf_.data() + used_, record, bytes);
        used_ += bytes;
        ++count_;
    }
    void open();
    /** Writes what buf_ holds (opening the body's file first if needed). */
    void flush();
    [[nodiscard]] std::string viewpointText() const;
    [[nodiscard]] std::string header(const std::string& file, std::size_t count) const;

    std::vector<std::string> files_;
    std::optional<std::size_t> expected_;
    std::string body_file_;        ///< the file the body is written to
    std::size_t body_offset_ = 0;  ///< where the body starts in it
    std::FILE* f_ = nullptr;
    bool closed_ = false;
    std::size_t count_ = 0;
    Record record_;
    std::vector<char> buf_;  ///< points not yet written
    std::size_t used_ = 0;   ///< bytes of buf_ in use
    Eigen::Isometry3d viewpoint_ = Eigen::Isometry3d::Identity();
};

/** A point cloud read from a PCD file: coordinates, intensity (0 when absent) and VIEWPOINT. */
struct PcdCloud : Cloud
{
    Eigen::Isometry3d viewpoint = Eigen::Isometry3d::Identity();
};

/** Reads an ASCII or binary PCD file (fields x y z [intensity] and others, float32 x y z).
 *  Throws std::runtime_error naming the file and the problem for anything else (compressed
 *  data, missing fields, a truncated body). */
[[nodiscard]] PcdCloud readPcd(const std::string& file);

}  // namespace hif::io
