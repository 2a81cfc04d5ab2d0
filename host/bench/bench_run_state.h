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

// The run's facts before it measures: vkray, the machine, the settings, the shard. The device's
// come with setDevice, once it is open.
BenchResults runHeader(const BenchOptions& options, const std::string& commandLine);
void setDevice(BenchResults& results, const gpu::VulkanContext& ctx);

// A run that continues `previous`, read from `file` (bench_resume.h: checkResumableSettings refuses
// another run's), keeps its scenes and its start. Its device is checked once open (checkResumable).
void continueFrom(const BenchResults& previous, const std::string& file, BenchResults& results);

// The results as the run stands: scenes in run order, the time since `start` after `before` seconds
// of earlier runs, and `failure` (BenchResults::failure).
void stampResults(BenchResults& results, Clock::time_point start, double before, std::string failure);

// Called in a catch block: saves the finished scenes, marked with the caught error, then rethrows
// it (or, when the save fails, an error naming both).
[[noreturn]] void saveAndRethrow(BenchResults& results, Clock::time_point start, double before, const BenchSaveFn& save);

}  // namespace vkray::bench
