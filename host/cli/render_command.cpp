// `vkray render SCENE`: load, render on the GPU (or the CPU reference with --cpu), write the image
// and the requested AOVs, report what was done.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "accel/accel.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "gpu/scene_buffers.h"
#include "gpu/vulkan_context.h"
#include "image/image_io.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray::cli {
namespace {

struct RenderArgs {
    std::string scene;
    std::string output;
    std::string accel = "bvh";  // DESIGN.md: the AAC BVH's default preset
    int aacDelta = 0;
    double aacEpsilon = 0.0;
    double kdTraversalCost = 0.0, kdIntersectionCost = 0.0;
    std::optional<double> kdEmptyBonus;
    int kdMaxDepth = 0;
    bool counters = false;
    bool cpu = false;
    std::string device;
    std::string size;
    std::optional<int> maxDepth;
    int threads = 0;
    std::vector<std::string> aovs;
    bool stats = false;
    bool json = false;
};

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

// "depth=d.pfm" -> {"depth", "d.pfm"}, names and file names checked by image_io's rules.
std::map<std::string, std::string> parseAovs(const std::vector<std::string>& specs) {
    std::map<std::string, std::string> out;
    for (const std::string& s : specs) {
        const auto eq = s.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
            throw Error("--aov " + s + ": expected NAME=FILE.pfm (names: depth, primid, normal)");
        const std::string name = s.substr(0, eq), file = s.substr(eq + 1);
        checkAovPath(file, name);
        out[name] = file;
    }
    return out;
}

// -o wins; else the scene's `output NAME` (".png" added when it has no extension); else SCENE.png.
std::filesystem::path outputPath(const RenderArgs& args, const Scene& scene) {
    if (!args.output.empty()) return args.output;
    if (!scene.output.empty()) {
        std::filesystem::path p = scene.output;
        if (!p.has_extension()) p += ".png";
        return p;
    }
    return std::filesystem::path(args.scene).stem().string() + ".png";
}

void checkRenderable(const Scene& scene, const std::string& file) {
    if (!scene.hasCamera) throw Error(FileLoc{file}, "the scene has no 'camera' line");
    if (scene.triangles.empty()) throw Error(FileLoc{file}, "the scene has no triangles (nothing to render)");
}

RenderOptions resolveOptions(const RenderArgs& args, const Scene& scene) {
    RenderOptions o;
    o.width = scene.width;
    o.height = scene.height;
    if (!args.size.empty()) std::tie(o.width, o.height) = parseSize(args.size);
    o.maxDepth = args.maxDepth.value_or(scene.maxDepth);
    if (o.maxDepth < 1 || o.maxDepth > kMaxDepthLimit)
        throw Error("--maxdepth " + std::to_string(o.maxDepth) + ": must be 1.." +
                    std::to_string(kMaxDepthLimit));
    // oneTBB crashes (SIGSEGV) on an arena of more than 65535 slots; no machine has 1024 cores.
    if (args.threads < 0 || args.threads > 1024) throw Error("--threads must be 0 (all cores) or 1..1024");
    o.threads = args.threads;
    o.accel = args.accel;
    o.countTraversal = args.counters;
    return o;
}

accel::AccelSpec resolveAccel(const RenderArgs& args) {
    accel::AccelSpec spec;
    try {
        spec = accel::parseAccel(args.accel);
    } catch (const Error& e) {
        throw Error("--accel " + args.accel + ": " + e.what());
    }
    // A leaf range is clustered by an all-pairs search, O(delta^2) per merge: bound it so a typo
    // cannot turn a build into hours.
    if (args.aacDelta < 0 || args.aacDelta > 1024) throw Error("--aac-delta must be 1..1024");
    if (!(args.aacEpsilon >= 0.0 && args.aacEpsilon < 0.5))  // NaN fails too
        throw Error("--aac-epsilon must be in [0, 0.5) (alpha = 1/2 - epsilon must stay positive)");
    if (!(args.kdTraversalCost >= 0.0 && args.kdTraversalCost < 1e9 && args.kdIntersectionCost >= 0.0 &&
          args.kdIntersectionCost < 1e9))
        throw Error("--kd-traversal-cost and --kd-intersection-cost must be finite and not negative");
    if (args.kdEmptyBonus && !(*args.kdEmptyBonus >= 0.0 && *args.kdEmptyBonus <= 1.0))
        throw Error("--kd-empty-bonus must be in [0, 1]");
    if (args.kdMaxDepth < 0 || args.kdMaxDepth > 64) throw Error("--kd-max-depth must be 1..64");
    spec.aacDelta = args.aacDelta;
    spec.aacEpsilon = args.aacEpsilon;
    spec.kdTraversalCost = args.kdTraversalCost;
    spec.kdIntersectionCost = args.kdIntersectionCost;
    if (args.kdEmptyBonus) spec.kdEmptyBonus = *args.kdEmptyBonus;
    spec.kdMaxDepth = args.kdMaxDepth;
    return spec;
}

// A progress line on stderr for long renders (only on a terminal: logs stay clean).
void printTileProgress(uint32_t done, uint32_t total) {
    std::fprintf(stderr, "\rrendering: tile %u/%u", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

void printBuildProgress(const std::string& phase, double fraction) {
    std::fprintf(stderr, "\rbuilding: %-24s %3d%%", phase.c_str(), int(fraction * 100.0 + 0.5));
}

void clearProgressLine() { std::fprintf(stderr, "\r%*s\r", 48, ""); }

void printRowProgress(int done, int total) {
    if (done % 16 != 0 && done != total) return;
    std::fprintf(stderr, "\rrendering: row %d/%d", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

void printAccelStats(const nlohmann::json& accelJson, const std::vector<accel::AccelStat>& stats) {
    std::printf("accel:       %s, built in %.1f ms\n", accelJson["name"].get<std::string>().c_str(),
                accelJson["build_ms"].get<double>());
    for (const accel::AccelStat& st : stats)
        std::printf("  %-24s %.6g %s\n", st.key.c_str(), st.value, st.unit.c_str());
}

void runRender(const RenderArgs& args) {
    const auto aovFiles = parseAovs(args.aovs);
    const accel::AccelSpec spec = resolveAccel(args);

    auto t0 = Clock::now();
    const Scene scene = loadScene(args.scene);
    const double loadMs = msSince(t0);
    checkRenderable(scene, args.scene);
    const RenderOptions options = resolveOptions(args, scene);
    const std::filesystem::path out = outputPath(args, scene);
    checkColorImagePath(out);  // refuse a bad output before spending minutes on the render

    nlohmann::json report;
    std::string deviceName;
    Frame frame;
    double renderMs = 0.0;
    const bool showProgress = !args.json && isatty(STDERR_FILENO);
    // The device first: a missing or unknown device fails before a long build.
    std::optional<gpu::VulkanContext> ctx;
    if (!args.cpu) {
        ctx.emplace(gpu::ContextOptions{.validation = gpu::validationRequestedByEnvironment(), .device = args.device});
        deviceName = ctx->info().name + " (" + ctx->info().driver + ")";
        gpu::checkSceneFits(*ctx, scene);
    } else {
        deviceName = "CPU reference (double precision)";
    }

    // Only the structure this render uses is built.
    t0 = Clock::now();
    const auto built = accel::buildAccel(
        scene, spec,
        accel::BuildOptions{.threads = options.threads,
                            .progress = showProgress ? accel::BuildProgress(printBuildProgress)
                                                     : accel::BuildProgress()});
    const double buildMs = msSince(t0);
    if (showProgress && spec.family != accel::Family::Brute) clearProgressLine();
    report["accel"] = {{"name", spec.name}, {"build_ms", buildMs}};
    for (const accel::AccelStat& st : built->stats()) report["accel"][st.key] = st.value;

    if (args.cpu) {
        t0 = Clock::now();
        frame = renderReference(scene, options, built->tracer(),
                                showProgress ? RenderProgress(printRowProgress) : RenderProgress());
        renderMs = msSince(t0);
    } else {
        gpu::GpuRenderReport rep;
        t0 = Clock::now();
        frame = gpu::renderOnGpu(*ctx, scene, options, built->gpuData(), &rep,
                                 showProgress ? gpu::TileProgress(printTileProgress) : gpu::TileProgress());
        renderMs = msSince(t0);
        nlohmann::json features = nlohmann::json::object();
        for (const auto& [name, on] : rep.features.list()) features[name] = on;
        report["gpu"] = {{"kernel", rep.kernel}, {"tiles", rep.tiles}, {"submissions", rep.submissions},
                         {"bytes_uploaded", rep.bytesUploaded}, {"accel_bytes", rep.accelBytes},
                         {"upload_ms", rep.uploadMs}, {"pipeline_ms", rep.pipelineMs},
                         {"gpu_ms", rep.gpuMs}, {"dispatch_ms", rep.renderMs}, {"rays", rep.raysTraced},
                         {"shadow_rays", rep.shadowRays}, {"capped_rays", rep.cappedRays},
                         {"features", features}};
        if (options.countTraversal)
            report["gpu"]["traversal"] = {{"nodes", rep.nodesVisited}, {"leaves", rep.leavesVisited},
                                          {"triangles", rep.trianglesTested}, {"restarts", rep.restarts}};
        if (rep.cappedRays > 0)
            std::fprintf(stderr, "warning: %llu rays reached the traversal's iteration cap and were ended "
                                 "there; their pixels may be wrong\n",
                         (unsigned long long)rep.cappedRays);
    }

    writeColorImage(out, frame.width, frame.height, frame.color);
    for (const auto& [name, file] : aovFiles) writeAov(file, frame, name);

    report["scene"] = args.scene;
    report["device"] = deviceName;
    report["width"] = options.width;
    report["height"] = options.height;
    report["maxdepth"] = options.maxDepth;
    report["triangles"] = scene.triangles.size();
    report["materials"] = scene.materials.size();
    report["lights"] = scene.lights.size();
    report["load_ms"] = loadMs;
    report["render_ms"] = renderMs;
    report["output"] = out.string();
    for (const auto& [name, file] : aovFiles) report["aov"][name] = file;

    if (args.json) {
        std::printf("%s\n", report.dump(2).c_str());
        return;
    }
    std::printf("device:      %s\n", deviceName.c_str());
    std::printf("resolution:  %dx%d, maxdepth %d, accel %s\n", options.width, options.height,
                options.maxDepth, options.accel.c_str());
    std::printf("render time: %.1f ms\n", renderMs);
    std::printf("output:      %s\n", out.string().c_str());
    for (const auto& [name, file] : aovFiles) std::printf("aov %-7s  %s\n", name.c_str(), file.c_str());
    if (!args.stats) return;
    std::printf("scene:       %zu triangles, %zu materials, %zu lights (loaded in %.1f ms)\n",
                scene.triangles.size(), scene.materials.size(), scene.lights.size(), loadMs);
    printAccelStats(report["accel"], built->stats());
    if (report.contains("gpu")) {
        const auto& g = report["gpu"];
        std::string on, off;
        for (const auto& [name, enabled] : g["features"].items())
            (enabled.get<bool>() ? on : off) += (name + ", ");
        auto trim = [](std::string s) { return s.empty() ? std::string("none") : s.substr(0, s.size() - 2); };
        std::printf("kernel:      compiled in: %s; left out: %s\n", trim(on).c_str(), trim(off).c_str());
        std::printf("gpu:         kernel render_%s, %u tiles in %u submissions, %.2f MiB uploaded "
                    "(%.2f MiB structure)\n",
                    g["kernel"].get<std::string>().c_str(), g["tiles"].get<unsigned>(),
                    g["submissions"].get<unsigned>(), g["bytes_uploaded"].get<double>() / (1 << 20),
                    g["accel_bytes"].get<double>() / (1 << 20));
        const auto rays = g["rays"].get<uint64_t>(), shadow = g["shadow_rays"].get<uint64_t>();
        std::printf("rays:        %llu camera and secondary, %llu shadow, %llu capped\n",
                    (unsigned long long)rays, (unsigned long long)shadow,
                    (unsigned long long)g["capped_rays"].get<uint64_t>());
        if (g.contains("traversal")) {
            const double all = double(std::max<uint64_t>(rays + shadow, 1));
            const auto& t = g["traversal"];
            std::printf("traversal:   per ray %.2f nodes, %.2f leaves, %.2f triangle tests, %.3f restarts\n",
                        t["nodes"].get<double>() / all, t["leaves"].get<double>() / all,
                        t["triangles"].get<double>() / all, t["restarts"].get<double>() / all);
        }
        std::printf("timing:      upload %.1f ms, pipeline %.1f ms, gpu %.1f ms (timestamps), dispatch+readback %.1f ms\n",
                    g["upload_ms"].get<double>(), g["pipeline_ms"].get<double>(),
                    g["gpu_ms"].get<double>(), g["dispatch_ms"].get<double>());
    }
}

}  // namespace

void registerRenderCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand("render", "Render a .scene file to an image");
    cmd->add_option("scene", args->scene, "Scene file (.scene, or a CSE167 .test file)")->required();
    cmd->add_option("-o,--output", args->output, "Output image (.png, .bmp or .pfm); default: the scene's 'output' or SCENE.png");
    std::string accelList;
    for (const std::string& n : accel::accelNames()) accelList += (accelList.empty() ? "" : ", ") + n;
    cmd->add_option("--accel", args->accel, "Acceleration structure: " + accelList)->default_str(args->accel);
    cmd->add_option("--aac-delta", args->aacDelta, "AAC: leaf-range size delta (overrides the preset)");
    cmd->add_option("--aac-epsilon", args->aacEpsilon, "AAC: reduction exponent epsilon, alpha = 1/2 - epsilon (overrides the preset)");
    cmd->add_option("--kd-traversal-cost", args->kdTraversalCost, "kd-tree SAH: cost of a traversal step (overrides the default)");
    cmd->add_option("--kd-intersection-cost", args->kdIntersectionCost, "kd-tree SAH: cost of a triangle test (overrides the default)");
    cmd->add_option("--kd-empty-bonus", args->kdEmptyBonus, "kd-tree SAH: bonus for cutting off empty space, 0..1 (overrides the default)");
    cmd->add_option("--kd-max-depth", args->kdMaxDepth, "kd-tree: maximum depth (default 8 + 1.3 log2 N)");
    cmd->add_flag("--counters", args->counters, "GPU: compile traversal counters in and report nodes, leaves and triangle tests per ray (slower)");
    cmd->add_flag("--cpu", args->cpu, "Render with the CPU reference renderer (double precision)");
    cmd->add_option("--device", args->device, "Vulkan device: index or name substring (see `vkray devices`)");
    cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT (overrides the scene's 'size')");
    cmd->add_option("--maxdepth", args->maxDepth, "Ray depth, primary rays count as 1 (overrides the scene's)");
    cmd->add_option("--threads", args->threads, "CPU threads (0 = all cores)");
    cmd->add_option("--aov", args->aovs, "Write an AOV: depth=F.pfm, primid=F.pfm, normal=F.pfm (repeatable)");
    cmd->add_flag("--stats", args->stats, "Print scene, kernel-feature and timing statistics");
    cmd->add_flag("--json", args->json, "Print the report as JSON");
    cmd->callback([args, &exitCode] {
        runRender(*args);
        exitCode = 0;
    });
}

}  // namespace vkray::cli
