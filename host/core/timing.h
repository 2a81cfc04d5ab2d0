// Wall-clock time on the host, for build phases, uploads and the figures of --stats and `vkray bench`
// (GPU time comes from timestamp queries instead: gpu/batch_timer.h).
#pragma once

#include <chrono>

namespace vkray {

using Clock = std::chrono::steady_clock;

// Milliseconds from `start` to now.
inline double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace vkray
