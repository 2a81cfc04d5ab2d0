// Traversal benchmark across accelerators, a lighter `vkray bench`: for each scene and
// accelerator, the build time, the GPU trace time (Vulkan timestamps, median of --runs after a
// warm-up, with min-max), and from one extra render with the statistics variant of
// the kernel (--counters) the mean nodes visited, leaves visited, triangle tests and restarts per
// ray, camera, secondary and shadow rays together. Prints a Markdown table; asserts nothing.
//
//   vkray_bench_traversals [--runs N] [--size WxH] [--accel LIST] [--device D] SCENE...
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "bench/spread.h"
#include "core/timing.h"
#include "gpu/gpu_renderer.h"
#include "gpu/vulkan_context.h"
#include "scene/scene_parser.h"

namespace {

using namespace vkray;

struct Options {
    int runs = 3;
    int width = 320, height = 240;
    std::vector<std::string> accels = {"bvh-fast", "bvh-hq", "bvh-sah", "kd-stack", "kd-restart", "kd-backtrack"};
    std::string device;
    std::vector<std::string> scenes;
};

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

Options parseArgs(int argc, char** argv) {
    Options o;
    const char* usage = "usage: vkray_bench_traversals [--runs N] [--size WxH] [--accel LIST] [--device D] SCENE...";
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const auto value = [&]() -> std::string {
            if (i + 1 >= argc) throw std::runtime_error(a + " needs a value; " + usage);
            return argv[++i];
        };
        if (a == "--runs") o.runs = std::max(1, std::atoi(value().c_str()));
        else if (a == "--size") {
            const std::string v = value();
            if (std::sscanf(v.c_str(), "%dx%d", &o.width, &o.height) != 2 || o.width < 1 || o.height < 1)
                throw std::runtime_error("--size " + v + ": expected WIDTHxHEIGHT");
        } else if (a == "--accel") o.accels = splitList(value());
        else if (a == "--device") o.device = value();
        else if (!a.empty() && a[0] == '-') throw std::runtime_error("unknown option " + a + "; " + usage);
        else o.scenes.push_back(a);
    }
    if (o.scenes.empty()) throw std::runtime_error(usage);
    return o;
}

using bench::Spread;
using bench::spreadOf;

void benchScene(const gpu::VulkanContext& ctx, const std::string& file, const Options& o) {
    const Scene scene = loadScene(file);
    RenderOptions render;
    render.width = o.width;
    render.height = o.height;
    render.maxDepth = scene.maxDepth;
    for (const std::string& name : o.accels) {
        const accel::AccelSpec spec = accel::resolveAccel(name);
        std::vector<double> buildMs;
        std::unique_ptr<accel::BuiltAccel> built;
        for (int r = 0; r < 1 + o.runs; ++r) {  // the first build warms the allocator and the pool
            const Clock::time_point t0 = Clock::now();
            built = accel::buildAccel(scene, spec);
            if (r > 0) buildMs.push_back(msSince(t0));
        }
        const accel::GpuAccelData data = built->gpuData();
        gpu::GpuRenderReport report;
        render.countTraversal = false;
        gpu::renderOnGpu(ctx, scene, render, data, &report);  // warm-up (pipeline caches, first touch)
        std::vector<double> gpuMs;
        for (int r = 0; r < o.runs; ++r) {
            gpu::renderOnGpu(ctx, scene, render, data, &report);
            gpuMs.push_back(report.gpuMs);
        }
        render.countTraversal = true;
        gpu::renderOnGpu(ctx, scene, render, data, &report);
        const double rays = double(std::max<uint64_t>(report.raysTraced + report.shadowRays, 1));
        const Spread b = spreadOf(buildMs), g = spreadOf(gpuMs);
        std::printf("| %s | %zu | %s | %.1f (%.1f-%.1f) | %.1f (%.1f-%.1f) | %.2f | %.2f | %.2f | %.2f | %.2f | %llu |\n",
                    file.c_str(), scene.triangles.size(), name.c_str(), b.median, b.min, b.max, g.median, g.min,
                    g.max, rays / (g.median * 1e3), double(report.nodesVisited) / rays,
                    double(report.leavesVisited) / rays, double(report.trianglesTested) / rays,
                    double(report.restarts) / rays, (unsigned long long)report.cappedRays);
        std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parseArgs(argc, argv);
        const gpu::VulkanContext ctx(gpu::ContextOptions{.validation = false, .device = o.device});
        std::printf("device: %s (%s); %dx%d; build and GPU ms: median (min-max) of %d runs after a warm-up; "
                    "per ray: camera, secondary and shadow rays together\n\n",
                    ctx.info().name.c_str(), ctx.info().driver.c_str(), o.width, o.height, o.runs);
        std::printf("| scene | triangles | accel | build ms | GPU ms | Mrays/s | nodes/ray | leaves/ray | "
                    "triangles/ray | restarts/ray | capped |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
        for (const std::string& file : o.scenes) benchScene(ctx, file, o);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
