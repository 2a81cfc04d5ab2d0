// The synthetic BenchResults the report tests share: one full scene (five accelerators, a delta
// sweep, a concurrent build, error points with an identical image) and one minimal scene (one
// accelerator, one thread count, nothing else, a name to escape).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bench/bench_results.h"
#include "bench/report.h"

namespace vkray::bench::fixture {

// Per scene: the reference, then per accelerator its render, difference and two heatmaps.
inline constexpr size_t kExpectedImages = (1 + 5 * 4) + (1 + 1 * 4);

Image gradient(int w, int h, float shift);
// A spread of median 0.9 x median to 1.2 x median.
Spread around(double median);
// An accelerator with every figure but the camera-ray times (primaryOnlyMs) and Embree's.
AccelResult makeAccel(const std::string& name, double traceMs, std::vector<ThreadTiming> build, int w, int h,
                      uint32_t nodeBase);
std::vector<ThreadTiming> oneAndTwoThreads(double oneMs, double twoMs);
ErrorPoint errorPoint(const std::string& label, const std::string& group, double buildMs, double traceMs, double rmse);
SceneResult fullScene();
SceneResult minimalScene();
BenchResults results();  // both scenes, --repeat 3, no load average recorded

// How often `needle` occurs in `haystack`, without overlaps.
size_t count(const std::string& haystack, const std::string& needle);

}  // namespace vkray::bench::fixture
