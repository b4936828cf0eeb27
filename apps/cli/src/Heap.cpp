// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Heap.cpp
 * @brief  glibc's allocator settings for scan-by-scan runs.
 */
#include "hif/apps/Heap.h"

#include <malloc.h>

namespace hif::apps
{
void keepScanBuffersInTheHeap()
{
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
    mallopt(M_ARENA_MAX, 1);
}

void returnFreeHeap() { malloc_trim(0); }

}  // namespace hif::apps
