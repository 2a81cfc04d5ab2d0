// Benchmark of the kd-tree family. For each scene file given:
//  - SAH kd-tree build time with each thread count (one warm-up, then the median of --runs, with
//    min-max), and the tree's shape;
//  - per traversal (kd-stack, kd-restart, kd-backtrack) on the CPU, for the camera rays of a
//    --size image: mean nodes visited, leaves visited, triangles tested and restarts per ray
//    (closest hit, double precision, kd_traversal.h);
//  - with --gpu: GPU time per traversal (Vulkan timestamps, median of --runs after a warm-up) of the
//    whole Whitted render at --size, through the GPU renderer.
// --ci 10,20,80 repeats everything for several intersection costs (the tuning of docs/kdtree.md).
// A benchmark prints figures; it asserts nothing (docs/performance.md, "Method").
//
//   vkray_bench_kd [--runs N] [--threads 1,2] [--size WxH] [--ci LIST] [--gpu] SCENE...
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "accel/kd/kd_traversal.h"
#include "accel/kd/sah_kd_builder.h"
#include "bench/spread.h"
#include "geometry/brute_force.h"
#include "gpu/gpu_renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace {

using namespace vkray;
using namespace vkray::accel;

using bench::Spread;
using bench::spreadOf;

std::vector<double> numberList(const std::string& s) {
    std::vector<double> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');) out.push_back(std::stod(item));
    return out;
}

struct Options {
    int runs = 5;
    std::vector<double> threads{1, 2};
    std::vector<double> intersectionCosts{kd::KdConfig{}.intersectionCost};
    int width = 320, height = 240;
    bool gpu = false;
    std::vector<std::string> scenes;
};

Options parseArgs(int argc, char** argv) {
    Options o;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto next = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value");
            return argv[++i];
        };
        if (a == "--runs") o.runs = std::max(1, std::stoi(next()));
        else if (a == "--threads") o.threads = numberList(next());
        else if (a == "--ci") o.intersectionCosts = numberList(next());
        else if (a == "--size") {
            const std::string s = next();
            o.width = std::stoi(s.substr(0, s.find('x')));
            o.height = std::stoi(s.substr(s.find('x') + 1));
        } else if (a == "--gpu") o.gpu = true;
        else o.scenes.push_back(a);
    }
    if (o.scenes.empty())
        throw std::runtime_error("usage: vkray_bench_kd [--runs N] [--threads 1,2] [--size WxH] [--ci LIST] [--gpu] SCENE...");
    return o;
}

kd::KdBuildResult timeBuilds(const Scene& scene, const kd::KdConfig& config, const Options& o) {
    kd::KdBuildResult last;
    for (double threads : o.threads) {
        std::vector<double> total, split;
        kd::buildSahKdTree(scene.triangles, config, int(threads));  // warm-up
        for (int r = 0; r < o.runs; ++r) {
            last = kd::buildSahKdTree(scene.triangles, config, int(threads));
            total.push_back(last.times.totalMs);
            split.push_back(last.times.treeMs);
        }
        const Spread t = spreadOf(total), s = spreadOf(split);
        std::printf("  build, %d thread(s): %.1f ms (min %.1f, max %.1f; splitting %.1f ms)\n", int(threads), t.median,
                    t.min, t.max, s.median);
    }
    const kd::KdTreeFigures f = kd::measureTree(last.tree, config);
    std::printf("  tree: %zu nodes, %zu leaves (%zu empty), depth %d, %.2f triangles/leaf, %zu duplicated "
                "references, SAH cost %.2f (%s)\n",
                f.nodes, f.leaves, f.emptyLeaves, f.maxDepth, f.meanTrianglesPerLeaf(), f.duplicatedReferences(),
                f.sahCost, config.describe().c_str());
    return last;
}

void cpuTraversalFigures(const Scene& scene, const kd::KdTree& tree, const Options& o) {
    const CameraFrame cam = makeCameraFrame(scene.camera, o.width, o.height);
    uint64_t stackNodes = 0;
    for (kd::Traversal t : {kd::Traversal::Stack, kd::Traversal::Restart, kd::Traversal::Backtrack}) {
        const auto tracer = kd::makeKdTracer(t, tree, geometry::triangleVertices(scene));
        geometry::TraversalCounters c;
        for (int j = 0; j < cam.height; ++j)
            for (int i = 0; i < cam.width; ++i) tracer->closest({cam.eye, primaryDirection(cam, i, j)}, INFINITY, &c);
        const double rays = double(cam.width) * cam.height;
        if (t == kd::Traversal::Stack) stackNodes = c.nodes;
        const char* name = t == kd::Traversal::Stack ? "kd-stack" : t == kd::Traversal::Restart ? "kd-restart" : "kd-backtrack";
        std::printf("  CPU %-12s per camera ray: %6.1f nodes (%.2fx stack), %5.2f leaves, %6.1f triangles, %5.2f "
                    "restarts, %llu capped\n",
                    name, c.nodes / rays, double(c.nodes) / double(std::max<uint64_t>(stackNodes, 1)), c.leaves / rays,
                    c.triangles / rays, c.restarts / rays, (unsigned long long)c.capped);
    }
}

void gpuTimes(const gpu::VulkanContext& ctx, const Scene& scene, const kd::KdConfig& config, const Options& o) {
    RenderOptions options{.width = o.width, .height = o.height, .maxDepth = scene.maxDepth};
    for (const char* name : {"kd-stack", "kd-restart", "kd-backtrack"}) {
        AccelSpec spec = resolveAccel(name);
        spec.kd = config;
        const auto built = buildAccel(scene, spec);
        const GpuAccelData data = built->gpuData();
        std::vector<double> ms;
        gpu::GpuRenderReport report;
        gpu::renderOnGpu(ctx, scene, options, data, &report);  // warm-up
        for (int r = 0; r < o.runs; ++r) {
            gpu::renderOnGpu(ctx, scene, options, data, &report);
            ms.push_back(report.gpuMs);
        }
        const Spread s = spreadOf(ms);
        std::printf("  GPU %-12s %dx%d Whitted: %.1f ms (min %.1f, max %.1f), %llu rays + %llu shadow rays, %llu "
                    "capped\n",
                    name, o.width, o.height, s.median, s.min, s.max, (unsigned long long)report.raysTraced,
                    (unsigned long long)report.shadowRays, (unsigned long long)report.cappedRays);
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parseArgs(argc, argv);
        std::unique_ptr<gpu::VulkanContext> ctx;
        if (o.gpu) {
            ctx = std::make_unique<gpu::VulkanContext>(gpu::ContextOptions{});
            std::printf("device: %s\n", ctx->info().name.c_str());
        }
        for (const std::string& file : o.scenes) {
            const Scene scene = loadScene(file);
            std::printf("%s: %zu triangles\n", file.c_str(), scene.triangles.size());
            for (double ci : o.intersectionCosts) {
                kd::KdConfig config;
                config.intersectionCost = ci;
                std::printf(" %s\n", config.describe().c_str());
                kd::KdBuildResult built = timeBuilds(scene, config, o);
                kd::deriveNodeExtras(built.tree, 0);  // kd-backtrack's parent links, after the timed builds
                if (scene.hasCamera) cpuTraversalFigures(scene, built.tree, o);
                if (ctx && scene.hasCamera) gpuTimes(*ctx, scene, config, o);
            }
        }
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
