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

// Loads each scene i with `measure[i]` (meshes and all) with the host memory check
// (render::withinMemory) and refuses the first that does not load, would not fit the process's
// memory or has nothing to render (render::checkRenderable); each error names its file (and line).
// Gives the size of each scene for checkBenchScenesOnDevice, in the order of `measure`'s trues. The
// scenes are not kept: the runner loads each again when it measures it, so that only one is in
// memory at a time. Before the device is waited for: starting a Vulkan driver needs memory of its
// own, so under a tight limit the scene's one-line refusal must come first.
std::vector<render::SceneSize> checkBenchScenesOnHost(const BenchOptions& options, const std::vector<bool>& measure);

// Refuses the first scene that does not fit the device (render::Device::checkFits), naming its
// file. Opens the device, which refuses an accelerator it cannot run (rayquery without
// VK_KHR_ray_query).
void checkBenchScenesOnDevice(render::Device& device, const std::vector<render::SceneSize>& scenes);

}  // namespace vkray::bench
