// Wall-clock time on the host, for build phases, uploads and the figures of --stats and `vkray bench`
// (GPU time comes from timestamp queries instead: gpu/batch_timer.h).
#pragma once

#include <chrono>
#include <cstdint>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

namespace vkray {

using Clock = std::chrono::steady_clock;

// Milliseconds from `start` to now.
inline double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// A cheap clock for timing many short steps (a builder's phases, per node): the processor's tick
// counter where there is one, turned into milliseconds against the wall clock by the caller.
inline uint64_t ticks() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return uint64_t(Clock::now().time_since_epoch().count());
#endif
}

}  // namespace vkray
