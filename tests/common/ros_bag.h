// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   ros_bag.h
 * @brief  ROS 1 bags (format 2.0) of sensor_msgs/PointCloud2 messages, as a LiDAR driver
 *         records them, for the tests of MRPT's rosbag2rawlog path: written by hand, since
 *         Debian's rosbag library needs pluginlib's headers to write one. One chunk, not
 *         compressed; the connection, the chunk's index and the chunk info after it, as rosbag
 *         reads them.
 */
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace hif::test
{
/** One sensor_msgs/PointCloud2 message: its time (seconds) and its points, x y z intensity
 *  (float32 each, in the sensor's frame). */
struct BagCloud
{
    double time = 0.0;
    std::vector<float> xyzi;
};

namespace bag_detail
{
/** Little-endian bytes. */
struct Bytes
{
    std::string b;
    void u8(uint8_t v) { b.push_back(static_cast<char>(v)); }
    void u32(uint32_t v)
    {
        for (int i = 0; i < 4; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
    }
    void u64(uint64_t v)
    {
        for (int i = 0; i < 8; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
    }
    /** A ROS string or byte array: its length (uint32), then its bytes. */
    void str(const std::string& s)
    {
        u32(static_cast<uint32_t>(s.size()));
        b += s;
    }
};
inline std::string u32(uint32_t v)
{
    Bytes x;
    x.u32(v);
    return x.b;
}
inline std::string u64(uint64_t v)
{
    Bytes x;
    x.u64(v);
    return x.b;
}
/** A ROS time: seconds and nanoseconds, uint32 each. */
inline std::string rosTime(double t)
{
    const auto sec = static_cast<uint32_t>(std::floor(t));
    const auto nsec =
        static_cast<uint32_t>(std::min<long long>(std::llround((t - sec) * 1e9), 999999999LL));
    Bytes x;
    x.u32(sec);
    x.u32(nsec);
    return x.b;
}
/** Record header fields: each its length (uint32), then "name=value". */
inline std::string fields(const std::vector<std::pair<std::string, std::string>>& f)
{
    Bytes x;
    for (const auto& [name, value] : f)
    {
        x.u32(static_cast<uint32_t>(name.size() + 1 + value.size()));
        x.b += name + "=" + value;
    }
    return x.b;
}
/** A record: its header's length and header, its data's length and data. */
inline std::string record(const std::vector<std::pair<std::string, std::string>>& header,
                          const std::string& data)
{
    Bytes x;
    x.str(fields(header));
    x.str(data);
    return x.b;
}
inline std::string op(uint8_t code) { return std::string(1, static_cast<char>(code)); }
}  // namespace bag_detail

/** Writes `file`: the clouds (times increasing) as sensor_msgs/PointCloud2 messages on
 *  `topic`, in frame `frame`, fields x y z intensity (FLOAT32). */
inline void writeRosBag(const std::string& file, const std::string& topic, const std::string& frame,
                        const std::vector<BagCloud>& clouds)
{
    using namespace bag_detail;
    if (clouds.empty()) throw std::invalid_argument("writeRosBag: no cloud");
    // The message type as sensor_msgs defines it (its MD5 sum is what rosbag checks).
    const std::string connection =
        record({{"op", op(0x07)}, {"conn", u32(0)}, {"topic", topic}},
               fields({{"topic", topic},
                       {"type", "sensor_msgs/PointCloud2"},
                       {"md5sum", "1158d486dd51d683ce2f1be655c3c181"},
                       {"message_definition",
                        "std_msgs/Header header\nuint32 height\nuint32 width\n"
                        "sensor_msgs/PointField[] fields\nbool is_bigendian\nuint32 point_step\n"
                        "uint32 row_step\nuint8[] data\nbool is_dense\n"}}));
    std::string chunk = connection;
    Bytes index;  // per message: its time and where its record starts in the chunk
    for (std::size_t k = 0; k < clouds.size(); ++k)
    {
        const BagCloud& c = clouds[k];
        const auto n = static_cast<uint32_t>(c.xyzi.size() / 4);
        Bytes m;
        m.u32(static_cast<uint32_t>(k));  // header: seq, stamp, frame_id
        m.b += rosTime(c.time);
        m.str(frame);
        m.u32(1);  // height: an unorganized cloud
        m.u32(n);  // width
        m.u32(4);
        const char* names[4] = {"x", "y", "z", "intensity"};
        for (uint32_t f = 0; f < 4; ++f)
        {
            m.str(names[f]);
            m.u32(4 * f);  // offset
            m.u8(7);       // FLOAT32
            m.u32(1);      // count
        }
        m.u8(0);        // is_bigendian
        m.u32(16);      // point_step
        m.u32(16 * n);  // row_step
        std::string data(16 * static_cast<std::size_t>(n), '\0');
        std::memcpy(data.data(), c.xyzi.data(), data.size());
        m.str(data);
        m.u8(1);  // is_dense
        index.b += rosTime(c.time);
        index.u32(static_cast<uint32_t>(chunk.size()));
        chunk += record({{"op", op(0x02)}, {"conn", u32(0)}, {"time", rosTime(c.time)}}, m.b);
    }
    const std::string magic = "#ROSBAG V2.0\n";
    constexpr std::size_t kHeaderRecord = 4096;  // padded, as rosbag writes it
    const uint64_t chunk_pos = magic.size() + kHeaderRecord;
    std::string body = record({{"op", op(0x05)},
                               {"compression", "none"},
                               {"size", u32(static_cast<uint32_t>(chunk.size()))}},
                              chunk);
    body += record({{"op", op(0x04)},
                    {"ver", u32(1)},
                    {"conn", u32(0)},
                    {"count", u32(static_cast<uint32_t>(clouds.size()))}},
                   index.b);
    const uint64_t index_pos = chunk_pos + body.size();
    body += connection;
    Bytes counts;  // per connection in the chunk: its messages
    counts.u32(0);
    counts.u32(static_cast<uint32_t>(clouds.size()));
    body += record({{"op", op(0x06)},
                    {"ver", u32(1)},
                    {"chunk_pos", u64(chunk_pos)},
                    {"start_time", rosTime(clouds.front().time)},
                    {"end_time", rosTime(clouds.back().time)},
                    {"count", u32(1)}},
                   counts.b);
    const std::string header = fields({{"op", op(0x03)},
                                       {"index_pos", u64(index_pos)},
                                       {"conn_count", u32(1)},
                                       {"chunk_count", u32(1)}});
    Bytes head;
    head.str(header);
    head.str(std::string(kHeaderRecord - 8 - header.size(), ' '));
    std::ofstream out(file, std::ios::binary);
    out << magic << head.b << body;
    if (!out) throw std::runtime_error("writeRosBag: cannot write '" + file + "'");
}

}  // namespace hif::test
