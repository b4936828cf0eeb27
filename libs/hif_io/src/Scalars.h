// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Scalars.h
 * @brief  The readers' scalar types (PLY's and PCD's): their sizes, and a binary little-endian
 *         value of any of them as a double.
 */
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace hif::io
{
enum class Scalar
{
    Int8,
    Uint8,
    Int16,
    Uint16,
    Int32,
    Uint32,
    Int64,
    Uint64,
    Float32,
    Float64,
    None
};

/** Bytes of a value of type `s` (0 for None). */
inline std::size_t bytesOf(Scalar s)
{
    switch (s)
    {
        case Scalar::Int8:
        case Scalar::Uint8:
            return 1;
        case Scalar::Int16:
        case Scalar::Uint16:
            return 2;
        case Scalar::Int32:
        case Scalar::Uint32:
        case Scalar::Float32:
            return 4;
        case Scalar::Int64:
        case Scalar::Uint64:
        case Scalar::Float64:
            return 8;
        case Scalar::None:
            break;
    }
    return 0;
}

/** A binary little-endian value of type `s` (not None) at `at`, as a double. */
inline double binaryValue(const char* at, Scalar s)
{
    const auto get = [at](auto v)
    {
        std::memcpy(&v, at, sizeof v);
        return static_cast<double>(v);
    };
    switch (s)
    {
        case Scalar::Int8:
            return get(int8_t{});
        case Scalar::Uint8:
            return get(uint8_t{});
        case Scalar::Int16:
            return get(int16_t{});
        case Scalar::Uint16:
            return get(uint16_t{});
        case Scalar::Int32:
            return get(int32_t{});
        case Scalar::Uint32:
            return get(uint32_t{});
        case Scalar::Int64:
            return get(int64_t{});
        case Scalar::Uint64:
            return get(uint64_t{});
        case Scalar::Float32:
            return get(float{});
        case Scalar::Float64:
        case Scalar::None:
            break;
    }
    return get(double{});
}

/** The scalar of a PCD field of TYPE `type` (I, U or F) and SIZE `size`; None for another. */
inline Scalar pcdScalar(char type, int size)
{
    switch (type)
    {
        case 'I':
            return size == 1   ? Scalar::Int8
                   : size == 2 ? Scalar::Int16
                   : size == 4 ? Scalar::Int32
                   : size == 8 ? Scalar::Int64
                               : Scalar::None;
        case 'U':
            return size == 1   ? Scalar::Uint8
                   : size == 2 ? Scalar::Uint16
                   : size == 4 ? Scalar::Uint32
                   : size == 8 ? Scalar::Uint64
                               : Scalar::None;
        case 'F':
            return size == 4 ? Scalar::Float32 : size == 8 ? Scalar::Float64 : Scalar::None;
        default:
            return Scalar::None;
    }
}

}  // namespace hif::io
