#include "bench/bench_runner.h"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <thread>

#include "accel/accel.h"
#include "bench/bench_checks.h"
#include "bench/bench_interrupt.h"
#include "bench/bench_resume.h"
#include "bench/bench_run_state.h"
#include "bench/bench_shard.h"
#include "bench/embree_baseline.h"
#include "bench/host_facts.h"
#include "bench/image_error.h"
#include "image/compare.h"
#include "bench/report.h"
#include "core/error.h"
#include "core/timing.h"
#include "cpu/reference_renderer.h"
#include "gpu/kernel_registry.h"
#include "render/scene_checks.h"
#include "render/structure.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray::bench {
namespace {

int maxThreads(const std::vector<int>& counts) { return *std::max_element(counts.begin(), counts.end()); }

double statValue(const std::vector<accel::AccelStat>& stats, const std::string& key) {
    for (const auto& s : stats)
        if (s.key == key) return s.value;
    return 0.0;
}

// A render's figures that one GPU run gives.
struct GpuRun {
    Frame frame;
    gpu::GpuRenderReport report;
};

class Runner {
public:
    Runner(render::Device& device, const BenchOptions& options, const BenchProgressFn& progress)
        : device_(device), options_(options), progress_(progress), start_(Clock::now()) {}

    // The work of one scene: everything in an unsharded run, the shard's share otherwise.
    SceneResult runScene(const std::string& file, int index, int count, const SceneWork& work) {
        sceneIndex_ = index + 1;
        sceneCount_ = count;
        sceneName_ = std::filesystem::path(file).stem().string();
        step("load");
        Scene scene = loadScene(file, render::withinMemory(render::gpuRender()));
        render::checkRenderable(scene, file);
        scene.camera = viewCamera(scene, options_.view);
        device_.checkFits(scene);
        SceneResult result;
        result.index = index;
        result.file = file;
        result.name = sceneName_;
        result.view = options_.view;
        result.triangles = scene.triangles.size();
        result.width = options_.width > 0 ? options_.width : scene.width;
        result.height = options_.height > 0 ? options_.height : scene.height;
        result.maxDepth = scene.maxDepth;

        RenderOptions render;
        render.width = result.width;
        render.height = result.height;
        render.maxDepth = scene.maxDepth;

        // Camera rays alone: the scene without its lights (no shadow rays) at maxdepth 1.
        Scene dark = scene;
        dark.lights.clear();

        Frame reference;
        if (work.needsReferenceImage()) reference = renderReferenceImage(scene, render, result);
        if (!work.accels.empty()) startEmbree(scene, reference, result);
        for (const std::string& name : work.accels)
            result.accels.push_back(runAccel(scene, dark, render, accel::resolveAccel(name), reference, result));
        for (const AccelResult& a : result.accels) result.errorPoints.push_back(acceleratorPoint(a, scene.maxDepth));
        finishEmbree(result);
        if (work.concurrent) result.concurrent = runConcurrentBuild(scene);
        for (int delta : work.deltas) runDelta(scene, render, delta, reference, result);
        if (work.maxDepthSweep) runMaxDepthSweep(scene, render, reference, result);
        if (work.reference) result.errorPoints.push_back(cpuReferencePoint(result));
        markParetoFront(result.errorPoints);
        return result;
    }

private:
    void step(const std::string& what, int repeat = 0, int repeats = 0) {
        throwIfStopRequested();  // SIGINT, SIGTERM (bench_interrupt.h)
        if (!progress_) return;
        progress_(BenchProgress{sceneIndex_, sceneCount_, sceneName_, what, repeat, repeats,
                                msSince(start_) / 1000.0});
    }

    const std::vector<int>& threadCounts() const { return threads_; }

    // The high-quality reference: the CPU renderer (double precision) with the exact CPU traversal
    // of the default BVH, timed like everything else for the "CPU double" point of the plot.
    Frame renderReferenceImage(const Scene& scene, const RenderOptions& render, SceneResult& result) {
        result.referenceAccel = "bvh";
        step("reference: build bvh");
        const render::Structure structure = render::buildStructure(scene, accel::resolveAccel("bvh"), {.tracer = true});
        result.referenceBuildMs = structure.buildMs;
        Frame frame;
        std::vector<double> ms;
        for (int r = 0; r <= options_.repeat; ++r) {  // run 0 warms up and gives the image
            step("reference: CPU render (double)", r, options_.repeat);
            const auto t0 = Clock::now();
            frame = renderReference(scene, render, *structure.tracer);
            if (r > 0) ms.push_back(msSince(t0));
        }
        result.referenceRenderMs = spreadOf(ms).median;
        result.reference = colorImage(frame);
        return frame;
    }

    // The CPU baseline (embree_baseline.h) on the camera rays: built once per scene, checked against
    // the reference's primary hits, then timed next to every accelerator's primary-only render.
    void startEmbree(const Scene& scene, const Frame& reference, SceneResult& result) {
        embree_.reset();
        embreeSingle_.clear();
        embreePacket_.clear();
        result.embree = {};
        if (!embreeAvailable()) {
            result.embree.note = embreeMissingNote();
            return;
        }
        step("Embree: build");
        embree_ = makeEmbreeBaseline(scene, reference.width, reference.height);
        result.embree.version = embree_->version();
        result.embree.threads = maxThreads(threads_);
        embree_->traceMs(EmbreeQuery::Single, result.embree.threads);
        size_t same = 0;
        for (size_t i = 0; i < reference.primId.size(); ++i) same += embree_->hits()[i] == reference.primId[i];
        result.embree.agreement = double(same) / double(std::max<size_t>(reference.primId.size(), 1));
    }

    void finishEmbree(SceneResult& result) {
        if (!embree_ || embreeSingle_.empty()) return;
        result.embree.singleMs = spreadOf(embreeSingle_);
        result.embree.packetMs = spreadOf(embreePacket_);
        result.embree.singleSamples = embreeSingle_;
        result.embree.packetSamples = embreePacket_;
        embree_.reset();
    }

    struct Built {
        std::unique_ptr<accel::BuiltAccel> accel;
        std::vector<ThreadTiming> timings;
    };

    // Warm-up, then `repeat` timed builds at each thread count; returns the last build with the
    // most threads.
    Built timeBuilds(const Scene& scene, const accel::AccelSpec& spec, const std::vector<int>& counts) {
        Built b;
        for (size_t k = 0; k < counts.size(); ++k) {
            std::vector<double> ms;
            for (int r = k == 0 ? 0 : 1; r <= options_.repeat; ++r) {
                step("build " + spec.name + " (" + std::to_string(counts[k]) + (counts[k] == 1 ? " thread)" : " threads)"),
                     r, options_.repeat);
                const auto t0 = Clock::now();
                b.accel = accel::buildAccel(scene, spec, {.threads = counts[k], .progress = {}});
                if (r > 0) ms.push_back(msSince(t0));
            }
            b.timings.push_back({counts[k], spreadOf(ms)});
        }
        return b;
    }

    Built buildOnce(const Scene& scene, const accel::AccelSpec& spec, std::vector<ThreadTiming> timings) {
        step("build " + spec.name);
        return {accel::buildAccel(scene, spec, {.threads = maxThreads(threads_), .progress = {}}), std::move(timings)};
    }

    // The build timings of a structure, timed now when this run has not timed it yet (a shard
    // without its accelerator).
    const std::vector<ThreadTiming>& timingsOf(const Scene& scene, const accel::AccelSpec& spec) {
        const std::string key = accel::structureKey(spec);
        if (!buildTimings_.contains(key)) buildTimings_[key] = timeBuilds(scene, spec, threads_).timings;
        return buildTimings_.at(key);
    }

    Built buildTimed(const Scene& scene, const accel::AccelSpec& spec) {
        const std::string key = accel::structureKey(spec);
        if (const auto it = buildTimings_.find(key); it != buildTimings_.end())
            return buildOnce(scene, spec, it->second);
        Built b = timeBuilds(scene, spec, threads_);
        buildTimings_[key] = b.timings;
        return b;
    }

    GpuRun render(const Scene& scene, const RenderOptions& render, const accel::GpuAccelData& data) {
        GpuRun run;
        run.frame = device_.render(scene, render, data, run.report);
        if (run.report.gpuMs < 0.0)
            throw Error("device '" + device_.get()->info().name + "' has no timestamp queries: vkray bench times "
                        "the GPU with them");
        return run;
    }

    // The three timed variants, interleaved in every repeat so that a drift of the machine's speed
    // touches them alike.
    struct Traced {
        Spread fullMs, primaryMs, depthOneMs;
        std::optional<Spread> embreeSingleMs, embreePacketMs;
        GpuRun full, depthOne;
        // rayquery: the driver's build of its structure on the device in each timed full render.
        std::optional<Spread> driverBuildMs;
    };
    Traced traceTimed(const Scene& scene, const Scene& dark, const RenderOptions& render,
                      const accel::GpuAccelData& data, const std::string& label, bool rayKinds) {
        RenderOptions timed = render, primary = render, depthOne = render;
        primary.maxDepth = depthOne.maxDepth = 1;
        // The timed renders keep no AOVs, as a render without --aov (the kernel then writes compact
        // pixel records); the error figures come from one more full render, with them, untimed.
        timed.primaryAovs = primary.primaryAovs = depthOne.primaryAovs = false;
        Traced t;
        std::vector<double> full, prim, one, single, packet, driverBuild;
        for (int r = 0; r <= options_.repeat; ++r) {  // run 0 is the warm-up
            step("trace " + label, r, options_.repeat);
            const GpuRun f = this->render(scene, timed, data);
            if (r > 0) full.push_back(f.report.gpuMs);
            if (r > 0 && f.report.driverBuildMs && *f.report.driverBuildMs >= 0.0)
                driverBuild.push_back(*f.report.driverBuildMs);
            if (!rayKinds) continue;
            const GpuRun p = this->render(dark, primary, data);
            t.depthOne = this->render(scene, depthOne, data);
            if (r > 0) {
                prim.push_back(p.report.gpuMs);
                one.push_back(t.depthOne.report.gpuMs);
            }
            if (!embree_) continue;
            const int threads = maxThreads(threads_);
            const double ms1 = embree_->traceMs(EmbreeQuery::Single, threads);
            const double ms16 = embree_->traceMs(EmbreeQuery::Packet16, threads);
            if (r > 0) {
                single.push_back(ms1);
                packet.push_back(ms16);
            }
        }
        if (!single.empty()) {
            t.embreeSingleMs = spreadOf(single);
            t.embreePacketMs = spreadOf(packet);
            embreeSingle_.insert(embreeSingle_.end(), single.begin(), single.end());
            embreePacket_.insert(embreePacket_.end(), packet.begin(), packet.end());
        }
        t.fullMs = spreadOf(full);
        if (!driverBuild.empty()) t.driverBuildMs = spreadOf(driverBuild);
        t.full = this->render(scene, render, data);  // the image and AOVs of the error figures
        if (rayKinds) {
            t.primaryMs = spreadOf(prim);
            t.depthOneMs = spreadOf(one);
        }
        return t;
    }

    // Traversal work per ray (all kinds together) from one render with the statistics variant.
    struct Counted {
        double nodesPerRay = 0.0, leavesPerRay = 0.0, trianglesPerRay = 0.0, restartsPerRay = 0.0;
        std::vector<uint32_t> nodesPerPixel;
    };
    Counted countTraversal(const Scene& scene, const RenderOptions& render, const accel::GpuAccelData& data,
                           const std::string& label) {
        step("count " + label);
        RenderOptions counting = render;
        counting.countTraversal = true;
        GpuRun c = this->render(scene, counting, data);
        const double rays = double(std::max<uint64_t>(c.report.raysTraced + c.report.shadowRays, 1));
        return {double(c.report.nodesVisited) / rays, double(c.report.leavesVisited) / rays,
                double(c.report.trianglesTested) / rays, double(c.report.restarts) / rays,
                std::move(c.report.nodesPerPixel)};
    }

    static std::vector<RayKindFigures> rayKindFigures(const Traced& t, uint64_t pixels) {
        const gpu::GpuRenderReport& full = t.full.report;
        const uint64_t secondary = full.raysTraced - std::min(full.raysTraced, pixels);
        const uint64_t shadowOfPrimary = t.depthOne.report.shadowRays;
        const uint64_t secondaryWithShadows = secondary + (full.shadowRays - std::min(full.shadowRays, shadowOfPrimary));
        const double shadowMs = t.depthOneMs.median - t.primaryMs.median;
        const double secondaryMs = t.fullMs.median - t.depthOneMs.median;
        std::vector<RayKindFigures> kinds(3);
        kinds[0] = {"primary", pixels, mraysPerSecond(double(pixels), t.primaryMs.median), ""};
        kinds[1] = {"shadow", full.shadowRays, mraysPerSecond(double(shadowOfPrimary), shadowMs), ""};
        kinds[2] = {"secondary", secondary, mraysPerSecond(double(secondaryWithShadows), secondaryMs), ""};
        for (RayKindFigures& k : kinds)
            if (!k.mraysPerSecond)
                k.note = k.rays == 0 ? "none in this scene" : "time difference within the noise";
        return kinds;
    }

    // The driver's build: its GPU timestamps over the timed full renders plus the CPU's ordering of
    // the triangles it builds over (a.build, timed as every CPU build), at the run's most threads
    // (what "build ms" means elsewhere in the report), and the structure it made.
    void takeDriverBuild(AccelResult& a, const Traced& t) const {
        if (!t.driverBuildMs)
            throw Error("device '" + device_.get()->info().name + "' reported no time for the driver's build of " +
                        a.accel + "'s structure: vkray bench times it with timestamp queries");
        const double host = a.build.empty() ? 0.0 : a.build.back().ms.median;  // ascending threads: the most
        const Spread& device = *t.driverBuildMs;
        a.build = {{maxThreads(threads_), {device.median + host, device.min + host, device.max + host}}};
        a.buildOnDevice = true;
        a.structureBytes = t.full.report.accelBytes;
    }

    AccelResult runAccel(const Scene& scene, const Scene& dark, const RenderOptions& render,
                         const accel::AccelSpec& spec, const Frame& reference, const SceneResult& result) {
        AccelResult a;
        a.accel = spec.name;
        const bool onDevice = spec.family == accel::Family::Driver;  // built by the driver on the device
        Built built = buildTimed(scene, spec);
        a.build = built.timings;
        a.buildStats = built.accel->stats();
        const accel::GpuAccelData data = built.accel->gpuData();
        built.accel.reset();  // the CPU side is not needed any more: free it before tracing
        a.kernel = std::string(gpu::kernelName(data.traversal));
        a.structureBytes = data.bytes();

        const Traced t = traceTimed(scene, dark, render, data, spec.name, true);
        if (onDevice) takeDriverBuild(a, t);
        a.traceMs = t.fullMs;
        a.primaryOnlyMs = t.primaryMs;
        a.depthOneMs = t.depthOneMs;
        a.embreeSingleMs = t.embreeSingleMs;
        a.embreePacketMs = t.embreePacketMs;
        const uint64_t pixels = uint64_t(render.width) * uint64_t(render.height);
        a.rayKinds = rayKindFigures(t, pixels);
        const gpu::GpuRenderReport& rep = t.full.report;
        a.mraysPerSecond = mraysPerSecond(double(rep.raysTraced + rep.shadowRays), t.fullMs.median).value_or(0.0);
        a.cappedRays = rep.cappedRays;
        a.image = colorImage(t.full.frame);
        a.error = imageError(t.full.frame, a.image, reference, result.reference);
        a.diff = makeDiffImage(a.image, result.reference, kDiffThreshold);

        a.traversalCounted = !onDevice;  // the driver's traversal has no counters
        if (!a.traversalCounted) return a;
        const Counted c = countTraversal(scene, render, data, spec.name);
        a.nodesPerRay = c.nodesPerRay;
        a.leavesPerRay = c.leavesPerRay;
        a.trianglesPerRay = c.trianglesPerRay;
        a.restartsPerRay = c.restartsPerRay;
        a.nodesPerPixel = c.nodesPerPixel;
        RenderOptions counting = render;
        counting.countTraversal = true;
        counting.maxDepth = 1;
        GpuRun p = this->render(dark, counting, data);
        a.primaryNodesPerRay = double(p.report.nodesVisited) / double(std::max<uint64_t>(pixels, 1));
        a.primaryTrianglesPerRay = double(p.report.trianglesTested) / double(std::max<uint64_t>(pixels, 1));
        a.primaryLockstepNodesPerRay = double(p.report.lockstepNodes) / double(std::max<uint64_t>(pixels, 1));
        a.simdLanes = p.report.lockstepLanes;
        a.primaryNodesPerPixel = std::move(p.report.nodesPerPixel);
        return a;
    }

    static ErrorPoint acceleratorPoint(const AccelResult& a, int maxDepth) {
        ErrorPoint p;
        p.maxDepth = maxDepth;
        p.label = a.accel;
        p.group = "accelerator";
        p.accel = a.accel;
        p.precision = "float (GPU)";
        p.buildMs = a.build.back().ms.median;
        p.traceMs = a.traceMs.median;
        p.error = a.error;
        return p;
    }

    static ErrorPoint cpuReferencePoint(const SceneResult& s) {
        ErrorPoint p;
        p.label = "CPU double";
        p.group = "cpu-reference";
        p.accel = s.referenceAccel;
        p.maxDepth = s.maxDepth;
        p.precision = "double (CPU)";
        p.buildMs = s.referenceBuildMs;
        p.traceMs = s.referenceRenderMs;
        return p;  // the reference itself: error 0
    }

    // The BVH and the kd-tree at the same time, each with all threads, against each alone.
    std::optional<ConcurrentBuild> runConcurrentBuild(const Scene& scene) {
        std::optional<accel::AccelSpec> bvh, kd;
        for (const std::string& name : options_.accels) {
            const accel::AccelSpec spec = accel::resolveAccel(name);
            if (spec.family == accel::Family::Bvh && !bvh) bvh = spec;
            if (spec.family == accel::Family::Kd && !kd) kd = spec;
        }
        if (!bvh || !kd) return std::nullopt;
        ConcurrentBuild c;
        c.bvhAccel = bvh->name;
        c.kdAccel = kd->name;
        c.bvhMs = timingsOf(scene, *bvh).back().ms;
        c.kdMs = timingsOf(scene, *kd).back().ms;
        std::vector<double> ms;
        const accel::BuildOptions all{.threads = maxThreads(threads_), .progress = {}};
        for (int r = 0; r <= options_.repeat; ++r) {
            step("build " + c.bvhAccel + " and " + c.kdAccel + " concurrently", r, options_.repeat);
            const auto t0 = Clock::now();
            const auto built = accel::buildAccelsConcurrently(scene, {*bvh, *kd}, all);
            if (r > 0) ms.push_back(msSince(t0));
        }
        c.concurrentMs = spreadOf(ms);
        return c;
    }

    // One point of the threshold sweep of A. F. Mahmuda, "Bounding Volume Hierarchy Construction Using
    // Agglomerative Clustering for Faster Ray Tracing", 2017: AAC-HQ's epsilon with another delta.
    void runDelta(const Scene& scene, const RenderOptions& render, int delta, const Frame& reference,
                  SceneResult& result) {
        accel::AccelSpec spec = accel::resolveAccel("bvh");
        spec.bvh.delta = delta;
        const std::string label = "aac delta " + std::to_string(delta);
        DeltaResult d;
        d.delta = delta;
        std::unique_ptr<accel::BuiltAccel> built;
        std::vector<double> ms;
        for (int r = 0; r <= options_.repeat; ++r) {
            step("build " + label, r, options_.repeat);
            const auto t0 = Clock::now();
            built = accel::buildAccel(scene, spec, {.threads = maxThreads(threads_), .progress = {}});
            if (r > 0) ms.push_back(msSince(t0));
        }
        d.buildMs = spreadOf(ms);
        const std::vector<accel::AccelStat> stats = built->stats();
        d.epsilon = statValue(stats, "aac_epsilon");
        d.sahCost = statValue(stats, "sah_cost");
        const accel::GpuAccelData data = built->gpuData();
        built.reset();
        const Traced t = traceTimed(scene, scene, render, data, label, false);
        d.traceMs = t.fullMs;

        const Counted c = countTraversal(scene, render, data, label);
        d.nodesPerRay = c.nodesPerRay;
        d.trianglesPerRay = c.trianglesPerRay;
        result.deltas.push_back(d);

        ErrorPoint p;
        p.label = label;
        p.group = "aac-delta";
        p.accel = "bvh";
        p.delta = delta;
        p.maxDepth = render.maxDepth;
        p.precision = "float (GPU)";
        p.buildMs = d.buildMs.median;
        p.traceMs = d.traceMs.median;
        const Image image = colorImage(t.full.frame);
        p.error = imageError(t.full.frame, image, reference, result.reference);
        result.errorPoints.push_back(p);
    }

    // Fewer bounces trade error for time: each depth below the scene's, with the first BVH of the
    // run (or the first accelerator when there is none).
    void runMaxDepthSweep(const Scene& scene, const RenderOptions& render, const Frame& reference,
                          SceneResult& result) {
        std::vector<int> depths = options_.maxDepths;
        if (depths.empty())
            for (int d = 1; d < scene.maxDepth; ++d) depths.push_back(d);
        std::erase_if(depths, [&](int d) { return d < 1 || d >= scene.maxDepth; });
        if (depths.empty()) return;
        std::string name = options_.accels.front();
        for (const std::string& a : options_.accels)
            if (accel::resolveAccel(a).family == accel::Family::Bvh) {
                name = a;
                break;
            }
        const accel::AccelSpec spec = accel::resolveAccel(name);
        const Built built = buildTimed(scene, spec);  // timed once per run, like the accelerator
        const accel::GpuAccelData data = built.accel->gpuData();
        const double buildMs = built.timings.back().ms.median;
        for (int depth : depths) {
            RenderOptions shallow = render;
            shallow.maxDepth = depth;
            const std::string label = name + " maxdepth " + std::to_string(depth);
            const Traced t = traceTimed(scene, scene, shallow, data, label, false);
            ErrorPoint p;
            p.label = label;
            p.group = "maxdepth";
            p.accel = name;
            p.maxDepth = depth;
            p.precision = "float (GPU)";
            p.buildMs = t.driverBuildMs ? t.driverBuildMs->median : buildMs;  // rayquery: the driver's
            p.traceMs = t.fullMs.median;
            const Image image = colorImage(t.full.frame);
            p.error = imageError(t.full.frame, image, reference, result.reference);
            result.errorPoints.push_back(p);
        }
    }

    render::Device& device_;  // its pipelines are kept for the whole run: they are not what it measures
    const BenchOptions& options_;
    const BenchProgressFn& progress_;
    const Clock::time_point start_;
    std::vector<int> threads_ = options_.threads.empty() ? defaultThreadCounts() : options_.threads;
    // Per accel::structureKey, per scene: builds of one structure are timed once, whatever walks it
    // (the kd traversals share the tree).
    std::map<std::string, std::vector<ThreadTiming>> buildTimings_;
    std::unique_ptr<EmbreeBaseline> embree_;          // of the current scene
    std::vector<double> embreeSingle_, embreePacket_;  // its timings over every accelerator
    int sceneIndex_ = 0, sceneCount_ = 0;
    std::string sceneName_;

public:
    void startScene() { buildTimings_.clear(); }
    const std::vector<int>& threads() const { return threads_; }
};

}  // namespace

BenchResults runBench(render::Device& device, const BenchOptions& options, const std::string& commandLine,
                      const BenchProgressFn& progress, const BenchContinuation& continuation) {
    checkBenchOptions(options);
    const auto start = Clock::now();
    BenchResults results = runHeader(options, commandLine);
    if (continuation.previous) continueFrom(*continuation.previous, continuation.previousFile, results);
    const double before = continuation.previous ? continuation.previous->elapsedSeconds : 0.0;
    const std::vector<SceneWork> work = shardWork(results.settings, options.shard);
    std::vector<bool> measure(options.scenes.size());
    for (size_t i = 0; i < measure.size(); ++i) measure[i] = !work[i].empty() && !hasScene(results, int(i));
    // Every scene, before the first is measured: on the host, then on the device.
    const std::vector<render::SceneSize> sizes = checkBenchScenesOnHost(options, measure);
    const gpu::VulkanContext* ctx = device.get();
    if (!ctx) throw std::logic_error("runBench: a render::Device without a device");
    setDevice(results, *ctx);
    if (continuation.previous) checkResumable(*continuation.previous, results, continuation.previousFile);
    checkBenchScenesOnDevice(device, sizes);

    Runner runner(device, options, progress);
    results.threadCounts = runner.threads();
    // Nothing to measure (a complete report resumed): nothing to save either, the report stays as it is.
    const bool anything = std::find(measure.begin(), measure.end(), true) != measure.end();
    const BenchSaveFn save = anything ? continuation.save : BenchSaveFn{};
    if (save) {  // from the start, --out holds this run's report, not an earlier one
        stampResults(results, start, before, kStillRunning);
        save(results);
    }
    for (size_t i = 0; i < options.scenes.size(); ++i) {
        if (!measure[i]) continue;
        try {
            runner.startScene();
            SceneResult scene = runner.runScene(options.scenes[i], int(i), int(options.scenes.size()), work[i]);
            for (const std::string& label : work[i].labels) scene.configurations.push_back({label, options.shard.index});
            results.scenes.push_back(std::move(scene));
        } catch (...) {
            saveAndRethrow(results, start, before, save);
        }
        stampResults(results, start, before, kStillRunning);
        if (save) save(results);
    }
    stampResults(results, start, before, "");
    return results;
}

}  // namespace vkray::bench
