// Build benchmark of the SAH kd-tree against two yardsticks on the same triangles, in the same run:
// Embree 3's BVH build at RTC_BUILD_QUALITY_HIGH (Wald, Woop, Benthin, Johnson and Ernst, "Embree:
// A Kernel Framework for Efficient CPU Ray Tracing", SIGGRAPH 2014) and one of vkray's BVH builds
// (--bvh, default `bvh`). The three builds alternate run by run, so a busy machine slows all of them
// alike; it prints the medians (min-max) after one warm-up of each, the kd build's ratio to each
// yardstick, the kd build's phases and the tree's shape. Beside the wall-clock times it prints the
// process's CPU time a build (all its threads), whose ratios hold when other processes take turns
// on the cores. A benchmark prints figures; it asserts nothing (docs/performance.md, "Method").
//
//   vkray_bench_kd_build [--runs N] [--threads N] [--bvh NAME] [--kd NAME] SCENE...
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "accel/accel.h"
#include "accel/accel_spec.h"
#include "bench/embree_baseline.h"
#include "bench/spread.h"
#include "core/timing.h"
#include "scene/scene_parser.h"

namespace {

using namespace vkray;

// Milliseconds of CPU time the process has used, all threads together.
double cpuMs() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

// Wall-clock and CPU milliseconds of f().
template <class F>
std::pair<double, double> timed(const F& f) {
    const auto start = Clock::now();
    const double cpu = cpuMs();
    f();
    const double cpuUsed = cpuMs() - cpu;
    return {msSince(start), cpuUsed};
}

struct Options {
    int runs = 5;
    int threads = 2;
    std::string bvh = "bvh";
    std::string kd = "kd-stack";
    std::vector<std::string> scenes;
};

// The command line through CLI11, as vkray's own: --help, and one line naming a bad flag.
Options parseArgs(int argc, char** argv) {
    Options o;
    CLI::App app("kd-tree build against Embree's HIGH BVH build and a vkray BVH build", "vkray_bench_kd_build");
    app.add_option("--runs", o.runs, "Timed builds of each, after one warm-up")->check(CLI::Range(1, 1 << 20));
    app.add_option("--threads", o.threads, "Worker threads of every build")->check(CLI::Range(1, 1 << 20));
    app.add_option("--bvh", o.bvh, "The vkray BVH to compare with");
    app.add_option("--kd", o.kd, "The kd accelerator whose tree is built");
    app.add_option("scenes", o.scenes, "Scene files")->required();
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        std::exit(app.exit(e));
    }
    return o;
}


void printSpread(const char* what, const bench::Spread& s) {
    std::printf("  %-28s %9.1f ms (min %.1f, max %.1f)\n", what, s.median, s.min, s.max);
}

void benchScene(const std::string& file, const Options& o) {
    const Scene scene = loadScene(file);
    std::printf("%s: %zu triangles, %d thread(s), %d runs\n", file.c_str(), scene.triangles.size(), o.threads, o.runs);
    const accel::AccelSpec kdSpec = accel::resolveAccel(o.kd), bvhSpec = accel::resolveAccel(o.bvh);
    accel::BuildOptions options;
    options.threads = o.threads;
    std::vector<double> kdMs, bvhMs, embreeMs, kdCpu, bvhCpu, embreeCpu;
    std::map<std::string, std::vector<double>> phases;
    std::vector<accel::AccelStat> last;
    const std::unique_ptr<bench::EmbreeBuild> embree = bench::makeEmbreeBuild(scene, o.threads);
    for (int r = 0; r <= o.runs; ++r) {  // run 0: the warm-up
        std::unique_ptr<accel::BuiltAccel> kd, bvh;
        const auto [k, kCpu] = timed([&] { kd = accel::buildAccel(scene, kdSpec, options); });
        last = kd->stats();
        kd.reset();
        const auto [b, bCpu] = timed([&] { bvh = accel::buildAccel(scene, bvhSpec, options); });
        bvh.reset();
        if (embree) {
            const auto [e, eCpu] = timed([&] { embree->build(); });
            embree->release();
            if (r > 0) {
                embreeMs.push_back(e);
                embreeCpu.push_back(eCpu);
            }
        }
        if (r == 0) continue;
        kdMs.push_back(k);
        bvhMs.push_back(b);
        kdCpu.push_back(kCpu);
        bvhCpu.push_back(bCpu);
        for (const accel::AccelStat& s : last)
            if (s.key.starts_with("build_") && s.key.ends_with("_ms")) phases[s.key].push_back(s.value);
    }
    const bench::Spread kd = bench::spreadOf(kdMs), bvh = bench::spreadOf(bvhMs);
    printSpread(o.kd.c_str(), kd);
    printSpread(o.bvh.c_str(), bvh);
    const double kdC = bench::spreadOf(kdCpu).median, bvhC = bench::spreadOf(bvhCpu).median;
    std::printf("  %s / %s: %.2fx wall, %.2fx CPU (%.0f / %.0f ms)\n", o.kd.c_str(), o.bvh.c_str(),
                kd.median / bvh.median, kdC / bvhC, kdC, bvhC);
    if (embree) {
        const bench::Spread em = bench::spreadOf(embreeMs);
        const double emC = bench::spreadOf(embreeCpu).median;
        printSpread("Embree 3 BVH, HIGH quality", em);
        std::printf("  %s / Embree HIGH: %.2fx wall, %.2fx CPU (%.0f / %.0f ms)\n", o.kd.c_str(), kd.median / em.median,
                    kdC / emC, kdC, emC);
    } else {
        std::printf("  Embree: %s\n", bench::embreeMissingNote());
    }
    for (const accel::AccelStat& s : last) {
        const auto p = phases.find(s.key);
        if (p != phases.end()) std::printf("  %-28s %9.1f ms (%s)\n", s.key.c_str(), bench::spreadOf(p->second).median, s.unit.c_str());
        else if (!s.key.ends_with("_ms")) std::printf("  %-28s %12.6g %s\n", s.key.c_str(), s.value, s.unit.c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    try {
        const Options o = parseArgs(argc, argv);
        for (const std::string& file : o.scenes) benchScene(file, o);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
}
