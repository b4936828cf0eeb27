// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file   Parallel.h
 * @brief  The grid's threads: a TBB arena of a fixed size, and a loop over ranges that runs on
 *         the calling thread when there is no arena.
 */
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace hif::detail
{
struct ThreadArena
{
    // No more threads than TBB will run (it warns and ignores the rest).
    explicit ThreadArena(std::size_t threads)
        : arena(std::min(static_cast<int>(std::min<std::size_t>(threads, 1024)),
                         tbb::info::default_concurrency()))
    {
    }
    tbb::task_arena arena;
};

/** Calls f(begin, end) over [0, n) in chunks of at least `grain`: on this thread when `arena`
 *  is null or n <= grain, else in parallel in the arena. */
template <typename F>
void forRanges(ThreadArena* arena, std::size_t n, std::size_t grain, F&& f)
{
    if (!arena || n <= grain)
    {
        f(std::size_t{0}, n);
        return;
    }
    arena->arena.execute(
        [&]
        {
            tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                              [&](const tbb::blocked_range<std::size_t>& r)
                              { f(r.begin(), r.end()); });
        });
}

}  // namespace hif::detail
