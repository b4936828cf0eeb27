// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   CloudFiles.h
 * @brief  Point-cloud files written point by point (binary PLY and PCD with x y z intensity),
 *         so that a map of any length is written without holding it in memory; and a PCD
 *         reader for the DynamicMap benchmark layout.
 */
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hif/io/Cloud.h"

namespace hif::io
{
/** What a point of a CloudWriter holds besides x y z, in this order. */
struct PointFields
{
    bool intensity = true;  ///< float intensity
    bool colour = false;    ///< uchar red, green, blue (PLY only)
    bool label = false;     ///< uchar class (hif-clean: 0 kept, 1 removed)
    bool scan = false;      ///< uint32 scan: the number of the point's scan
    bool time = false;      ///< double time: its scan's time, seconds
    bool points = false;    ///< uint32 points: how many points were merged into it

    /** x y z and a colour only. */
    static PointFields colourOnly()
    {
        PointFields f;
        f.intensity = false;
        f.colour = true;
        return f;
    }
    /** Bytes of a record after x y z. */
    [[nodiscard]] std::size_t tailBytes() const
    {
        return (intensity ? 4 : 0) + (colour ? 3 : 0) + (label ? 1 : 0) + (scan ? 4 : 0) +
               (time ? 8 : 0) + (points ? 4 : 0);
    }
};

/** A point as CloudWriter::add() takes it: the fields its writer does not hold are ignored. */
struct CloudPoint
{
    double x = 0, y = 0, z = 0;
    float intensity = 0;
    uint8_t red = 0, green = 0, blue = 0;
    uint8_t label = 0;
    uint32_t scan = 0;
    double time = 0;
    uint32_t points = 0;
};

/** Writes the same points to one or more files, each a binary little-endian PLY or a binary PCD
 *  chosen by its extension (.ply or .pcd). A point is x y z and the PointFields chosen (by
 *  default the intensity; a colour only in a PLY). The coordinates are float32 while every one
 *  is below kFloatCoordinateLimit in magnitude (there float32 keeps them to a quarter of a
 *  millimetre); from the first point beyond it (world coordinates: UTM, ENU with a large
 *  offset) the whole file holds float64 (double) x y z, the points written so far converted
 *  once, and the other fields stay as they are. PCL, Open3D, CloudCompare and MRPT read both.
 *  All files have the same body, so it is written once: into the first file, after the room for
 *  its header, when expectCount() says how many digits the count will have; otherwise into
 *  "<first file>.part". close() writes each header (which needs the count) and copies the body
 *  behind the other headers. Throws std::runtime_error naming the file on any I/O failure; the
 *  files are complete only after close(), and a writer destroyed before removes its body. */
class CloudWriter
{
public:
    /** Coordinates at or beyond this magnitude (metres) make the file's x y z float64. */
    static constexpr double kFloatCoordinateLimit = 8192.0;

    explicit CloudWriter(std::vector<std::string> files, PointFields fields = {});
    ~CloudWriter();
    CloudWriter(const CloudWriter&) = delete;
    CloudWriter& operator=(const CloudWriter&) = delete;

    /** The sensor pose a .pcd file states in its VIEWPOINT line (default: identity); set it
     *  before the first point. */
    void setViewpoint(const Eigen::Isometry3d& viewpoint) { viewpoint_ = viewpoint; }
    /** A guess of the final count, before the first point: right to the number of digits, it
     *  saves a copy of the body (wrong, it costs the copy it would have saved). */
    void expectCount(std::size_t count);
    /** Other fields than given at construction, before the first point. */
    void setFields(const PointFields& fields);
    [[nodiscard]] const PointFields& fields() const { return fields_; }
    /** A point with its fields. */
    void add(const CloudPoint& p)
    {
        if (!double_ && needsDouble(p.x, p.y, p.z)) promote();
        char v[24 + kMaxTail];
        std::size_t at = 0;
        if (double_)
        {
            const double xyz[3] = {p.x, p.y, p.z};
            std::memcpy(v, xyz, at = 24);
        }
        else
        {
            const float xyz[3] = {static_cast<float>(p.x), static_cast<float>(p.y),
                                  static_cast<float>(p.z)};
            std::memcpy(v, xyz, at = 12);
        }
        if (fields_.intensity)
        {
            std::memcpy(v + at, &p.intensity, 4);
            at += 4;
        }
        if (fields_.colour)
        {
            v[at] = static_cast<char>(p.red);
            v[at + 1] = static_cast<char>(p.green);
            v[at + 2] = static_cast<char>(p.blue);
            at += 3;
        }
        if (fields_.label) v[at++] = static_cast<char>(p.label);
        if (fields_.scan)
        {
            std::memcpy(v + at, &p.scan, 4);
            at += 4;
        }
        if (fields_.time)
        {
            std::memcpy(v + at, &p.time, 8);
            at += 8;
        }
        if (fields_.points)
        {
            std::memcpy(v + at, &p.points, 4);
            at += 4;
        }
        append(v, at);
    }
    /** A point of x y z and intensity. */
    void add(double x, double y, double z, float intensity)
    {
        CloudPoint p;
        p.x = x;
        p.y = y;
        p.z = z;
        p.intensity = intensity;
        add(p);
    }
    /** A point of x y z and a colour. */
    void add(double x, double y, double z, uint8_t red, uint8_t green, uint8_t blue)
    {
        CloudPoint p;
        p.x = x;
        p.y = y;
        p.z = z;
        p.red = red;
        p.green = green;
        p.blue = blue;
        add(p);
    }
    /** Writes the files; they are complete only after this. */
    void close();
    [[nodiscard]] std::size_t count() const { return count_; }
    /** Whether the files hold float64 coordinates (some point reached kFloatCoordinateLimit). */
    [[nodiscard]] bool doubleCoordinates() const { return double_; }

private:
    static bool needsDouble(double x, double y, double z)
    {
        // NaN compares false: it stays a float NaN.
        return std::abs(x) >= kFloatCoordinateLimit || std::abs(y) >= kFloatCoordinateLimit ||
               std::abs(z) >= kFloatCoordinateLimit;
    }
    void append(const void* record, std::size_t bytes)
    {
        if (used_ + bytes > buf_.size()) flush();
        std::memcpy(buf_.data() + used_, record, bytes);
        used_ += bytes;
        ++count_;
    }
    void open();
    /** Hands what buf_ holds to the background writes (opening the body's file first if
     *  needed); throws if an earlier write failed. */
    void flush();
    /** Throws naming the body's file if a write failed (with `wait`, once the write under way
     *  is done). */
    void throwIfAWriteFailed(bool wait);
    /** From float32 to float64 coordinates: the body written so far is rewritten. */
    void promote();
    [[nodiscard]] std::size_t recordBytes() const;
    [[nodiscard]] std::string viewpointText() const;
    [[nodiscard]] std::string header(const std::string& file, std::size_t count) const;

    std::vector<std::string> files_;
    std::optional<std::size_t> expected_;
    std::string body_file_;        ///< the file the body is written to
    std::size_t body_offset_ = 0;  ///< where the body starts in it
    std::FILE* f_ = nullptr;
    bool closed_ = false;
    bool double_ = false;  ///< float64 coordinates
    std::size_t count_ = 0;
    PointFields fields_;
    static constexpr std::size_t kMaxTail = 24;  ///< tailBytes() with every field
    static constexpr std::size_t kBufferBytes = std::size_t{1} << 19;
    std::vector<char> buf_;  ///< points not yet written
    class BackgroundWrites;
    std::unique_ptr<BackgroundWrites> writes_;  ///< from the first flush() to close()
    std::size_t used_ = 0;                      ///< bytes of buf_ in use
    Eigen::Isometry3d viewpoint_ = Eigen::Isometry3d::Identity();
};

/** A point cloud read from a PCD (or PLY) file: coordinates (float32, relative to `origin`),
 * intensity (0 when absent) and VIEWPOINT. A file with float32 x y z has `origin` zero, so the
 * points are exactly the file's; one with float64 x y z (world coordinates in the millions of
 *  metres) has `origin` at its first finite point, so that the float32 offsets keep the
 *  file's precision (to a millimetre up to 16 km from that point; a scan spans far less). */
struct PcdCloud : Cloud
{
    Eigen::Isometry3d viewpoint = Eigen::Isometry3d::Identity();
    bool has_viewpoint = false;  ///< the file has a VIEWPOINT line
    Eigen::Vector3d origin = Eigen::Vector3d::Zero();

    /** Point i as the file holds it (origin added, in double). */
    [[nodiscard]] Eigen::Vector3d point(std::size_t i) const
    {
        return Eigen::Vector3d(x[i], y[i], z[i]) + origin;
    }
};

/** Reads a PCD file, ASCII, binary or PCL's binary_compressed (fields x y z [intensity] and
 *  others, PCL's padding fields "_" too; x y z float32 or float64, intensity of any number type,
 *  as float32; in ASCII, `nan` for an invalid point, as PCL writes it). Throws
 *  std::runtime_error naming the file and the problem for anything else (missing fields, a
 *  truncated body, compressed data that do not uncompress). */
[[nodiscard]] PcdCloud readPcd(const std::string& file);

/** Reads a PLY point cloud (ASCII or binary little-endian; the vertex element first, with
 *  scalar properties x y z (float or double) and, optionally, intensity (any scalar type; or
 *  CloudCompare's scalar_intensity); other properties and elements are skipped), into a PcdCloud
 *  without a viewpoint, float64 coordinates as readPcd() keeps them. Throws std::runtime_error
 *  naming the file and the problem (big-endian data, no x y z, a truncated body). */
[[nodiscard]] PcdCloud readPly(const std::string& file);

/** The points of `pcd` as float32 coordinates of their own, in place: point(i) (the file's
 *  float64 coordinates, through `origin`) for each, `origin` then zero. For a cloud in a
 *  sensor's frame, whose coordinates float32 holds to well under a millimetre. */
void absorbOrigin(PcdCloud& pcd);

/** The points of `pcd` (world frame) in the frame of its VIEWPOINT, in place: point i becomes
 *  inverse(viewpoint) * point(i), computed in double; `origin` becomes zero. */
void toViewpointFrame(PcdCloud& pcd);

}  // namespace hif::io
