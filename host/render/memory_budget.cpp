#include "render/memory_budget.h"

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "render/render_request.h"
#include "shared/gpu_layout.h"

namespace vkray::render {
namespace {

// The model, in bytes a triangle. The builders' peaks are what `/usr/bin/time -v` reported as the
// peak resident set of `vkray render --build-only` on generated scenes of several sizes, less the
// scene's own arrays, each raised by a margin (docs/outputs.md, "Memory", has the measurements): a
// triangle soup is the kd-tree's worst case (many overlapping triangles, each referenced up to
// KdConfig::maxDuplication times), and its figure is the one used for every scene.
struct AccelModel {
    uint64_t buildPeak = 0;  // host, above the scene and the arrays below: the builder's at its peak
    uint64_t structure = 0;  // the arrays in the kernel's layout (GpuAccelData::bytes), host and device
    uint64_t driver = 0;     // rayquery: the driver's structure and its build's scratch, on the device
};

constexpr uint64_t kSceneTriangle = sizeof(Triangle);
constexpr uint64_t kSceneNormals = sizeof(TriangleNormals);
// Parsing: the scene's arrays grow by doubling (a file without a count up front) and the builder keeps
// the double world positions while the scene's origin may still move (scene_builder.h).
constexpr uint64_t kParsing = 3 * sizeof(glm::dvec3) + sizeof(Triangle);
// The process before any scene: code, the Vulkan loader and driver, the workers' stacks and arenas.
constexpr uint64_t kProcessBase = uint64_t(96) << 20;
// The device's own buffers besides the scene's: the tiles' pixels, counters, materials, lights.
constexpr uint64_t kDeviceBase = uint64_t(64) << 20;
// Counts past this (a petabyte of scene arrays alone) are counted as this: the estimate's products
// (a few kB a triangle at the most) stay far from wrapping around 2^64, so no count, however absurd,
// gets a small estimate.
constexpr uint64_t kMaxCounted = uint64_t(1) << 40;

// The kd-tree's arrays: the nodes and leaf lists every traversal reads (kd_layout.h), and with them
// the parent links and node boxes of kd-backtrack, or the leaves' boxes and six ropes of kd-ropes.
uint64_t kdStructure(accel::kd::Traversal t) {
    switch (t) {
        case accel::kd::Traversal::Backtrack: return 384;
        case accel::kd::Traversal::Ropes: return 512;
        default: return 128;
    }
}

AccelModel modelOf(const accel::AccelSpec& spec) {
    switch (spec.family) {
        case accel::Family::Brute: return {};
        case accel::Family::Bvh: return {.buildPeak = 160, .structure = 40};
        case accel::Family::Kd: return {.buildPeak = 512, .structure = kdStructure(spec.kdTraversal)};
        // The Morton order of the triangles on the host (bvh::mortonOrder: codes, indices, sort
        // scratch); the driver's structure and scratch are an allowance of five triangle buffers.
        case accel::Family::Driver: return {.buildPeak = 32, .structure = 0, .driver = 5 * sizeof(gpu::GpuTriangle)};
    }
    return {};
}

std::optional<uint64_t> readProcValue(const std::string& file, const std::string& key) {
    std::ifstream in(file);
    std::string line;
    while (std::getline(in, line)) {
        if (!line.starts_with(key)) continue;
        std::istringstream s(line.substr(key.size()));
        uint64_t kb = 0;
        if (s >> kb) return kb * 1024;  // /proc/meminfo and /proc/self/status count kB
    }
    return std::nullopt;
}

// A cgroup v2 file of this process's group as a number ("max": no limit).
std::optional<uint64_t> cgroupValue(const std::string& name) {
    std::ifstream groups("/proc/self/cgroup");
    std::string line;
    while (std::getline(groups, line)) {
        if (!line.starts_with("0::")) continue;
        std::ifstream in("/sys/fs/cgroup" + line.substr(3) + "/" + name);
        uint64_t v = 0;
        if (in >> v) return v;
    }
    return std::nullopt;
}

// What the process may still map under a resource limit, less what it already uses of it.
std::optional<uint64_t> rlimitLeft(int resource, const char* usedKey) {
    rlimit r{};
    if (getrlimit(resource, &r) != 0 || r.rlim_cur == RLIM_INFINITY) return std::nullopt;
    const uint64_t used = readProcValue("/proc/self/status", usedKey).value_or(0);
    return r.rlim_cur > used ? uint64_t(r.rlim_cur) - used : 0;
}

std::optional<uint64_t> minOf(std::optional<uint64_t> a, std::optional<uint64_t> b) {
    if (a && b) return std::min(*a, *b);
    return a ? a : b;
}

MemoryLimits readHostMemoryLimits() {
    MemoryLimits l;
    l.hostAvailable = readProcValue("/proc/meminfo", "MemAvailable:");
    l.processLimit = minOf(rlimitLeft(RLIMIT_AS, "VmSize:"), rlimitLeft(RLIMIT_DATA, "VmData:"));
    if (const auto max = cgroupValue("memory.max")) {
        const uint64_t used = cgroupValue("memory.current").value_or(0);
        l.cgroupLimit = *max > used ? *max - used : 0;
    }
    return l;
}

// The accelerators compared in a refusal, one of each family; of those that need as little, the first is named.
std::vector<std::string> candidates(bool device) {
    std::vector<std::string> names{"bvh", "kd-restart", "brute"};
    if (device) names.push_back("rayquery");
    return names;
}

// Where the estimate does not fit: "host", the need, the limit and its name; nothing when it fits.
struct Shortfall {
    bool device = false;
    uint64_t need = 0, have = 0;
    std::string limit;
};

std::optional<Shortfall> shortfall(const MemoryEstimate& e, const MemoryLimits& limits) {
    if (const auto host = limits.host(); host && e.hostBytes > host->first)
        return Shortfall{false, e.hostBytes, host->first, host->second};
    if (limits.deviceHeap && e.deviceBytes > *limits.deviceHeap)
        return Shortfall{true, e.deviceBytes, *limits.deviceHeap, "the device's memory"};
    return std::nullopt;
}

// The sentence's last part: an accelerator that fits, else the one that needs the least.
std::string alternative(uint64_t triangles, uint64_t normals, const MemoryUse& use, const MemoryLimits& limits,
                        bool device) {
    std::string least;
    uint64_t leastNeed = UINT64_MAX;
    for (const std::string& name : candidates(use.device)) {
        MemoryUse other = use;
        other.accel = accel::resolveAccel(name);
        if (other.accel.family == use.accel.family) continue;
        const MemoryEstimate e = estimateMemory(triangles, normals, other);
        if (!shortfall(e, limits)) return "; --accel " + name + " needs less and fits";
        const uint64_t need = device ? e.deviceBytes : e.hostBytes;
        if (need < leastNeed) leastNeed = need, least = name;
    }
    const MemoryEstimate mine = estimateMemory(triangles, normals, use);
    if (leastNeed >= (device ? mine.deviceBytes : mine.hostBytes)) return "; no accelerator needs less";
    return "; no accelerator fits (--accel " + least + ", the least, needs " + formatBytes(leastNeed) + ")";
}

}  // namespace

MemoryEstimate estimateMemory(uint64_t triangles, uint64_t normals, const MemoryUse& use) {
    triangles = std::min(triangles, kMaxCounted);
    normals = std::min(normals, kMaxCounted);
    const AccelModel m = modelOf(use.accel);
    MemoryEstimate e;
    const uint64_t scene = triangles * kSceneTriangle + normals * kSceneNormals;
    if (use.gpuData) e.structureBytes = triangles * m.structure;
    if (use.device) {
        e.deviceBytes = kDeviceBase + triangles * sizeof(gpu::GpuTriangle) + normals * sizeof(gpu::GpuTriangleNormals) +
                        e.structureBytes + triangles * m.driver;
    }
    // The scene in the kernel's layout (gpu::PackedScene) is packed on the host before its upload.
    const uint64_t packed = use.device ? triangles * sizeof(gpu::GpuTriangle) + normals * sizeof(gpu::GpuTriangleNormals) : 0;
    // The builder's result stays beside the arrays made from it (render::Structure keeps both).
    const uint64_t structure = (use.build ? triangles * m.buildPeak : 0) + e.structureBytes;
    const uint64_t rendering = structure + packed + (use.deviceSharesHost ? e.deviceBytes : 0);
    e.hostBytes = kProcessBase + scene + std::max(triangles * kParsing, rendering);
    return e;
}

MemoryUse memoryUseOf(const RenderRequest& request) {
    return MemoryUse{.accel = request.accel,
                     .gpuData = !request.cpu,
                     .device = !request.cpu && !request.buildOnly,
                     .build = request.loadAccel.empty()};
}

std::optional<std::pair<uint64_t, std::string>> MemoryLimits::host() const {
    std::optional<std::pair<uint64_t, std::string>> least;
    const auto consider = [&](const std::optional<uint64_t>& v, const char* name) {
        if (v && (!least || *v < least->first)) least = std::make_pair(*v, std::string(name));
    };
    consider(hostAvailable, "MemAvailable");
    consider(processLimit, "the process's limit (ulimit -v)");
    consider(cgroupLimit, "the cgroup's memory.max");
    return least;
}

MemoryLimits hostMemoryLimits() {
    static const MemoryLimits limits = readHostMemoryLimits();
    return limits;
}

std::optional<std::string> memoryProblem(uint64_t triangles, uint64_t normals, const MemoryUse& use,
                                         const MemoryLimits& limits) {
    const std::optional<Shortfall> s = shortfall(estimateMemory(triangles, normals, use), limits);
    if (!s) return std::nullopt;
    return std::to_string(triangles) + " triangles need an estimated " + formatBytes(s->need) + " of " +
           (s->device ? "device" : "host") + " memory with --accel " + use.accel.name + ", but " + s->limit +
           " leaves " + formatBytes(s->have) + alternative(triangles, normals, use, limits, s->device);
}

ParseOptions withinMemory(const MemoryUse& use, ParseOptions options) {
    options.memoryProblem = [use, limits = hostMemoryLimits()](uint64_t triangles) {
        return memoryProblem(triangles, 0, use, limits);
    };
    return options;
}

MemoryReport checkSceneMemory(const SceneSize& scene, const MemoryUse& use, const MemoryLimits& limits) {
    if (const auto problem = memoryProblem(scene.triangles, scene.normals, use, limits))
        throw scene.sourceFile.empty() ? Error(*problem) : fileError(scene.sourceFile, *problem);
    const MemoryEstimate e = estimateMemory(scene.triangles, scene.normals, use);
    const auto host = limits.host();
    return MemoryReport{.hostBytes = e.hostBytes,
                        .deviceBytes = e.deviceBytes,
                        .hostLimit = host ? std::optional(host->first) : std::nullopt,
                        .deviceLimit = use.device ? limits.deviceHeap : std::nullopt,
                        .hostLimitName = host ? host->second : ""};
}

std::string formatBytes(uint64_t bytes) {
    char text[32];
    if (bytes >= 1000000000) std::snprintf(text, sizeof text, "%.2f GB", double(bytes) / 1e9);
    else std::snprintf(text, sizeof text, "%.0f MB", double(bytes) / 1e6);
    return text;
}

}  // namespace vkray::render
