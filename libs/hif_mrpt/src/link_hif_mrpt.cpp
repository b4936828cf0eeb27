// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   link_hif_mrpt.cpp
 * @brief  Compiled into every program that links hif::hif_mrpt (an interface source of the
 *         target): it references the library, so that a linker that drops libraries no symbol
 *         is taken from (--as-needed, Debian's default) keeps it, and the library's MRPT class
 *         and map registrations run. A program that only creates maps from an .ini, as MRPT's
 *         own tools do, names no hif symbol of its own.
 */
namespace hif
{
int linkHifMrpt();
}

namespace
{
[[maybe_unused]] const int hif_mrpt_linked = hif::linkHifMrpt();
}
