// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Labels.cpp
 * @brief  .label files and scores.
 */
#include "hif/io/Labels.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "hif/io/FileError.h"

namespace hif::io
{
std::vector<uint32_t> readLabels(const std::string& file)
{
    std::ifstream f(file, std::ios::binary);
    if (!f) throwFileError(file, "cannot be opened (a label file)");
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(file, ec);
    if (ec) throwFileError(file, "has a size that cannot be read: " + ec.message());
    if (bytes % 4 != 0)
        throwFileError(file, "is " + std::to_string(bytes) +
                                 " bytes, not a multiple of 4 (one uint32 label per point)");
    std::vector<uint32_t> v(static_cast<std::size_t>(bytes / 4));
    if (!f.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(bytes)))
        throwFileError(file, "could not be read whole");
    return v;
}

void writeLabels(const std::string& file, const std::vector<uint32_t>& labels)
{
    std::ofstream f(file, std::ios::binary | std::ios::trunc);
    if (!f) throwFileError(file, "cannot be created");
    f.write(reinterpret_cast<const char*>(labels.data()),
            static_cast<std::streamsize>(labels.size() * sizeof(uint32_t)));
    f.close();  // the last bytes are written here
    if (!f) throwFileError(file, "could not be written (disk full?)");
}

void Scores::add(uint32_t truth, bool removed)
{
    if (!isScored(truth))
    {
        ++ignored;
        return;
    }
    if (isMovingClass(truth))
    {
        ++dynamic_total;
        dynamic_removed += removed ? 1 : 0;
    }
    else
    {
        ++static_total;
        static_kept += removed ? 0 : 1;
    }
}

Scores& Scores::operator+=(const Scores& o)
{
    static_total += o.static_total;
    static_kept += o.static_kept;
    dynamic_total += o.dynamic_total;
    dynamic_removed += o.dynamic_removed;
    ignored += o.ignored;
    return *this;
}

double Scores::sa() const
{
    return static_total ? 100.0 * double(static_kept) / double(static_total) : 100.0;
}
double Scores::da() const
{
    return dynamic_total ? 100.0 * double(dynamic_removed) / double(dynamic_total) : 100.0;
}
double Scores::aa() const { return std::sqrt(sa() * da()); }
double Scores::ha() const
{
    const double s = sa(), d = da();
    return s + d > 0 ? 2.0 * s * d / (s + d) : 0.0;
}

}  // namespace hif::io
