// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   map_bytes.h
 * @brief  Test helpers: a map as the bytes of its serialization, and what reading bytes back
 *         into a map says (for tests that corrupt a file on purpose).
 */
#pragma once

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdint>
#include <exception>
#include <string>
#include <vector>

#include "hif/CHeightIntervalMap.h"

namespace hif::test
{
/** The bytes MRPT writes for `map`. */
inline std::vector<uint8_t> mapBytes(const hif::CHeightIntervalMap& map)
{
    mrpt::io::CMemoryStream buf;
    auto out = mrpt::serialization::archiveFrom(buf);
    out << map;
    const auto* data = static_cast<const uint8_t*>(buf.getRawBufferData());
    return {data, data + buf.getTotalBytesCount()};
}

/** Reads `bytes` into a map: the error's message, or "" when it loaded. */
inline std::string loadError(const std::vector<uint8_t>& bytes)
{
    mrpt::io::CMemoryStream in_buf;
    in_buf.Write(bytes.data(), bytes.size());
    in_buf.Seek(0);
    auto in = mrpt::serialization::archiveFrom(in_buf);
    hif::CHeightIntervalMap loaded;
    try
    {
        in >> loaded;
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return "";
}
}  // namespace hif::test
