// The bookkeeping of a bench run around its measurements (bench_runner.h): the run's facts, the
// results as they stand after each scene, and the save of the finished scenes when the run fails.
// Internal to host/bench.
#pragma once

#include <string>

#include "bench/bench_results.h"
#include "bench/bench_runner.h"
#include "core/timing.h"
#include "gpu/vulkan_context.h"

namespace vkray::bench {

// The run's facts before it measures: vkray, the machine, the device, the settings, the shard.
BenchResults runHeader(const gpu::VulkanContext& ctx, const BenchOptions& options, const std::string& commandLine);

// A run that continues `previous`, read from `file` (bench_resume.h: checkResumable refuses another
// run's), keeps its scenes and its start.
void continueFrom(const BenchResults& previous, const std::string& file, BenchResults& results);

// The results as the run stands: scenes in run order, the time since `start` after `before` seconds
// of earlier runs, and `failure` (BenchResults::failure).
void stampResults(BenchResults& results, Clock::time_point start, double before, std::string failure);

// Called in a catch block: saves the finished scenes, marked with the caught error, then rethrows
// it (or, when the save fails, an error naming both).
[[noreturn]] void saveAndRethrow(BenchResults& results, Clock::time_point start, double before, const BenchSaveFn& save);

}  // namespace vkray::bench
