// Acceleration structures as the renderers see them: a name from the command line (DESIGN.md,
// "Accelerator names") becomes an AccelSpec; buildAccel() builds only the structure that spec needs
// (a scene rendered with `brute` builds nothing) and returns it as a BuiltAccel, which offers a CPU
// tracer (for the reference renderer and unit tests) and the flattened arrays the GPU kernel reads.
//
// Each family lives in its own folder: accel/bvh/ (AAC after Gu et al. 2013, binned-SAH reference),
// accel/kd/ (SAH kd-tree after Wald and Havran 2006, traversals after Foley and Sugerman 2005).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cpu/tracer.h"
#include "scene/scene.h"

namespace vkray::accel {

enum class Family { Brute, Bvh, Kd };

// The three kd-tree traversals of Foley and Sugerman (2005); the tree is the same for all three.
enum class KdTraversal { Stack, Restart, Backtrack };

// Which structure to build and how, from `--accel NAME` and the tuning options. Tuning fields left
// at their "unset" value mean "the preset's value"; the builders document their defaults.
struct AccelSpec {
    std::string name = "bvh";  // as given on the command line
    Family family = Family::Bvh;
    KdTraversal kdTraversal = KdTraversal::Restart;

    // BVH (AAC): preset from the name (bvh, bvh-fast, bvh-hq); overrides when > 0.
    int aacDelta = 0;
    double aacEpsilon = 0.0;
    bool bvhSahReference = false;  // the binned-SAH reference builder instead of AAC (`bvh-sah`)

    // kd-tree SAH constants; overrides when > 0.
    double kdTraversalCost = 0.0;
    double kdIntersectionCost = 0.0;
    double kdEmptyBonus = -1.0;  // overrides when >= 0
    int kdMaxDepth = 0;
};

// Every accelerator name vkray accepts, in the order `--help` lists them.
const std::vector<std::string>& accelNames();

// The spec for a name; an unknown name is an Error listing the known ones.
AccelSpec parseAccel(const std::string& name);

// Progress of a long build, for a progress line: what is being done and the fraction done (0..1).
using BuildProgress = std::function<void(const std::string& phase, double fraction)>;

struct BuildOptions {
    int threads = 0;  // worker threads; 0 = all cores. The result never depends on it.
    BuildProgress progress;
};

// One figure of a build for --stats and --json: key (snake_case, stable for scripts), value, and a
// short unit or note for people ("ms", "bytes", "SAH: Ct=1 Ci=1").
struct AccelStat {
    std::string key;
    double value = 0.0;
    std::string unit;
};

// What the GPU kernel needs of a built structure, in the layouts of shaders/shared/*_layout.h.
struct GpuAccelData {
    // The kernel, by name: shaders/render_<kernel>.comp (for example "brute", "bvh", "kd_restart").
    std::string kernel = "brute";
    // Triangle-buffer slot k holds scene triangle triangleOrder[k] (leaf order, for locality);
    // empty = scene order. GpuTriangle.original keeps the identity for AOVs either way.
    std::vector<uint32_t> triangleOrder;
    // Raw contents of the bindings VKRAY_BINDING_ACCEL_NODES, _ACCEL_INDICES, _ACCEL_EXTRA; an
    // empty one is bound to a small dummy buffer.
    std::vector<std::byte> nodes, indices, extra;

    size_t bytes() const { return nodes.size() + indices.size() + extra.size(); }
};

class BuiltAccel {
public:
    virtual ~BuiltAccel() = default;

    // CPU traversal of the structure: same answers as brute force, ties included (cpu/tracer.h).
    virtual const cpu::Tracer& tracer() const = 0;
    // The structure flattened for the GPU.
    virtual GpuAccelData gpuData() const = 0;
    // Build figures (time by phase, nodes, depth, SAH cost...).
    virtual std::vector<AccelStat> stats() const = 0;
};

std::unique_ptr<BuiltAccel> buildAccel(const Scene& scene, const AccelSpec& spec,
                                       const BuildOptions& options = {});

// Builds several structures at the same time, each on its own thread with options.threads workers
// (the mission's "the BVH and the kd-tree are built in parallel"): a render that needs both waits
// for the slower one instead of the sum. Results are in the order of `specs`; the first failure is
// rethrown after every build has ended.
std::vector<std::unique_ptr<BuiltAccel>> buildAccelsConcurrently(const Scene& scene,
                                                                 const std::vector<AccelSpec>& specs,
                                                                 const BuildOptions& options = {});

// A typed array as raw bytes for GpuAccelData.
template <class T>
std::vector<std::byte> asBytes(const std::vector<T>& v) {
    const auto* p = reinterpret_cast<const std::byte*>(v.data());
    return std::vector<std::byte>(p, p + v.size() * sizeof(T));
}

}  // namespace vkray::accel
