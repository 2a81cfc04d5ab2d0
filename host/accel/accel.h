// Acceleration structures as the renderers see them: an AccelSpec (accel_spec.h: the name from the
// command line and its tuning, resolved and validated) goes to buildAccel(), which builds only the
// structure that spec needs (a scene rendered with `brute` builds nothing) and returns it as a
// BuiltAccel: the flattened arrays the GPU kernel reads and, on request, a CPU tracer (for the
// reference renderer and the tests).
//
// Each family lives in its own folder: accel/bvh/ (AAC after Gu, He, Fatahalian and Blelloch 2013,
// binned-SAH reference), accel/kd/ (SAH kd-tree after Wald and Havran 2006, traversals after Foley
// and Sugerman 2005).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "accel/accel_spec.h"
#include "core/parallel_alloc.h"
#include "core/phase_log.h"
#include "geometry/tracer.h"
#include "scene/scene.h"

namespace vkray::accel {

// The walk a structure's arrays are laid out for (GpuAccelData::traversal): the family and, within
// it, the traversal that decides which arrays the build adds (the parent links of Hapala et al.'s
// stackless BVH walk, the ropes of Popov et al. 2007, the parent links and boxes of Foley and
// Sugerman's kd-backtrack, section 4.2). The GPU layer runs each with a kernel of its own
// (gpu/kernel_registry.h).
// RayQuery: the driver's (its structure built on the device from the scene's triangles).
enum class Traversal {
    Brute, Bvh, BvhStackless, BvhPacket, BvhSphere, KdStack, KdRestart, KdBacktrack, KdPushDown, KdShortStack, KdRopes,
    KdPacket, RayQuery
};
inline constexpr std::array kTraversals{Traversal::Brute,       Traversal::Bvh,        Traversal::BvhStackless,
                                        Traversal::BvhPacket,   Traversal::BvhSphere,  Traversal::KdStack,
                                        Traversal::KdRestart,   Traversal::KdBacktrack, Traversal::KdPushDown,
                                        Traversal::KdShortStack, Traversal::KdRopes,   Traversal::KdPacket,
                                        Traversal::RayQuery};

// Its name, as structure files record it: the accelerator that walks it (accel_spec.cpp's names).
constexpr std::string_view traversalName(Traversal t) {
    switch (t) {
    case Traversal::Brute: return "brute";
    case Traversal::Bvh: return "bvh";
    case Traversal::BvhStackless: return "bvh-stackless";
    case Traversal::BvhPacket: return "bvh-packet";
    case Traversal::BvhSphere: return "bvh-sphere";
    case Traversal::KdStack: return "kd-stack";
    case Traversal::KdRestart: return "kd-restart";
    case Traversal::KdBacktrack: return "kd-backtrack";
    case Traversal::KdPushDown: return "kd-pushdown";
    case Traversal::KdRopes: return "kd-ropes";
    case Traversal::KdShortStack: return "kd-shortstack";
    case Traversal::KdPacket: return "kd-packet";
    case Traversal::RayQuery: return "rayquery";
    }
    return "";
}

// Whether the kernel of `t` walks closest-hit rays as subgroup packets (bvh_packet.glsl,
// kd_packet.glsl): its counters then count the steps each lane sat out (GpuPixel.walkEvents).
constexpr bool isPacketWalk(Traversal t) { return t == Traversal::BvhPacket || t == Traversal::KdPacket; }

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
    Traversal traversal = Traversal::Brute;
    // Triangle-buffer slot k holds scene triangle triangleOrder[k] (leaf order, for locality);
    // empty = scene order. GpuTriangle.original keeps the identity for AOVs either way.
    std::vector<uint32_t> triangleOrder;
    // Raw contents of the texel views VKRAY_BINDING_NODE_TEXELS, _INDEX_TEXELS, _EXTRA_TEXELS (whole
    // texels each); an empty one is bound to a one-texel dummy.
    std::vector<std::byte> nodes, indices, extra;
    // Bytes per texel of the nodes' texel view (VKRAY_BINDING_NODE_TEXELS): 16 (RGBA32UI), 8 (RG32UI)
    // or 4 (R32UI), the node size or a divisor of it, so one node is whole texels.
    uint32_t nodeTexelBytes = 16;
    // Most triangles a leaf holds (0 for brute force): beyond VKRAY_SINGLE_SLOT_LEAF_LIMIT the
    // resumable variant's leaf loop tests four a pass (VKRAY_SPEC_LEAF_SLOTS).
    uint32_t maxLeafTriangles = 0;
    // kd-shortstack: its stack's entries (VKRAY_SPEC_KD_SHORT_STACK); 0 for the other kernels.
    uint32_t kdShortStack = 0;
    // rayquery: how the driver builds its structure on the device, from the triangle buffer.
    DriverBuild driverBuild;

    size_t bytes() const { return nodes.size() + indices.size() + extra.size(); }
};

class BuiltAccel {
public:
    virtual ~BuiltAccel() = default;

    // A CPU traversal of the structure in double precision: the same answers as brute force, ties
    // included (geometry/tracer.h). Made only when asked for (a GPU render needs none), over
    // `scene`, the scene the structure was built from; it must not outlive *this.
    virtual std::unique_ptr<geometry::Tracer> makeTracer(const Scene& scene) const = 0;
    // The structure flattened for the GPU.
    virtual GpuAccelData gpuData() const = 0;
    // Build figures (time by phase, nodes, depth, SAH cost...).
    virtual std::vector<AccelStat> stats() const = 0;
};

std::unique_ptr<BuiltAccel> buildAccel(const Scene& scene, const AccelSpec& spec,
                                       const BuildOptions& options = {});

// The traversal of what `spec` builds (GpuAccelData::traversal), known without building it.
Traversal traversalOf(const AccelSpec& spec);

// Builds several structures at the same time, each on its own thread with options.threads workers,
// so that a run that needs the BVH and the kd-tree waits for the slower build instead of the sum.
// Results are in the order of `specs`; the first failure is rethrown after every build has ended.
std::vector<std::unique_ptr<BuiltAccel>> buildAccelsConcurrently(const Scene& scene,
                                                                 const std::vector<AccelSpec>& specs,
                                                                 const BuildOptions& options = {});

// A typed array as raw bytes for GpuAccelData. The copy's pages are populated by all workers first:
// a structure of tens of millions of triangles has arrays of gigabytes, and their page faults on
// one thread were most of the copy's time.
template <class T, class A>
std::vector<std::byte> asBytes(const std::vector<T, A>& v) {
    const auto* p = reinterpret_cast<const std::byte*>(v.data());
    const size_t n = v.size() * sizeof(T);
    std::vector<std::byte> bytes;
    reservePopulated(bytes, n);
    bytes.assign(p, p + n);
    return bytes;
}

}  // namespace vkray::accel
