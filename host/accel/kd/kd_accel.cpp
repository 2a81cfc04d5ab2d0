#include "accel/kd/kd_accel.h"

#include <utility>

#include "accel/kd/kd_traversal.h"
#include "accel/kd/sah_kd_builder.h"
#include "cpu/brute_force.h"

namespace vkray::accel {
namespace {

const char* kernelName(KdTraversal t) {
    switch (t) {
    case KdTraversal::Stack: return "kd_stack";
    case KdTraversal::Restart: return "kd_restart";
    case KdTraversal::Backtrack: return "kd_backtrack";
    }
    return "kd_restart";
}

// The kd family's BuiltAccel: one SAH tree, walked by the traversal the spec names on the CPU and GPU.
class KdAccel final : public BuiltAccel {
public:
    KdAccel(const Scene& scene, const AccelSpec& spec, const BuildOptions& options)
        : traversal_(spec.kdTraversal), config_(configFor(spec)),
          build_(kd::buildSahKdTree(scene.triangles, config_, options.threads, options.progress)),
          tracer_(kd::makeKdTracer(traversal_, build_.tree, cpu::triangleVertices(scene))) {}

    const cpu::Tracer& tracer() const override { return *tracer_; }

    GpuAccelData gpuData() const override {
        GpuAccelData data;
        data.kernel = kernelName(traversal_);
        const kd::KdTree& t = build_.tree;
        data.nodes = asBytes(std::vector<gpu::KdTreeHeader>{t.header});
        const std::vector<std::byte> nodeBytes = asBytes(t.nodes);
        data.nodes.insert(data.nodes.end(), nodeBytes.begin(), nodeBytes.end());
        data.indices = asBytes(t.indices);
        if (traversal_ == KdTraversal::Backtrack) data.extra = asBytes(t.extra);  // only it pays for them
        return data;
    }

    std::vector<AccelStat> stats() const override {
        const kd::KdTreeFigures f = kd::measureTree(build_.tree, config_);
        const kd::KdBuildTimes& ms = build_.times;
        return {
            {"build_ms", ms.totalMs, "ms"},
            {"build_events_ms", ms.eventsMs, "ms: bounds, events, sort"},
            {"build_split_ms", ms.treeMs, "ms: SAH splitting"},
            {"build_flatten_ms", ms.flattenMs, "ms: GPU arrays"},
            {"nodes", double(f.nodes), "8 bytes each"},
            {"leaves", double(f.leaves), ""},
            {"empty_leaves", double(f.emptyLeaves), ""},
            {"max_depth", double(f.maxDepth), "limit " + std::to_string(config_.resolvedMaxDepth(f.indexedTriangles))},
            {"mean_triangles_per_leaf", f.meanTrianglesPerLeaf(), "references / leaves"},
            {"duplicated_references", double(f.duplicatedReferences()), "references beyond one per triangle"},
            {"sah_cost", f.sahCost, config_.describe()},
            {"gpu_bytes", double(gpuData().bytes()), "bytes"},
        };
    }

private:
    static kd::KdConfig configFor(const AccelSpec& spec) {
        kd::KdConfig c;
        if (spec.kdTraversalCost > 0.0) c.traversalCost = spec.kdTraversalCost;
        if (spec.kdIntersectionCost > 0.0) c.intersectionCost = spec.kdIntersectionCost;
        if (spec.kdEmptyBonus >= 0.0) c.emptyBonus = spec.kdEmptyBonus;
        if (spec.kdMaxDepth > 0) c.maxDepth = spec.kdMaxDepth;
        return c;
    }

    KdTraversal traversal_;
    kd::KdConfig config_;
    kd::KdBuildResult build_;
    std::unique_ptr<kd::KdTracer> tracer_;
};

}  // namespace

std::unique_ptr<BuiltAccel> buildKdAccel(const Scene& scene, const AccelSpec& spec, const BuildOptions& options) {
    return std::make_unique<KdAccel>(scene, spec, options);
}

}  // namespace vkray::accel
