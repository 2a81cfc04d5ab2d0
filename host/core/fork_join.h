// The two recursive calls of a depth-first build step (builders, leaf collapse, flattening): as
// two oneTBB tasks where the subtree is big enough to be worth it, one after the other otherwise.
#pragma once

#include <tbb/parallel_invoke.h>

namespace vkray {

// Recursions over a finished tree fork down to this depth (2^10 tasks at most).
inline constexpr int kParallelDepth = 10;

template <class First, class Second>
void forkJoin(bool parallel, const First& first, const Second& second) {
    if (parallel) {
        tbb::parallel_invoke(first, second);
    } else {
        first();
        second();
    }
}

}  // namespace vkray
