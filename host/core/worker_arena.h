// The oneTBB arena of a command's --threads: 0 means every core.
#pragma once

#include <tbb/task_arena.h>

namespace vkray {

// The concurrency of a tbb::task_arena for `threads` (--threads, BuildOptions::threads): the count
// itself, or oneTBB's default (all cores) for 0 and below.
inline int arenaThreads(int threads) { return threads > 0 ? threads : tbb::task_arena::automatic; }

}  // namespace vkray
