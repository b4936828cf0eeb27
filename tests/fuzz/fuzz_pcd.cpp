// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   fuzz_pcd.cpp
 * @brief  libFuzzer target: the PCD reader (DynamicMap benchmark scans). The input is the file;
 *         it must be read or rejected with an exception, never crash.
 */
#include <exception>

#include "FuzzFiles.h"
#include "hif/io/CloudFiles.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size)
{
    using namespace hif::fuzz;
    const auto file = workDir() / "scan.pcd";
    writeFile(file, std::string_view(reinterpret_cast<const char*>(data), size));
    try
    {
        const auto pcd = hif::io::readPcd(file.string());
        (void)pcd;
    }
    catch (const std::exception&)
    {
    }
    return 0;
}
