// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Heap.h
 * @brief  How an app that handles scan after scan asks glibc's allocator to keep its buffers.
 */
#pragma once

namespace hif::apps
{
/** For a run over many scans, before the first: every scan allocates and frees the same few
 *  buffers of megabytes (points, labels, range images). By default glibc maps each one afresh
 *  and unmaps it when freed, and every page is then faulted in and zeroed again, scan after
 *  scan; kept in the heap they are reused. One heap for every thread (a reader thread and the
 *  main one): what one frees the other reuses (a second arena kept 55 MB of it). */
void keepScanBuffersInTheHeap();

/** After the last scan: the heap's free memory goes back to the system. */
void returnFreeHeap();

}  // namespace hif::apps
