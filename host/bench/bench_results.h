// Everything `vkray bench` measures, as plain data: the runner (bench_runner.h) fills it,
// the writers (report.h) turn it into bench.json, bench.md and report.html. Figures that could not
// be measured are empty optionals (JSON null) with a note, never a made-up number.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "bench/spread.h"
#include "image/image.h"

namespace vkray::bench {

// Millions of rays per second: `rays` traced in `ms`; empty when there are none or no time.
inline std::optional<double> mraysPerSecond(double rays, double ms) {
    if (rays <= 0.0 || !(ms > 0.0)) return std::nullopt;
    return rays / (ms * 1e3);
}

// A rendered image against the reference (BenchScene::reference): colour error and primary hits.
struct ImageError {
    double rmse = 0.0;                // over RGB, values clamped to [0, 1] as in the PNG
    std::optional<double> psnr;       // dB, peak 1; empty when rmse == 0 (identical)
    double maxError = 0.0;            // largest channel difference
    double primaryMismatch = 0.0;     // fraction of pixels whose primary hit (primid) differs
};

// Rays of one kind in the whole render and how fast they were traced. Primary rates come from a
// render with only camera rays, shadow rates from the extra time a depth-1 render with lights
// takes, secondary rates (reflected and refracted rays with their own shadow rays) from the extra
// time of the full render: differences of medians, so a difference within the noise is empty.
struct RayKindFigures {
    std::string kind;                       // "primary", "shadow", "secondary"
    uint64_t rays = 0;                      // in the full render
    std::optional<double> mraysPerSecond;   // empty when there are no such rays or not resolved
    std::string note;                       // why mraysPerSecond is empty
};

// Build time at one thread count.
struct ThreadTiming {
    int threads = 0;
    Spread ms;
};

// One accelerator on one scene, at the scene's maxdepth.
struct AccelResult {
    std::string accel;                  // --accel name, e.g. "bvh-hq", "kd-restart"
    std::string kernel;                 // shaders/render_<kernel>.comp
    std::vector<ThreadTiming> build;    // CPU build time per thread count, ascending threads (or buildOnDevice)
    // The build is the driver's on the device (rayquery): one ThreadTiming at the run's most threads,
    // GPU timestamps of the driver's build in each timed full render; not in the CPU build scaling.
    bool buildOnDevice = false;
    // false: the traversal has no counters (the driver's, rayquery), so the per-ray figures, the
    // SIMD efficiency and the heatmaps are not measured (reports print "—", bench.json null).
    bool traversalCounted = true;
    std::vector<accel::AccelStat> buildStats;  // of the build with the most threads
    uint64_t structureBytes = 0;        // on the GPU: nodes, index lists, extra arrays (the driver's)

    Spread traceMs;                     // full Whitted render, GPU timestamps
    Spread primaryOnlyMs;               // camera rays only (maxdepth 1, no lights)
    Spread depthOneMs;                  // camera rays and their shadow rays (maxdepth 1)
    // Embree on the same camera rays, timed in the same repeats as primaryOnlyMs (interleaved), so a
    // change of the machine's load along the run shows beside the accelerator it touched; the ratios
    // use the scene's one Embree figure (primaryVsEmbree), of which these runs are a part. Empty
    // without Embree.
    std::optional<Spread> embreeSingleMs, embreePacketMs;  // rtcIntersect1, rtcIntersect16
    std::vector<RayKindFigures> rayKinds;  // primary, shadow, secondary
    double mraysPerSecond = 0.0;        // all rays of the full render / its median time

    // Statistics variant of the kernel, full render; per ray over all kinds together.
    double nodesPerRay = 0.0, leavesPerRay = 0.0, trianglesPerRay = 0.0, restartsPerRay = 0.0;
    // The same for camera rays alone (from the primary-only statistics render).
    double primaryNodesPerRay = 0.0, primaryTrianglesPerRay = 0.0;
    // Camera rays' node steps a ray as the device's subgroups run them in lock-step (gpu/lockstep.h),
    // and the subgroup size; 0 in a report from before they were measured.
    double primaryLockstepNodesPerRay = 0.0;
    uint32_t simdLanes = 0;
    std::optional<double> primarySimdEfficiency() const {
        if (primaryLockstepNodesPerRay <= 0.0) return std::nullopt;
        return primaryNodesPerRay / primaryLockstepNodesPerRay;
    }
    // The camera-ray rate (the "primary" ray kind).
    std::optional<double> primaryMrays() const {
        for (const RayKindFigures& k : rayKinds)
            if (k.kind == "primary") return k.mraysPerSecond;
        return std::nullopt;
    }
    uint64_t cappedRays = 0;            // rays a traversal ended at its iteration cap

    ImageError error;                   // the full render against the reference
    Image image;                        // the full render, 3 channels, linear RGB
    Image diff;                         // makeDiffImage(image, reference, 2/255)
    std::vector<uint32_t> nodesPerPixel;  // nodes visited by all rays of each pixel, top row first
    // The same for the camera ray alone (the primary-only statistics render): a reflective or
    // refractive object, whose pixels trace many rays, does not hide what the walk of a camera
    // ray costs. Empty in a report from before they were kept.
    std::vector<uint32_t> primaryNodesPerPixel;
};

// One point of the error-against-time plot.
struct ErrorPoint {
    std::string label;         // "kd-restart", "aac delta 8", "bvh maxdepth 2", "CPU double"
    std::string group;         // "accelerator", "aac-delta", "maxdepth", "cpu-reference"
    std::string accel;         // structure used
    int delta = 0;             // AAC delta of the aac-delta group; 0 otherwise
    int maxDepth = 0;
    std::string precision;     // "float (GPU)" or "double (CPU)"
    double buildMs = 0.0;      // median, all threads
    double traceMs = 0.0;      // median GPU time (CPU render time for the CPU reference)
    double totalMs() const { return buildMs + traceMs; }
    ImageError error;
    bool pareto = false;       // on the front: no other point is both faster and more accurate
};

// The AAC BVH against its delta, after Tables 5.5 and 5.6 of A. F. Mahmuda, "Bounding Volume
// Hierarchy Construction Using Agglomerative Clustering for Faster Ray Tracing", thesis, ITS 2017.
struct DeltaResult {
    int delta = 0;
    double epsilon = 0.0;
    Spread buildMs;            // all threads
    Spread traceMs;            // full render, GPU
    double nodesPerRay = 0.0, trianglesPerRay = 0.0;  // Mahmuda 2017 counts both as intersection tests
    double sahCost = 0.0;
};

// The BVH and the kd-tree built one after the other and at the same time (each with all threads).
struct ConcurrentBuild {
    std::string bvhAccel, kdAccel;
    Spread bvhMs, kdMs;        // each alone
    Spread concurrentMs;       // both at once, wall clock
};

// The CPU baseline of the scene (bench/embree_baseline.h): Embree on the camera rays, all threads.
struct EmbreeResult {
    std::string version;               // "Embree 3.13.5"; empty when there is no baseline
    std::string note;                  // why there is none
    int threads = 0;
    // Over every interleaved repeat of every accelerator of the scene: the one figure every
    // accelerator's ratio to Embree divides by (primaryVsEmbree).
    Spread singleMs, packetMs;
    // The timings those spreads summarise, so that `vkray bench --merge` summarises the samples of
    // every shard as one run would.
    std::vector<double> singleSamples, packetSamples;
    // Camera rays on which Embree names the reference's triangle (primary hit), as a check that the
    // baseline traces the same rays; below 1 only through ties and float rounding at edges.
    double agreement = 0.0;

    // Whether the scene has the Embree figure that ratios divide by.
    bool measured() const { return !version.empty() && singleMs.median > 0.0; }
};

// One unit of measurement of the run (bench_shard.h): "reference", "accel NAME", "concurrent",
// "aac-delta D" or "maxdepth-sweep", and the shard that measured it (0 in an unsharded run).
struct ConfigurationRun {
    std::string label;
    int shard = 0;
};

struct SceneResult {
    int index = 0;             // 0-based position among the run's scenes (a scene may be given twice)
    std::string file;          // as given on the command line
    std::string name;          // file stem, for headings and image names
    std::string view;          // the camera: "scene", "close" or the --camera text
    uint64_t triangles = 0;
    int width = 0, height = 0, maxDepth = 0;

    // The high-quality reference: the CPU renderer in double precision at the scene's maxdepth,
    // tracing with the CPU traversal of `referenceAccel` (exact: same hits as brute force).
    std::string referenceAccel;
    double referenceBuildMs = 0.0, referenceRenderMs = 0.0;
    Image reference;

    EmbreeResult embree;
    std::vector<AccelResult> accels;
    std::vector<DeltaResult> deltas;
    std::vector<ErrorPoint> errorPoints;
    std::optional<ConcurrentBuild> concurrent;
    std::vector<ConfigurationRun> configurations;  // what of this scene the run measured, in run order
};

// Accelerator a's camera-ray rate over Embree rtcIntersect1's on the same rays: the scene's one
// Embree figure (EmbreeResult::singleMs, the median of every interleaved Embree run of the scene) over
// a's camera-ray median. One divisor for every accelerator, so the ratios order the accelerators as
// their rates do. Empty without Embree or without a camera-ray time.
inline std::optional<double> primaryVsEmbree(const SceneResult& scene, const AccelResult& a) {
    if (!scene.embree.measured() || !(a.primaryOnlyMs.median > 0.0)) return std::nullopt;
    return scene.embree.singleMs.median / a.primaryOnlyMs.median;
}

// The scene's accelerator `name` ("bvh", "rayquery") with a camera-ray time, a yardstick of
// primaryVs; null when there is none.
inline const AccelResult* yardstick(const SceneResult& scene, const std::string& name) {
    const AccelResult* found = nullptr;
    for (const AccelResult& b : scene.accels)
        if (b.accel == name) found = &b;
    return found && found->primaryOnlyMs.median > 0.0 ? found : nullptr;
}

// Accelerator a's camera-ray rate over yardstick `name`'s in the same scene ("vs bvh", the kd walks'
// yardstick; "x rayquery", the driver's): the yardstick's camera-ray median over a's, which is also the
// quotient of the two ratios to Embree. Empty when the scene has no such accelerator or either time is
// missing.
inline std::optional<double> primaryVs(const SceneResult& scene, const AccelResult& a, const std::string& name) {
    const AccelResult* y = yardstick(scene, name);
    if (!y || !(a.primaryOnlyMs.median > 0.0)) return std::nullopt;
    return y->primaryOnlyMs.median / a.primaryOnlyMs.median;
}

// The settings that decide what a run measures; shards merge only when theirs are equal.
struct BenchSettings {
    std::vector<std::string> scenes, accels;
    int width = 0, height = 0;        // 0: each scene's size
    std::string view = "scene";
    int repeat = 0;
    std::vector<int> threads;         // resolved build thread counts
    std::vector<int> deltas, maxDepths;
    bool maxDepthSweep = true;
};

// A share of the run: shard `index` of `count` (0-based).
struct ShardSpec {
    int index = 0, count = 1;
};

// Where and when one shard ran, as a merged report lists it.
struct ShardInfo {
    ShardSpec shard;
    std::string node, device, driver, deviceType, vulkanApi;
    int hardwareThreads = 0;
    std::string commandLine, startedAt;
    double elapsedSeconds = 0.0;
    size_t configurations = 0;        // how many this shard measured
    std::string source;               // the bench.json it was read from
    std::optional<double> loadAverageStart, loadAverageEnd;  // as BenchResults has them
};

struct BenchResults {
    std::string vkrayVersion, revision;   // VKRAY_VERSION, git revision at build time
    std::string commandLine;
    std::string startedAt;                // ISO 8601, UTC
    double elapsedSeconds = 0.0;
    std::string device, driver, deviceType, vulkanApi;
    int hardwareThreads = 0;
    // The machine's 1-minute load average (getloadavg) when the run started and when it ended, for
    // the warning about a machine busy with other work (runWarnings, report.h); empty where the
    // system does not give it, and in a merged report (its shards have theirs).
    std::optional<double> loadAverageStart, loadAverageEnd;
    int repeat = 0;                       // timed repeats after one warm-up
    std::vector<int> threadCounts;        // build-scaling thread counts
    std::vector<SceneResult> scenes;

    std::string node;                     // the machine's host name
    BenchSettings settings;
    ShardSpec shard;                      // 0/1 for an unsharded run
    size_t configurationCount = 0;        // of the whole run, every shard together
    std::string configurationHash;        // of that list (bench_shard.h)
    std::vector<ShardInfo> shards;        // a merged report: every shard; empty otherwise

    // Why the run did not measure all it was to (the error of the scene it stopped at, or
    // "interrupted by SIGTERM"); kStillRunning in the report a run saves after each scene, which a
    // killed run leaves behind; empty when the run is complete. `vkray bench --resume` measures the
    // rest (bench_resume.h).
    std::string failure;
    bool complete() const { return failure.empty(); }
};

inline constexpr const char* kStillRunning = "the run was still measuring when this report was saved (killed, or running)";

}  // namespace vkray::bench
