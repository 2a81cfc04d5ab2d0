// What `vkray bench` checks before it measures anything, so that a run of many scenes does not
// fail on its last one after hours of measuring: the options, and every scene the run will measure
// loaded as it will be measured, on the run's device. Internal to host/bench.
#pragma once

#include <vector>

#include "bench/bench_runner.h"
#include "render/device.h"

namespace vkray::bench {

// Refuses (vkray::Error) options out of range, an unknown accelerator or tuning, no scene.
void checkBenchOptions(const BenchOptions& options);

// Loads every scene with the host memory check (render::withinMemory) and refuses the first that
// does not load, would not fit the process's memory or has nothing to render
// (render::checkRenderable). Before the device is waited for: starting a Vulkan driver needs memory
// of its own, so under a tight limit the scene's one-line refusal must come first.
void checkBenchScenesOnHost(const BenchOptions& options);

// Loads each scene i with `measure[i]` (meshes and all), with the run's view, and refuses the first
// that does not load, has nothing to render (render::checkRenderable) or does not fit the device
// (render::Device::checkFits): each error names its file (and line). Opens the device, which refuses
// an accelerator it cannot run (rayquery without VK_KHR_ray_query). The scenes are not kept: the
// runner loads each again when it measures it, so that only one is in memory at a time.
void checkBenchScenes(render::Device& device, const BenchOptions& options, const std::vector<bool>& measure);

}  // namespace vkray::bench
