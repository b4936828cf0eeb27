// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Cpu.cpp
 * @brief  AVX detection (once) and its override.
 */
#include "hif/detail/Cpu.h"

#include <atomic>

#include "Simd.h"

namespace hif::detail
{
namespace
{
std::atomic<bool> avx_allowed{true};

bool cpuHasAvx()
{
#if HIF_X86_AVX
    static const bool has_avx = __builtin_cpu_supports("avx");
    return has_avx;
#else
    return false;
#endif
}
}  // namespace

bool useAvx() { return cpuHasAvx() && avx_allowed.load(std::memory_order_relaxed); }

void setAvxAllowed(bool allowed) { avx_allowed.store(allowed, std::memory_order_relaxed); }

}  // namespace hif::detail
