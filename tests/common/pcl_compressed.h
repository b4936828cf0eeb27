// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   pcl_compressed.h
 * @brief  PCD files as PCL writes them with DATA binary_compressed (its
 * savePCDFileBinaryCompressed), for the readers' tests: the fields packed one after the other, then
 * LZF.
 */
#pragma once

#include <lzf.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hif::test
{
/** PCL's compressed body for `packed` (each field's values for every point, one field after
 *  the other, padding left out): the compressed and the uncompressed size (little-endian
 *  uint32), then the LZF data. */
inline std::vector<char> pclCompressedBody(const std::vector<char>& packed)
{
    std::vector<char> lzf(packed.size() + packed.size() / 16 + 64);
    const unsigned n = lzf_compress(packed.data(), static_cast<unsigned>(packed.size()), lzf.data(),
                                    static_cast<unsigned>(lzf.size()));
    if (n == 0) throw std::runtime_error("pclCompressedBody: lzf_compress failed");
    std::vector<char> out(8 + n);
    const uint32_t sizes[2] = {n, static_cast<uint32_t>(packed.size())};
    for (std::size_t k = 0; k < 8; ++k)
        out[k] = static_cast<char>((sizes[k / 4] >> (8 * (k % 4))) & 0xff);
    std::copy_n(lzf.data(), n, out.data() + 8);
    return out;
}

/** Writes `file`: a PCD of float32 x y z intensity, binary_compressed. */
inline void writePclCompressedPcd(const std::string& file, const std::vector<float>& x,
                                  const std::vector<float>& y, const std::vector<float>& z,
                                  const std::vector<float>& intensity)
{
    const std::size_t n = x.size();
    std::vector<char> packed(16 * n);
    char* at = packed.data();
    for (const std::vector<float>* field : {&x, &y, &z, &intensity})
    {
        std::memcpy(at, field->data(), 4 * n);
        at += 4 * n;
    }
    const std::vector<char> body = pclCompressedBody(packed);
    std::ofstream f(file, std::ios::binary);
    f << "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n"
         "SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\nWIDTH "
      << n << "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " << n << "\nDATA binary_compressed\n";
    f.write(body.data(), static_cast<std::streamsize>(body.size()));
}

}  // namespace hif::test
