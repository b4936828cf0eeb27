// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Simd.h
 * @brief  Whether this build has the AVX versions of the per-point passes (x86-64, GCC or
 *         Clang; chosen at run time by detail::useAvx()), and their intrinsics.
 */
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define HIF_X86_AVX 1
#include <immintrin.h>
#else
#define HIF_X86_AVX 0
#endif
