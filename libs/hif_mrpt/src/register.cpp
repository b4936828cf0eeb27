// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   register.cpp
 * @brief  Registers hif's classes with MRPT's class factory when the library is loaded.
 */
#include <mrpt/core/initializer.h>
#include <mrpt/rtti/CObject.h>

#include "hif/CHeightIntervalMap.h"

namespace hif
{
/** Referenced by link_hif_mrpt.cpp in every program that links hif_mrpt (see there). */
int linkHifMrpt() { return 1; }
}  // namespace hif

MRPT_INITIALIZER(register_hif_mrpt)
{
    using namespace mrpt::rtti;
    registerClass(CLASS_ID(hif::CHeightIntervalMap));
}
