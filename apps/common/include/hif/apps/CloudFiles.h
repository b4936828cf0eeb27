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
#include <cstdio>
#include <string>
#include <vector>

namespace hif::apps
{
/** Writes x y z intensity (float32 each) to a binary little-endian PLY or a binary PCD file,
 *  chosen by the extension (.ply or .pcd). The point count in the header is filled in by
 *  close(). Throws std::runtime_error naming the file on any I/O failure. */
class CloudWriter
{
public:
    explicit CloudWriter(const std::string& file);
    ~CloudWriter();
    CloudWriter(const CloudWriter&) = delete;
    CloudWriter& operator=(const CloudWriter&) = delete;

    void add(float x, float y, float z, float intensity);
    /** Writes the final header; the file is complete only after this. */
    void close();
    [[nodiscard]] std::size_t count() const { return count_; }
    [[nodiscard]] const std::string& file() const { return file_; }

private:
    void writeHeader();
    std::string file_;
    bool ply_ = true;
    std::FILE* f_ = nullptr;
    std::size_t count_ = 0;
    std::vector<float> buf_;
};

/** A point cloud read from a PCD file: coordinates, intensity (0 when absent) and VIEWPOINT. */
struct PcdCloud
{
    std::vector<float> x, y, z, intensity;
    Eigen::Isometry3d viewpoint = Eigen::Isometry3d::Identity();
};

/** Reads an ASCII or binary PCD file (fields x y z [intensity] and others, float32 x y z).
 *  Throws std::runtime_error naming the file and the problem for anything else (compressed
 *  data, missing fields, a truncated body). */
[[nodiscard]] PcdCloud readPcd(const std::string& file);

}  // namespace hif::apps
