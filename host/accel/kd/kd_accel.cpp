#include "accel/kd/kd_accel.h"

#include <algorithm>
#include <span>
#include <string>
#include <utility>

#include "accel/kd/kd_ropes.h"
#include "accel/kd/kd_traversal.h"
#include "accel/kd/sah_kd_builder.h"
#include "core/error.h"
#include "core/format.h"
#include "core/timing.h"
#include "geometry/brute_force.h"

namespace vkray::accel {
namespace {

// Parent links and node boxes (kd-backtrack) or node boxes and leaf ropes (kd-ropes): only the
// traversal that reads them makes (after the tree), uploads and pays for them; the time to make
// them is a build figure of its own.
struct Extra {
    std::span<const std::byte> bytes;
    const char* what;
    const char* buildStat = nullptr;  // its --stats name, with buildWhat
    const char* buildWhat = nullptr;
};

Extra extraOf(const kd::KdTree& t, kd::Traversal traversal) {
    switch (traversal) {
    case kd::Traversal::Backtrack:
        return {std::as_bytes(std::span(t.extra)), "bytes: parent links and node boxes", "build_links_ms",
                "ms: parent links and node boxes"};
    case kd::Traversal::Ropes:
        return {std::as_bytes(std::span(t.ropes)), "bytes: node boxes and leaf ropes", "build_ropes_ms", "ms: ropes"};
    default: return {{}, "bytes: none"};
    }
}

uint32_t maxLeafTriangles(const kd::KdTree& t) {
    uint32_t most = 0;
    for (const gpu::KdNode& n : t.nodes)
        if (n.isLeaf()) most = std::max(most, n.triangleCount());
    return most;
}

// The kd family's BuiltAccel: one SAH tree, walked by one traversal on the CPU and the GPU.
class KdAccel final : public BuiltAccel {
public:
    KdAccel(const Scene& scene, const kd::KdConfig& config, kd::Traversal traversal, int shortStack,
            const BuildOptions& options)
        : traversal_(traversal), shortStack_(shortStack), config_(config),
          build_(kd::buildSahKdTree(scene.triangles, config_, options.threads, options.progress)) {
        // What only one traversal reads is made after the build, for it alone (extraOf).
        const auto start = Clock::now();
        if (traversal_ == kd::Traversal::Ropes) build_.tree.ropes = kd::buildRopes(build_.tree, options.threads);
        else if (traversal_ == kd::Traversal::Backtrack) kd::deriveNodeExtras(build_.tree, options.threads);
        extraMs_ = msSince(start);
    }

    std::unique_ptr<geometry::Tracer> makeTracer(const Scene& scene) const override {
        return kd::makeKdTracer(traversal_, build_.tree, geometry::triangleVertices(scene), VKRAY_KD_MAX_STEPS,
                                shortStack_);
    }

    GpuAccelData gpuData() const override { return kdGpuData(build_.tree, traversal_, shortStack_); }

    std::vector<AccelStat> stats() const override {
        const kd::KdTreeFigures f = kd::measureTree(build_.tree, config_);
        const kd::KdBuildTimes& ms = build_.times;
        // What gpuData() would upload, counted without copying the arrays.
        const kd::KdTree& t = build_.tree;
        const Extra extra = extraOf(t, traversal_);
        const size_t gpuBytes = sizeof(gpu::KdTreeHeader) + t.nodes.size() * sizeof(gpu::KdNode) +
                                t.indices.size() * sizeof(uint32_t) + extra.bytes.size();
        std::vector<AccelStat> stats = {
            {"build_ms", ms.totalMs + extraMs_, "ms"},
            {"build_events_ms", ms.eventsMs, "ms: bounds, events, sort"},
            {"build_split_ms", ms.treeMs, "ms: SAH splitting"},
            {"build_sweep_ms", ms.sweepMs, "ms of the workers: plane sweeps"},
            {"build_classify_ms", ms.classifyMs, "ms of the workers: side marks, straddlers"},
            {"build_clip_ms", ms.clipMs, "ms of the workers: straddlers clipped"},
            {"build_distribute_ms", ms.distributeMs, "ms of the workers: lists split in order, new events merged in"},
            {"build_leaves_ms", ms.leavesMs, "ms of the workers: leaves"},
            {"build_small_ms", ms.smallMs,
             "ms of the workers: subtrees under " + std::to_string(kd::kSmallSubtreeEvents) +
                 " events, in the phases above (their share estimated from one node in " +
                 std::to_string(kd::kSampledSmallNodes) + ")"},
            {"build_flatten_ms", ms.flattenMs, "ms: GPU arrays"},
            {"nodes", double(f.nodes), "8 bytes each"},
            {"leaves", double(f.leaves), ""},
            {"max_leaf_triangles", double(maxLeafTriangles(t)), ""},
            {"empty_leaves", double(f.emptyLeaves), ""},
            {"max_depth", double(f.maxDepth), "limit " + std::to_string(config_.resolvedMaxDepth(f.indexedTriangles))},
            {"mean_triangles_per_leaf", f.meanTrianglesPerLeaf(), "references / leaves"},
            {"duplicated_references", double(f.duplicatedReferences()), "references beyond one per triangle"},
            {"references_per_triangle", f.indexedTriangles ? double(f.references) / double(f.indexedTriangles) : 0.0,
             "budget " + shortNumber(config_.maxDuplication)},
            {"sah_cost", f.sahCost, config_.describe()},
            {"gpu_bytes", double(gpuBytes), "bytes"},
            {"extra_bytes", double(extra.bytes.size()), extra.what},
        };
        if (extra.buildStat) stats.insert(stats.begin() + 10, {extra.buildStat, extraMs_, extra.buildWhat});
        return stats;
    }

private:
    kd::Traversal traversal_;
    int shortStack_;
    kd::KdConfig config_;
    kd::KdBuildResult build_;
    double extraMs_ = 0.0;  // the ropes (kd-ropes) or the parent links and node boxes (kd-backtrack)
};

}  // namespace

Traversal kdTraversal(kd::Traversal traversal) {
    switch (traversal) {
    case kd::Traversal::Stack: return Traversal::KdStack;
    case kd::Traversal::Restart: return Traversal::KdRestart;
    case kd::Traversal::Backtrack: return Traversal::KdBacktrack;
    case kd::Traversal::PushDown: return Traversal::KdPushDown;
    case kd::Traversal::ShortStack: return Traversal::KdShortStack;
    case kd::Traversal::Ropes: return Traversal::KdRopes;
    case kd::Traversal::Packet: return Traversal::KdPacket;
    }
    return Traversal::KdRestart;
}

uint32_t kdShortStack(kd::Traversal traversal, int shortStack) {
    return traversal == kd::Traversal::ShortStack ? uint32_t(shortStack) : 0u;
}

GpuAccelData kdGpuData(const kd::KdTree& t, kd::Traversal traversal, int shortStack) {
    GpuAccelData data;
    data.traversal = kdTraversal(traversal);
    data.nodeTexelBytes = VKRAY_KD_NODE_TEXEL_BYTES;
    // kd-stack keeps a node index and two bits in one stack word (kd_stack.glsl).
    if (t.nodes.size() > VKRAY_KD_MAX_NODES)
        throw Error("the kd-tree has " + std::to_string(t.nodes.size()) + " nodes; the GPU kernels address at most " +
                    std::to_string(VKRAY_KD_MAX_NODES) + " (raise kd-traversal-cost or lower kd-max-depth: --accel help)");
    data.maxLeafTriangles = maxLeafTriangles(t);
    data.kdShortStack = kdShortStack(traversal, shortStack);
    data.nodes = asBytes(std::vector<gpu::KdTreeHeader>{t.header});
    const std::vector<std::byte> nodeBytes = asBytes(t.nodes);
    data.nodes.insert(data.nodes.end(), nodeBytes.begin(), nodeBytes.end());
    data.indices = asBytes(t.indices);
    const Extra e = extraOf(t, traversal);
    data.extra.assign(e.bytes.begin(), e.bytes.end());
    return data;
}

std::unique_ptr<BuiltAccel> buildKdAccel(const Scene& scene, const kd::KdConfig& config, kd::Traversal traversal,
                                         int shortStack, const BuildOptions& options) {
    return std::make_unique<KdAccel>(scene, config, traversal, shortStack, options);
}

}  // namespace vkray::accel
