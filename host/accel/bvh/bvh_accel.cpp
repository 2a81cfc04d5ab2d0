#include "accel/bvh/bvh_accel.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include "accel/bvh/aac_builder.h"
#include "accel/bvh/bvh_tracer.h"
#include "accel/bvh/flatten.h"
#include "accel/bvh/leaf_collapse.h"
#include "accel/bvh/primitives.h"
#include "accel/bvh/reinsert.h"
#include "accel/bvh/sah_builder.h"
#include "accel/bvh/treelet.h"
#include "core/error.h"
#include "core/format.h"
#include "core/timing.h"
#include "core/worker_arena.h"

namespace vkray::bvh {
namespace {

std::string sahUnit(const Config& c) {
    return "Ct=" + shortNumber(c.sah.traversal) + ", Ci=" + shortNumber(c.sah.intersection) +
           ", normalised by root area, leaves <= " + std::to_string(c.maxLeafSize);
}

BinaryTree buildTree(const PrimitiveSet& prims, const Config& config, PhaseLog& log) {
    return config.builder == Config::Builder::Aac ? buildAac(prims, config, log)
                                                  : buildBinnedSah(prims, config, log);
}

class BvhAccel final : public accel::BuiltAccel {
public:
    BvhAccel(const Config& config, accel::BvhWalk walk, BuildResult result, int threads)
        : config_(config), walk_(walk), flat_(std::move(result.flat)), phases_(std::move(result.phases)),
          totalMs_(result.totalMs), reinserted_(result.reinsertIterations), threads_(threads) {}

    std::unique_ptr<geometry::Tracer> makeTracer(const Scene& scene) const override {
        return std::make_unique<BvhTracer>(flat_, scene.triangles, walk_ == accel::BvhWalk::Stackless);
    }

    accel::GpuAccelData gpuData() const override {
        accel::GpuAccelData data;
        data.traversal = accel::bvhTraversal(config_, walk_);
        data.triangleOrder = flat_.triangleOrder;
        // Every BVH kernel walks its shadow rays stackless, by the parent links: a box node holds
        // its own, sphere nodes' are an array beside them. The nodes are made in parallel, on as
        // many workers as the build had.
        tbb::task_arena arena(arenaThreads(threads_));
        arena.execute([&] {
            if (spheres()) {
                const std::vector<gpu::GpuBvhSphereNode> nodes = gpuSphereNodes(flat_);
                data.indices = accel::asBytes(gpuParentLinks(nodes));
                data.nodes = accel::asBytes(nodes);
            } else {
                data.nodes = accel::asBytes(gpuNodes(flat_));
            }
        });
        data.maxLeafTriangles = uint32_t(config_.maxLeafSize);
        return data;
    }

    std::vector<accel::AccelStat> stats() const override {
        const FlatBvh& flat = flat_;
        std::vector<accel::AccelStat> s;
        s.push_back({"build_ms", totalMs_, "ms"});
        for (const auto& [name, ms] : phases_) s.push_back({name + "_ms", ms, "ms"});
        s.push_back({"threads", double(threads_ > 0 ? threads_ : tbb::info::default_concurrency()), "oneTBB workers"});
        if (config_.builder == Config::Builder::Aac) {
            s.push_back({"aac_delta", double(config_.delta), "Gu et al. 2013"});
            s.push_back({"aac_epsilon", config_.epsilon, "Gu et al. 2013"});
        } else {
            s.push_back({"sah_bins", double(config_.sahBins), "per axis"});
        }
        if (config_.reinsertIterations > 0) {
            s.push_back({"reinsert_iterations", double(reinserted_),
                         "run, of at most " + std::to_string(config_.reinsertIterations) + "; Bittner et al. 2013"});
            s.push_back({"reinsert_batch", config_.reinsertBatch, "of the inner nodes an iteration"});
        }
        if (config_.treeletPasses > 0) {
            s.push_back({"treelet_passes", double(config_.treeletPasses), "Karras and Aila 2013"});
            s.push_back({"treelet_min", double(config_.treeletMinPrimitives), "triangles"});
        }
        s.push_back({"nodes", double(flat.nodes.size()), "binary: inner nodes and leaves"});
        s.push_back({"leaves", double(flat.leaves), ""});
        s.push_back({"max_depth", double(flat.maxDepth), "root = 0"});
        const double mean = flat.leaves ? double(flat.triangleOrder.size()) / flat.leaves : 0.0;
        s.push_back({"mean_leaf_size", mean, "triangles"});
        s.push_back({"sah_cost", flat.sahCost, sahUnit(config_)});
        const size_t wide = gpuNodeCount(flat);
        s.push_back({"gpu_nodes", double(wide), std::to_string(VKRAY_BVH_WIDTH) + "-wide nodes of the kernel"});
        const size_t nodeBytes = spheres() ? sizeof(gpu::GpuBvhSphereNode) + sizeof(uint32_t) : sizeof(gpu::GpuBvhNode);
        s.push_back({"gpu_bytes", double(wide * nodeBytes),
                     "bytes: nodes with their parent links (triangles, reordered, are uploaded as usual)"});
        return s;
    }

private:
    bool spheres() const { return config_.container == Config::Container::Sphere; }

    Config config_;
    accel::BvhWalk walk_;
    FlatBvh flat_;
    std::vector<std::pair<std::string, double>> phases_;
    double totalMs_;
    int reinserted_;
    int threads_;
};

}  // namespace

std::string Config::describe() const {
    const std::string builderText = builder == Builder::Aac
                                        ? "AAC delta=" + shortNumber(delta) + " epsilon=" + shortNumber(epsilon) +
                                              (container == Container::Sphere ? ", sphere containers" : "")
                                        : "binned SAH, " + std::to_string(sahBins) + " bins";
    const std::string reinsertion = reinsertIterations > 0 ? "; reinsertion, at most " + std::to_string(reinsertIterations) +
                                                                " iterations of " + shortNumber(reinsertBatch) + " of the nodes"
                                                          : "";
    const std::string treelets = treeletPasses > 0 ? "; " + std::to_string(treeletPasses) +
                                                         " treelet passes from " + std::to_string(treeletMinPrimitives) + " triangles"
                                                   : "";
    return builderText + reinsertion + treelets + "; " + sahUnit(*this);
}

BuildResult buildFlatBvh(std::span<const Triangle> triangles, const Config& config, int threads,
                         BuildProgress progress) {
    const Clock::time_point start = Clock::now();
    PhaseLog log(std::move(progress));
    int reinserted = 0;
    tbb::task_arena arena(arenaThreads(threads));
    FlatBvh flat = arena.execute([&] {
        const bool spheres = config.container == Config::Container::Sphere;
        const PrimitiveSet prims = log.run("primitives", 0.05, [&] { return primitivesOf(triangles, spheres); });
        // AAC records the leaf collapse while it clusters, unless restructuring changes the tree after.
        const bool restructured = config.treeletPasses > 0 || config.reinsertIterations > 0;
        const bool collapseInBuild = config.builder == Config::Builder::Aac && !restructured;
        CollapsedTree collapsed;
        BinaryTree tree = collapseInBuild ? buildAac(prims, config, log, &collapsed) : buildTree(prims, config, log);
        if (config.reinsertIterations > 0)
            reinserted = log.run("reinsert", 0.8, [&] { return reinsertNodes(tree, config); });
        if (config.treeletPasses > 0) log.run("treelets", 0.88, [&] { restructureTreelets(tree, config); });
        if (!collapseInBuild) collapsed = log.run("collapse", 0.92, [&] { return collapseLeaves(tree, config); });
        return log.run("flatten", 1.0, [&] { return flatten(tree, collapsed); });
    });
    log.finish();
    return BuildResult{std::move(flat), log.phases(), msSince(start), reinserted};
}

}  // namespace vkray::bvh

namespace vkray::accel {

Traversal bvhTraversal(const bvh::Config& config, BvhWalk walk) {
    if (config.container == bvh::Config::Container::Sphere) return Traversal::BvhSphere;
    switch (walk) {
    case BvhWalk::Stack: return Traversal::Bvh;
    case BvhWalk::Stackless: return Traversal::BvhStackless;
    case BvhWalk::Packet: return Traversal::BvhPacket;
    }
    return Traversal::Bvh;
}

std::unique_ptr<BuiltAccel> buildBvhAccel(const Scene& scene, const bvh::Config& config, BvhWalk walk,
                                          const BuildOptions& options) {
    if (config.builder == bvh::Config::Builder::Aac) bvh::validateAacConfig(config);
    if (config.container == bvh::Config::Container::Sphere &&
        (config.builder != bvh::Config::Builder::Aac || config.treeletPasses > 0 || config.reinsertIterations > 0 ||
         walk != BvhWalk::Stack))
        throw Error("sphere containers are built by AAC and walked with a stack: no binned SAH, treelets, reinsertion, "
                    "stackless or packet walk");
    bvh::BuildResult result = bvh::buildFlatBvh(scene.triangles, config, options.threads, options.progress);
    return std::make_unique<bvh::BvhAccel>(config, walk, std::move(result), options.threads);
}

}  // namespace vkray::accel
