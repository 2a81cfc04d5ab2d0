// `vkray bench`: every accelerator on every scene, measured the same way (docs/performance.md,
// "Method"): CPU build time over thread counts, GPU trace time from timestamp
// queries split by ray kind, traversal work per ray from the statistics variant of the kernels,
// and the image error of each configuration against a double-precision CPU reference, so time can
// be weighed against error. The results go to report.h's writers.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "bench/bench_results.h"
#include "render/device.h"

namespace vkray::bench {

struct BenchOptions {
    std::vector<std::string> scenes;
    // Accelerators compared at the scene's maxdepth; each is built and traced on its own.
    std::vector<std::string> accels = {"bvh",        "bvh-fast",    "bvh-hq",   "bvh-stackless", "kd-stack",
                                       "kd-shortstack", "kd-restart", "kd-pushdown", "kd-ropes", "kd-backtrack"};
    int width = 0, height = 0;   // 0: the scene's own size
    // The camera of every scene: "scene", "close" or "EX,EY,EZ,CX,CY,CZ[,FOVY]" (scene/camera.h,
    // viewCamera).
    std::string view = "scene";
    int repeat = 3;              // timed runs after one warm-up; medians with min-max
    std::vector<int> threads;    // build-scaling thread counts; empty: 1, 2, 4, ... up to all cores
    // AAC deltas of the sweep after A. F. Mahmuda, "Bounding Volume Hierarchy Construction Using
    // Agglomerative Clustering for Faster Ray Tracing", 2017 (Tables 5.5, 5.6), built as `bvh` (AAC-HQ's
    // epsilon) with aac-delta=N; empty: no sweep.
    std::vector<int> deltas = {4, 8, 12, 20, 30, 50};
    // Depths of the maxdepth sweep; empty: 1 .. scene maxdepth - 1. Depths at or above the scene's
    // are left out (the reference is rendered at the scene's maxdepth).
    std::vector<int> maxDepths;
    bool maxDepthSweep = true;
    // The share of the run's configurations this run measures (bench_shard.h); 0/1: all of them.
    ShardSpec shard;
};

// What the runner is doing, for a progress line.
struct BenchProgress {
    int scene = 0, scenes = 0;     // 1-based
    std::string sceneName;
    std::string step;              // "reference", "build bvh-hq (2 threads)", "trace kd-restart"...
    int repeat = 0, repeats = 0;   // 1-based; 0 when the step is not repeated
    double elapsedSeconds = 0.0;
};
using BenchProgressFn = std::function<void(const BenchProgress&)>;

// The default build-scaling thread counts for this machine: 1, 2, 4, ... and all cores.
std::vector<int> defaultThreadCounts();

// Receives the results of a run as it goes (bench_resume.h): at the start (no scene yet), after
// every finished scene (both marked kStillRunning) and, before the error goes on, when a scene fails
// or the run is interrupted (marked with the failure).
using BenchSaveFn = std::function<void(const BenchResults&)>;

struct BenchContinuation {
    BenchSaveFn save;
    // The report of an earlier, unfinished run of the same settings (bench_resume.h,
    // checkResumable): its scenes are kept, and only the others are measured.
    const BenchResults* previous = nullptr;
    std::string previousFile = "bench.json";  // where it was read from, for errors
};

// Runs the whole benchmark, or the options' shard of it. Before measuring anything it throws
// vkray::Error for bad options, a scene that does not load or does not fit the device, an
// accelerator the device cannot run, or a `continuation.previous` of another run. A failure while
// measuring (a render the device cuts short, SIGINT or SIGTERM under bench_interrupt.h's
// StopOnSignals) gives the finished scenes to `continuation.save`, then throws. `device` must have
// a device; its pipelines serve every render of the run.
BenchResults runBench(render::Device& device, const BenchOptions& options, const std::string& commandLine,
                      const BenchProgressFn& progress = {}, const BenchContinuation& continuation = {});

}  // namespace vkray::bench
