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
#include <optional>
#include <string>
#include <vector>

#include "hif/io/Cloud.h"

namespace hif::io
{
/** Writes the same points to one or more files, each a binary little-endian PLY or a binary PCD
 *  chosen by its extension (.ply or .pcd). A point is x y z intensity, or, for a writer made
 *  with Record::XyzRgb (PLY only), x y z and a colour (red, green, blue: uchar). The
 *  coordinates are float32 while every one is below kFloatCoordinateLimit in magnitude (there
 *  float32 keeps them to a quarter of a millimetre); from the first point beyond it (world
 *  coordinates: UTM, ENU with a large offset) the whole file holds float64 (double) x y z, the
 *  points written so far converted once, and the intensity stays float32. PCL, Open3D,
 *  CloudCompare and MRPT read both. All files have the same body, so it is written once: into
 *  the first file, after the room for its header, when expectCount() says how many digits the
 *  count will have; otherwise into "<first file>.part". close() writes each header (which needs
 *  the count) and copies the body behind the other headers. Throws std::runtime_error naming
 *  the file on any I/O failure; the files are complete only after close(), and a writer
 *  destroyed before removes its body. */
class CloudWriter
{
public:
    enum class Record
    {
        XyzIntensity,
        XyzRgb
    };
    /** Coordinates at or beyond this magnitude (metres) make the file's x y z float64. */
    static constexpr double kFloatCoordinateLimit = 8192.0;

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
    void add(double x, double y, double z, float intensity)
    {
        if (!double_ && needsDouble(x, y, z)) promote();
        if (double_)
        {
            char v[28];
            const double xyz[3] = {x, y, z};
            std::memcpy(v, xyz, 24);
            std::memcpy(v + 24, &intensity, 4);
            append(v, sizeof v);
        }
        else
        {
            const float v[4] = {static_cast<float>(x), static_cast<float>(y), static_cast<float>(z),
                                intensity};
            append(v, sizeof v);
        }
    }
    /** A point of a Record::XyzRgb writer. */
    void add(double x, double y, double z, uint8_t red, uint8_t green, uint8_t blue)
    {
        if (!double_ && needsDouble(x, y, z)) promote();
        char v[27];
        std::size_t at = 0;
        if (double_)
        {
            const double xyz[3] = {x, y, z};
            std::memcpy(v, xyz, at = 24);
        }
        else
        {
            const float xyz[3] = {static_cast<float>(x), static_cast<float>(y),
                                  static_cast<float>(z)};
            std::memcpy(v, xyz, at = 12);
        }
        v[at] = static_cast<char>(red);
        v[at + 1] = static_cast<char>(green);
        v[at + 2] = static_cast<char>(blue);
        append(v, at + 3);
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
    /** Writes what buf_ holds (opening the body's file first if needed). */
    void flush();
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
    Record record_;
    std::vector<char> buf_;  ///< points not yet written
    std::size_t used_ = 0;   ///< bytes of buf_ in use
    Eigen::Isometry3d viewpoint_ = Eigen::Isometry3d::Identity();
};

/** A point cloud read from a PCD file: coordinates (float32, relative to `origin`), intensity
 *  (0 when absent) and VIEWPOINT. A file with float32 x y z has `origin` zero, so the points
 *  are exactly the file's; one with float64 x y z (world coordinates in the millions of
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

/** Reads an ASCII or binary PCD file (fields x y z [intensity] and others; x y z float32 or
 *  float64, intensity float32; in ASCII, `nan` for an invalid point, as PCL writes it).
 *  Throws std::runtime_error naming the file and the problem for anything else (compressed
 *  data, missing fields, a truncated body). */
[[nodiscard]] PcdCloud readPcd(const std::string& file);

/** The points of `pcd` (world frame) in the frame of its VIEWPOINT, in place: point i becomes
 *  inverse(viewpoint) * point(i), computed in double; `origin` becomes zero. */
void toViewpointFrame(PcdCloud& pcd);

}  // namespace hif::io
