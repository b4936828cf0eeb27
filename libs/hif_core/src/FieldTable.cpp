// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   FieldTable.cpp
 * @brief  Messages of the field tables' validation.
 */
#include "hif/FieldTable.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace hif
{
std::string Bounds::describe() const
{
    std::ostringstream os;
    const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
    if (has_lo && has_hi)
        os << "in " << (lo_open ? '(' : '[') << lo << ", " << hi << (hi_open ? ')' : ']');
    else if (has_lo)
        os << (lo_open ? "> " : ">= ") << lo;
    else if (has_hi)
        os << (hi_open ? "< " : "<= ") << hi;
    else
        os << "a finite number";
    return os.str();
}

void throwInvalid(const char* owner, const char* field, double value,
                  const std::string& requirement)
{
    std::ostringstream os;
    os << owner << ": invalid " << field << " = " << value << " (must be " << requirement << ")";
    throw std::invalid_argument(os.str());
}

}  // namespace hif
