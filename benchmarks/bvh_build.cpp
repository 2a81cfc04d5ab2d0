// Build benchmark of the BVH family: for each scene file given, builds bvh-fast (AAC-Fast),
// bvh-hq (AAC-HQ), bvh (AAC-HQ with treelet restructuring) and bvh-sah (binned-SAH reference) with 1 and 2 worker threads, and prints the
// median build time with its min-max over the runs (after one warm-up), the speed-up of 2 threads
// over 1, the SAH cost of each tree and its size. A benchmark prints figures; it asserts nothing.
//
//   vkray_bench_bvh_build [--runs N] [--threads 1,2] SCENE...
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "accel/bvh/bvh_accel.h"
#include "bench/spread.h"
#include "scene/scene_parser.h"

namespace {

using vkray::bvh::Config;

struct Preset {
    const char* name;
    Config config;
};

struct Timing {
    double median = 0.0, min = 0.0, max = 0.0;
    std::map<std::string, double> phaseMedians;
};

double median(std::vector<double> v) { return vkray::bench::spreadOf(std::move(v)).median; }

Timing timeBuilds(const vkray::Scene& scene, const Config& config, int threads, int runs,
                  vkray::bvh::FlatBvh& last) {
    vkray::bvh::buildFlatBvh(scene.triangles, config, threads);  // warm-up
    std::vector<double> totals;
    std::map<std::string, std::vector<double>> phases;
    for (int r = 0; r < runs; ++r) {
        vkray::bvh::BuildResult result = vkray::bvh::buildFlatBvh(scene.triangles, config, threads);
        totals.push_back(result.totalMs);
        for (const auto& [name, ms] : result.phases) phases[name].push_back(ms);
        last = std::move(result.flat);
    }
    const vkray::bench::Spread total = vkray::bench::spreadOf(totals);
    Timing t{total.median, total.min, total.max, {}};
    for (const auto& [name, v] : phases) t.phaseMedians[name] = median(v);
    return t;
}

std::string phaseList(const Timing& t) {
    std::string s;
    for (const auto& [name, ms] : t.phaseMedians) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%s %.1f", s.empty() ? "" : ", ", name.c_str(), ms);
        s += buf;
    }
    return s;
}

void benchScene(const std::string& file, const std::vector<int>& threadCounts, int runs) {
    const vkray::Scene scene = vkray::loadScene(file);
    std::printf("\n%s: %zu triangles, %d runs after a warm-up, median (min-max) ms\n", file.c_str(),
                scene.triangles.size(), runs);
    std::printf("%-9s %7s %22s %8s %9s %9s %8s %6s   phases (median ms)\n", "preset", "threads", "build ms",
                "speedup", "SAH cost", "nodes", "leaves", "depth");
    const Preset presets[] = {{"bvh-fast", Config::aacFast()}, {"bvh-hq", Config::aacHq()},
                              {"bvh", Config::aacHqRestructured()}, {"bvh-sah", Config::binnedSah()}};
    std::map<std::string, double> oneThreadMs, sahCost;
    for (const Preset& p : presets) {
        for (int threads : threadCounts) {
            vkray::bvh::FlatBvh flat;
            const Timing t = timeBuilds(scene, p.config, threads, runs, flat);
            if (threads == threadCounts.front()) oneThreadMs[p.name] = t.median;
            sahCost[p.name] = flat.sahCost;
            char range[48];
            std::snprintf(range, sizeof range, "%.1f (%.1f-%.1f)", t.median, t.min, t.max);
            std::printf("%-9s %7d %22s %7.2fx %9.3f %9zu %8u %6u   %s\n", p.name, threads, range,
                        oneThreadMs[p.name] / t.median, flat.sahCost, flat.nodes.size(), flat.leaves,
                        flat.maxDepth, phaseList(t).c_str());
        }
    }
    std::printf("SAH cost vs bvh-sah: bvh-fast %.3f, bvh-hq %.3f, bvh %.3f; 1-thread build time vs bvh-sah: "
                "bvh-fast %.2f, bvh-hq %.2f, bvh %.2f\n",
                sahCost["bvh-fast"] / sahCost["bvh-sah"], sahCost["bvh-hq"] / sahCost["bvh-sah"],
                sahCost["bvh"] / sahCost["bvh-sah"], oneThreadMs["bvh-fast"] / oneThreadMs["bvh-sah"],
                oneThreadMs["bvh-hq"] / oneThreadMs["bvh-sah"], oneThreadMs["bvh"] / oneThreadMs["bvh-sah"]);
}

std::vector<int> parseThreads(const std::string& list) {
    std::vector<int> out;
    std::stringstream ss(list);
    for (std::string item; std::getline(ss, item, ',');) out.push_back(std::max(1, std::atoi(item.c_str())));
    return out;
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    std::vector<int> threads = {1, 2};
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc) {
            runs = std::max(1, std::atoi(argv[++i]));
        } else if (a == "--threads" && i + 1 < argc) {
            threads = parseThreads(argv[++i]);
        } else {
            scenes.push_back(a);
        }
    }
    if (scenes.empty() || threads.empty()) {
        std::fprintf(stderr, "usage: %s [--runs N] [--threads 1,2] SCENE...\n", argv[0]);
        return 2;
    }
    try {
        for (const std::string& s : scenes) benchScene(s, threads, runs);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
