// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Cpu.h
 * @brief  Which code path the per-point passes take: AVX (four points at a time) when the CPU
 *         has it, else scalar. Both give the same bits; the override lets tests and benchmarks
 *         run the scalar path on an AVX machine.
 */
#pragma once

namespace hif::detail
{
/** True when the AVX paths run: the CPU has AVX, this build has the AVX code (x86-64 with
 *  GCC or Clang), and setAvxAllowed(false) was not called. */
[[nodiscard]] bool useAvx();

/** Allows (the default) or forbids the AVX paths, for the whole process. Not to be called
 *  while an insertion or classification is running. */
void setAvxAllowed(bool allowed);

}  // namespace hif::detail
