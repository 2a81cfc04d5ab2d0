// Memory known before the work: what a render of a scene will need of the host and of the device,
// estimated from its triangle count for the chosen accelerator, and checked against what the
// machine and the device have before the scene's triangles are made, before the structure is built
// and before anything is uploaded. A scene that cannot fit is refused with one line naming what it
// needs, what there is, and the accelerator that needs less, rather than ending in the kernel's OOM
// killer or a driver's allocation failure hours into a build.
//
// The model (memory_budget.cpp) counts the scene's arrays, the builder's peak and the arrays in the
// kernel's layout per triangle; its per-triangle figures and the measurements behind them are in
// docs/outputs.md, "Memory".
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>

#include "accel/accel_spec.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray::render {

// What the estimate is for: the accelerator, and where the frame is traced.
struct MemoryUse {
    accel::AccelSpec accel;
    bool gpuData = false;  // the arrays in the kernel's layout (a GPU render, --build-only)
    bool device = false;   // a GPU render: the device buffers
    bool build = true;     // built here; else read from a structure file (--load-accel)
    // A device that allocates from the host's memory (a CPU device, as lavapipe): its buffers count
    // against the host's limits too.
    bool deviceSharesHost = false;
};

struct MemoryEstimate {
    uint64_t hostBytes = 0;      // the process's peak: scene, build, arrays, device buffers staged
    uint64_t deviceBytes = 0;    // device-local buffers, 0 without a device
    uint64_t structureBytes = 0; // of both, the structure's arrays in the kernel's layout
};

// What the memory of a scene's render depends on: its size, and the file to name when it does not
// fit. Kept where a scene is checked long before it is rendered (`vkray bench` checks every scene
// before its first measurement but holds one in memory at a time).
struct SceneSize {
    uint64_t triangles = 0;
    uint64_t normals = 0;  // triangles with vertex normals
    std::filesystem::path sourceFile;
};
inline SceneSize sizeOf(const Scene& scene) {
    return SceneSize{scene.triangles.size(), scene.normals.size(), scene.sourceFile};
}

// The estimate for a scene of `triangles` triangles, `normals` of them with vertex normals.
MemoryEstimate estimateMemory(uint64_t triangles, uint64_t normals, const MemoryUse& use);
inline MemoryEstimate estimateMemory(const Scene& scene, const MemoryUse& use) {
    return estimateMemory(scene.triangles.size(), scene.normals.size(), use);
}

// A GPU render with `accel` (the default accelerator unless given).
inline MemoryUse gpuRender(accel::AccelSpec accel = {}) {
    return MemoryUse{.accel = std::move(accel), .gpuData = true, .device = true};
}

// What `request` renders a scene with (a device's deviceSharesHost is set once the device is open).
struct RenderRequest;
MemoryUse memoryUseOf(const RenderRequest& request);

// What the machine and the device let the process have; a limit not known or not set is empty.
struct MemoryLimits {
    std::optional<uint64_t> hostAvailable{};  // /proc/meminfo MemAvailable
    std::optional<uint64_t> processLimit{};   // RLIMIT_AS or RLIMIT_DATA (ulimit -v), less what is mapped
    std::optional<uint64_t> cgroupLimit{};    // the cgroup's memory.max, less its memory.current
    std::optional<uint64_t> deviceHeap{};     // device-local heap (VK_EXT_memory_budget's budget where known)
    // The smallest host limit and its name ("MemAvailable", "ulimit -v", "cgroup memory.max").
    std::optional<std::pair<uint64_t, std::string>> host() const;
};

// The host's limits (no device part), read from /proc and getrlimit once, at the first call: before
// the first scene is loaded, as the estimate holds the whole process (a limit read once the scene is
// loaded would count its arrays twice, as used and as needed), and the same for every scene after it.
MemoryLimits hostMemoryLimits();

// Why a render as `use` of `triangles` triangles, `normals` of them with vertex normals, does not fit
// `limits`, as one sentence that names an accelerator that fits, or the one that needs the least;
// nothing when it fits.
std::optional<std::string> memoryProblem(uint64_t triangles, uint64_t normals, const MemoryUse& use,
                                         const MemoryLimits& limits);

// The memory a render was estimated to need before its work, and the smallest limit of each side
// it was checked against (empty: none known): for --stats and --json.
struct MemoryReport {
    uint64_t hostBytes = 0, deviceBytes = 0;
    std::optional<uint64_t> hostLimit, deviceLimit;
    std::string hostLimitName;  // "MemAvailable", "the process's limit (ulimit -v)", ...
};

// `options` with ParseOptions::memoryProblem set: triangles past what a render as `use` fits in the
// host's memory (hostMemoryLimits) are refused at the line that would make them. The
// device's limits come once it is open (checkSceneMemory).
ParseOptions withinMemory(const MemoryUse& use, ParseOptions options = {});

// The check of a loaded scene before its structure is built: throws vkray::Error ("FILE: " and
// memoryProblem's sentence, FILE from its sourceFile) when it does not fit, else gives the
// estimate and the limits for --stats.
MemoryReport checkSceneMemory(const SceneSize& scene, const MemoryUse& use, const MemoryLimits& limits);

// "1.23 GB", "456 MB": decimal units.
std::string formatBytes(uint64_t bytes);

}  // namespace vkray::render
