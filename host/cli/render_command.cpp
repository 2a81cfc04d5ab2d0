// `vkray render SCENE`: load, render on the GPU (or the CPU reference with --cpu), write the image
// and the requested AOVs, report what was done.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_file.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "cli/render_report.h"
#include "core/error.h"
#include "core/timing.h"
#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "gpu/scene_buffers.h"
#include "gpu/vulkan_context.h"
#include "image/image_io.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray::cli {
namespace {

struct RenderArgs {
    std::string scene;
    std::string output;
    std::string accel{accel::kDefaultAccel};
    accel::Tuning tuning;  // --aac-delta, --kd-max-depth, ... (accel/accel_spec.cpp)
    bool counters = false;
    bool cpu = false;
    std::string device;
    std::string size;
    std::string view = "scene";
    std::string background;  // R,G,B: overrides the scene's
    std::optional<int> maxDepth;
    std::optional<int> spp;
    int threads = 0;
    std::vector<std::string> aovs;
    bool stats = false;
    bool json = false;
    bool quiet = false;  // no progress line, no summary: errors and warnings only
    std::string saveAccel, loadAccel;  // structure files (accel/accel_file.h)
};

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
// The colour image's file: -o, else the scene's `output`, else SCENE.png; a name without an
// extension, from either, gets .png.
std::filesystem::path outputPath(const RenderArgs& args, const Scene& scene) {
    const auto withPng = [](std::filesystem::path p) {
        if (!p.has_extension()) p += ".png";
        return p;
    };
    if (!args.output.empty()) {
        if (args.output == "-") throw Error("-o -: the image goes to a file, not to standard output: name one");
        if (!std::filesystem::path(args.output).has_filename() || std::filesystem::is_directory(args.output))
            throw Error("-o " + args.output + ": names a directory; name the image file");
        return withPng(args.output);
    }
    if (!scene.output.empty()) return withPng(scene.output);
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
    o.spp = args.spp.value_or(scene.spp);
    if (o.spp < 1 || o.spp > kMaxSamplesPerPixel)
        throw Error("--spp " + std::to_string(o.spp) + ": must be 1.." + std::to_string(kMaxSamplesPerPixel));
    o.countTraversal = args.counters;
    o.primaryAovs = !args.aovs.empty();
    return o;
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

void printLoadProgress(const std::string& step) {
    clearProgressLine();
    std::fprintf(stderr, "loading: %s", step.c_str());
}

void printRowProgress(int done, int total) {
    if (done % 16 != 0 && done != total) return;
    std::fprintf(stderr, "\rrendering: row %d/%d", done, total);
    if (done == total) std::fprintf(stderr, "\r%*s\r", 40, "");
}

// --save-accel / --load-accel, checked against the rest of the command line before any work.
struct AccelFiles {
    std::string save;
    std::optional<accel::AccelFileReader> load;  // header read, spec checked; the arrays come later
    double loadMs = 0.0;                          // spent on `load` so far
};

AccelFiles openAccelFiles(const RenderArgs& args, const accel::AccelSpec& spec) {
    AccelFiles files;
    if (!args.saveAccel.empty() && !args.loadAccel.empty())
        throw Error("--save-accel and --load-accel: give one (a loaded structure is already in its file)");
    const bool brute = spec.family == accel::Family::Brute;
    if (!args.saveAccel.empty()) {
        if (brute) throw Error("--save-accel: --accel brute builds no structure to save");
        accel::checkAccelFileTarget(args.saveAccel);
        files.save = args.saveAccel;
    }
    if (!args.loadAccel.empty()) {
        if (brute) throw Error("--load-accel: --accel brute uses no structure to load");
        // The file holds only what the GPU kernel reads; the CPU renderer walks the builder's own
        // tree. Refusing says so, where rebuilding silently would spend the time the flag was to save.
        if (args.cpu)
            throw Error("--load-accel " + args.loadAccel + ": the file holds the GPU's arrays only; --cpu "
                        "builds its own structure (drop --load-accel)");
        const Clock::time_point t0 = Clock::now();
        files.load.emplace(args.loadAccel);
        files.load->checkSpec(spec);
        files.loadMs = msSince(t0);
    }
    return files;
}

struct Structure {
    std::unique_ptr<accel::BuiltAccel> built;  // none when loaded from a file
    std::unique_ptr<geometry::Tracer> tracer;  // CPU renders; walks *built, so is destroyed first
    std::optional<accel::GpuAccelData> data;   // GPU renders, and what --save-accel writes
};

// The structure of a render, read from --load-accel's file or built (and written to --save-accel's).
Structure prepareStructure(const Scene& scene, const RenderOptions& options, const accel::AccelSpec& spec,
                           AccelFiles& files, bool gpu, bool showProgress, RenderReport& report) {
    Structure s;
    Clock::time_point t0 = Clock::now();
    if (files.load) {
        accel::LoadedAccel loaded = files.load->readArrays();
        report.accelFile =
            AccelFileReport{.path = files.load->path().string(), .loaded = true, .ms = files.loadMs + msSince(t0)};
        report.accelStats = std::move(loaded.stats);
        s.data = std::move(loaded.data);
        return s;
    }
    s.built = accel::buildAccel(
        scene, spec,
        accel::BuildOptions{.threads = options.threads,
                            .progress = showProgress ? BuildProgress(printBuildProgress) : BuildProgress()});
    // The CPU's tracer is part of its build; a GPU render needs none.
    if (!gpu) s.tracer = s.built->makeTracer(scene);
    report.buildMs = msSince(t0);
    if (showProgress && spec.family != accel::Family::Brute) clearProgressLine();
    report.accelStats = s.built->stats();
    if (gpu || !files.save.empty()) s.data = s.built->gpuData();
    if (!files.save.empty()) {
        t0 = Clock::now();
        accel::saveAccelFile(files.save, spec, scene, *s.data, report.accelStats);
        report.accelFile = AccelFileReport{.path = files.save, .loaded = false, .ms = msSince(t0)};
    }
    return s;
}

// Renders with the structure `spec` names: on the GPU of `ctx`, or on the CPU reference when there
// is none. Fills the build and render parts of `report`. On the GPU the kernel's pipeline is
// created on a thread while the structure is built (tens of ms on lavapipe).
Frame renderFrame(const Scene& scene, const RenderOptions& options, const accel::AccelSpec& spec,
                  const gpu::VulkanContext* ctx, AccelFiles& files, bool showProgress, RenderReport& report) {
    std::optional<gpu::KernelCache> kernels;
    std::future<double> compiling;  // waits in its destructor, so kernels outlives it
    if (ctx) {
        kernels.emplace(*ctx);
        compiling = std::async(std::launch::async, [&] {
            return gpu::prepareKernel(scene, options, accel::kernelOf(spec), *kernels);
        });
    }
    const Structure structure = prepareStructure(scene, options, spec, files, ctx != nullptr, showProgress, report);

    Frame frame;
    const Clock::time_point t0 = Clock::now();
    if (structure.tracer) {
        frame = renderReference(scene, options, *structure.tracer,
                                showProgress ? RenderProgress(printRowProgress) : RenderProgress());
        report.renderMs = msSince(t0);
        return frame;
    }
    const double preparedMs = compiling.get();
    gpu::GpuRenderReport& rep = report.gpu.emplace();
    frame = gpu::renderOnGpu(*ctx, scene, options, *structure.data, &rep,
                             showProgress ? gpu::TileProgress(printTileProgress) : gpu::TileProgress(), &*kernels);
    rep.pipelineMs += preparedMs;
    report.renderMs = msSince(t0);
    if (rep.cappedRays > 0)
        std::fprintf(stderr, "warning: %llu rays reached the traversal's iteration cap and were ended "
                             "there; their pixels may be wrong\n",
                     (unsigned long long)rep.cappedRays);
    return frame;
}

void runRender(const RenderArgs& args) {
    const auto aovFiles = parseAovs(args.aovs);
    const accel::AccelSpec spec = accel::resolveAccel(args.accel, args.tuning);
    // A wrong structure file fails here, in milliseconds, before a big scene loads.
    AccelFiles accelFiles = openAccelFiles(args, spec);

    const bool showProgress = !args.json && !args.quiet && isatty(STDERR_FILENO);
    const Clock::time_point t0 = Clock::now();
    // The device opens while the scene loads: the Vulkan loader and the driver take tens of
    // milliseconds to start. Its errors surface after the scene's, as when it opened second.
    std::future<std::unique_ptr<gpu::VulkanContext>> opening;
    if (!args.cpu)
        opening = std::async(std::launch::async, [device = args.device] {
            return std::make_unique<gpu::VulkanContext>(
                gpu::ContextOptions{.validation = gpu::validationRequestedByEnvironment(), .device = device});
        });
    ParseOptions parse;
    if (showProgress) parse.progress = printLoadProgress;
    Scene scene = loadScene(args.scene, parse);
    if (showProgress) clearProgressLine();
    RenderReport report;
    report.loadMs = msSince(t0);
    checkRenderable(scene, args.scene);
    scene.camera = viewCamera(scene, args.view);
    if (!args.background.empty()) scene.background = parseColour(args.background, "--background");
    const RenderOptions options = resolveOptions(args, scene);
    const std::filesystem::path out = outputPath(args, scene);
    checkColorImagePath(out);  // refuse a bad output before spending minutes on the render
    if (accelFiles.load) {  // and a structure file for another scene
        const Clock::time_point t1 = Clock::now();
        accelFiles.load->checkScene(scene);
        accelFiles.loadMs += msSince(t1);
    }

    // The device before the build: a missing or unknown device fails before a long build.
    std::unique_ptr<gpu::VulkanContext> ctx;
    if (!args.cpu) {
        ctx = opening.get();
        report.device = ctx->info().name + " (" + ctx->info().driver + ")";
        gpu::checkSceneFits(*ctx, scene);
    } else {
        report.device = "CPU reference (double precision)";
    }

    const Frame frame = renderFrame(scene, options, spec, ctx.get(), accelFiles, showProgress, report);
    writeColorImage(out, frame.width, frame.height, frame.color);
    for (const auto& [name, file] : aovFiles) writeAov(file, frame, name);

    report.scene = args.scene;
    report.output = out.string();
    report.aovs = aovFiles;
    report.options = options;
    report.totalMs = msSince(t0);
    report.accel = spec.name;
    report.triangles = scene.triangles.size();
    report.materials = scene.materials.size();
    report.lights = scene.lights.size();
    report.origin = {scene.origin.x, scene.origin.y, scene.origin.z};
    if (args.json) {
        std::printf("%s\n", reportJson(report).c_str());
        return;
    }
    if (!args.quiet) printReport(report, args.stats);
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
    for (const accel::TuningOption& o : accel::tuningOptions())
        cmd->add_option(std::string(o.flag), args->tuning[std::string(o.flag)], std::string(o.help))
            ->type_name(o.integer ? "INT" : "FLOAT");
    CLI::Option* counters = cmd->add_flag("--counters", args->counters,
                                          "GPU: compile traversal counters in and report nodes, leaves and triangle tests per ray (slower)");
    CLI::Option* cpu = cmd->add_flag("--cpu", args->cpu, "Render with the CPU reference renderer (double precision)");
    CLI::Option* device = cmd->add_option("--device", args->device, "Vulkan device: index or name substring (see `vkray devices`)");
    // GPU-only flags with --cpu would be silently ignored: refused instead.
    cpu->excludes(counters);
    cpu->excludes(device);
    cmd->add_option("--size", args->size, "Image size WIDTHxHEIGHT (overrides the scene's 'size')");
    addViewOption(*cmd, args->view);
    cmd->add_option("--spp", args->spp,
                    "Camera rays per pixel, averaged (overrides the scene's 'spp'; default 1, the pixel centre)");
    cmd->add_option("--background", args->background,
                    "R,G,B: the radiance of rays that hit nothing (overrides the scene's 'background'; default black)");
    cmd->add_option("--maxdepth", args->maxDepth, "Ray depth, primary rays count as 1 (overrides the scene's)");
    cmd->add_option("--threads", args->threads, "CPU threads (0 = all cores)");
    cmd->add_option("--aov", args->aovs, "Write an AOV: depth=F.pfm, primid=F.pfm, normal=F.pfm (repeatable)");
    cmd->add_option("--save-accel", args->saveAccel,
                    "Write the built structure to FILE, for --load-accel in later renders of the same scene")
        ->type_name("FILE");
    cmd->add_option("--load-accel", args->loadAccel,
                    "Read the structure from FILE (written by --save-accel for this scene and --accel) "
                    "instead of building it; GPU only")
        ->type_name("FILE");
    CLI::Option* stats = cmd->add_flag("--stats", args->stats, "Print scene, kernel-feature and timing statistics");
    CLI::Option* json = cmd->add_flag("--json", args->json, "Print the report as JSON");
    cmd->add_flag("--quiet", args->quiet, "No progress line and no summary: errors and warnings only")
        ->excludes(json)
        ->excludes(stats);
    cmd->callback([args, &exitCode] {
        runRender(*args);
        exitCode = 0;
    });
}

}  // namespace vkray::cli
