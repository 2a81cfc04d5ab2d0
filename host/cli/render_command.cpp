// `vkray render SCENE`: load, render on the GPU (or the CPU reference with --cpu), write the image
// and the requested AOVs, report what was done.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "gpu/vulkan_context.h"
#include "image/image_io.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray::cli {
namespace {

// Every accelerator name of DESIGN.md; those not built yet are refused with a clear message.
const std::vector<std::string> kAccelNames = {"brute", "bvh", "bvh-fast", "bvh-hq",
                                              "kd-restart", "kd-backtrack", "kd-stack"};

struct RenderArgs {
    std::string scene;
    std::string output;
    std::string accel = "brute";
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

// "640x480" -> (640, 480), within the limits of scene.h.
std::pair<int, int> parseSize(const std::string& text) {
    std::smatch m;
    static const std::regex pattern(R"((\d{1,9})[xX](\d{1,9}))");
    if (!std::regex_match(text, m, pattern))
        throw Error("--size " + text + ": expected WIDTHxHEIGHT, for example 640x480");
    const long long w = std::stoll(m[1]), h = std::stoll(m[2]);
    if (const auto problem = imageSizeProblem(w, h)) throw Error("--size " + text + ": " + *problem);
    return {int(w), int(h)};
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
    if (args.threads < 0) throw Error("--threads must be 0 (all cores) or positive");
    o.threads = args.threads;
    o.accel = args.accel;
    return o;
}

// A progress line on stderr for long renders (only on a terminal: logs stay clean).
void printTileProgress(uint32_t done, uint32_t total) {
    std::fprintf(stderr, "\rrendering: tile %u/%u", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

void printRowProgress(int done, int total) {
    if (done % 16 != 0 && done != total) return;
    std::fprintf(stderr, "\rrendering: row %d/%d", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

void runRender(const RenderArgs& args) {
    const auto aovFiles = parseAovs(args.aovs);
    if (std::find(kAccelNames.begin(), kAccelNames.end(), args.accel) == kAccelNames.end())
        throw Error("--accel " + args.accel + ": unknown accelerator (brute, bvh, bvh-fast, bvh-hq, "
                    "kd-restart, kd-backtrack, kd-stack)");

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
    if (args.cpu) {
        if (options.accel != "brute")
            throw Error("--cpu: accelerator '" + options.accel + "' is not implemented on the CPU yet (available: brute)");
        deviceName = "CPU reference (double precision)";
        t0 = Clock::now();
        frame = renderReference(scene, options, showProgress ? RenderProgress(printRowProgress) : RenderProgress());
        renderMs = msSince(t0);
    } else {
        if (!gpu::gpuSupportsAccel(options.accel))
            throw Error("--accel " + options.accel + ": not implemented on the GPU yet (available: brute)");
        gpu::VulkanContext ctx({.validation = gpu::validationRequestedByEnvironment(), .device = args.device});
        deviceName = ctx.info().name + " (" + ctx.info().driver + ")";
        gpu::GpuRenderReport rep;
        t0 = Clock::now();
        frame = gpu::renderOnGpu(ctx, scene, options, &rep,
                                 showProgress ? gpu::TileProgress(printTileProgress) : gpu::TileProgress());
        renderMs = msSince(t0);
        nlohmann::json features = nlohmann::json::object();
        for (const auto& [name, on] : rep.features.list()) features[name] = on;
        report["gpu"] = {{"tiles", rep.tiles}, {"submissions", rep.submissions},
                         {"bytes_uploaded", rep.bytesUploaded}, {"upload_ms", rep.uploadMs},
                         {"pipeline_ms", rep.pipelineMs}, {"gpu_ms", rep.gpuMs},
                         {"dispatch_ms", rep.renderMs}, {"rays", rep.raysTraced},
                         {"features", features}};
    }

    writeColorImage(out, frame.width, frame.height, frame.color);
    for (const auto& [name, file] : aovFiles) writeAov(file, frame, name);

    report["scene"] = args.scene;
    report["device"] = deviceName;
    report["accel"] = options.accel;
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
    if (report.contains("gpu")) {
        const auto& g = report["gpu"];
        std::string on, off;
        for (const auto& [name, enabled] : g["features"].items())
            (enabled.get<bool>() ? on : off) += (name + ", ");
        auto trim = [](std::string s) { return s.empty() ? std::string("none") : s.substr(0, s.size() - 2); };
        std::printf("kernel:      compiled in: %s; left out: %s\n", trim(on).c_str(), trim(off).c_str());
        std::printf("gpu:         %u tiles in %u submissions, %.2f MiB uploaded, %llu camera and secondary rays\n",
                    g["tiles"].get<unsigned>(), g["submissions"].get<unsigned>(),
                    g["bytes_uploaded"].get<double>() / (1 << 20),
                    (unsigned long long)g["rays"].get<uint64_t>());
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
    cmd->add_option("--accel", args->accel, "Acceleration structure: brute (bvh, kd-* come with their issues)");
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
