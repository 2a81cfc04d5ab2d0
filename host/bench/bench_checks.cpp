// bench_checks.h, and the default thread counts of bench_runner.h.
#include "bench/bench_checks.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>

#include "accel/accel.h"
#include "bench/bench_shard.h"
#include "core/error.h"
#include "render/memory_budget.h"
#include "render/scene_checks.h"
#include "scene/scene_parser.h"

namespace vkray::bench {

std::vector<int> defaultThreadCounts() {
    const int all = int(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<int> counts;
    for (int t = 1; t < all; t *= 2) counts.push_back(t);
    counts.push_back(all);
    return counts;
}

void checkBenchOptions(const BenchOptions& o) {
    if (o.shard.count < 1 || o.shard.index < 0 || o.shard.index >= o.shard.count)
        throw Error("--shard " + shardText(o.shard) + ": expected I/N with 0 <= I < N");
    if (o.scenes.empty()) throw Error("vkray bench: no scene given");
    if (o.accels.empty()) throw Error("vkray bench: --accel names no accelerator");
    if (o.repeat < 1 || o.repeat > 1000) throw Error("--repeat " + std::to_string(o.repeat) + ": expected 1..1000");
    for (const std::string& a : o.accels) accel::resolveAccel(a);  // an unknown name fails before any work
    for (int t : o.threads)
        if (t < 1 || t > 1024) throw Error("--threads " + std::to_string(t) + ": expected 1..1024");
    for (int d : o.deltas)
        if (d < 1 || d > 1024) throw Error("--deltas " + std::to_string(d) + ": expected 1..1024");
    for (int d : o.maxDepths)
        if (d < 1 || d > 64) throw Error("--maxdepths " + std::to_string(d) + ": expected 1..64");
    for (const std::string& file : o.scenes)
        if (!std::filesystem::is_regular_file(file)) throw Error(file + ": no such scene file");
}

std::vector<render::SceneSize> checkBenchScenesOnHost(const BenchOptions& options, const std::vector<bool>& measure) {
    std::vector<render::SceneSize> sizes;
    const ParseOptions parse = render::withinMemory(render::gpuRender());
    for (size_t i = 0; i < options.scenes.size() && i < measure.size(); ++i) {
        if (!measure[i]) continue;
        const Scene scene = loadScene(options.scenes[i], parse);
        render::checkRenderable(scene, options.scenes[i]);
        sizes.push_back(render::sizeOf(scene));
        sizes.back().sourceFile = options.scenes[i];  // as the user named it
    }
    return sizes;
}

void checkBenchScenesOnDevice(render::Device& device, const std::vector<render::SceneSize>& scenes) {
    if (!device.get()) throw std::logic_error("checkBenchScenesOnDevice: a render::Device without a device");
    for (const render::SceneSize& scene : scenes) {
        try {
            device.checkFits(scene);
        } catch (const Error& e) {
            if (e.hasLocation()) throw;
            throw fileError(scene.sourceFile, e.what());  // the device's limits, which name no file
        }
    }
}

}  // namespace vkray::bench
