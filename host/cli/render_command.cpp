// `vkray render SCENE`: load, render on the GPU (or the CPU reference with --cpu), write the image
// and the requested AOVs, report what was done.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>
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
#include "core/hash64.h"
#include "core/timing.h"
#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "gpu/scene_buffers.h"
#include "gpu/vulkan_context.h"
#include "image/image_io.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"
#include "vkray_revision.h"  // generated at build time by scripts/revision.cmake

namespace vkray::cli {
namespace {

struct RenderArgs {
    std::vector<std::string> scenes;
    std::string output;
    std::string outDir;  // several scenes: each image into this folder under its own name
    std::string accel{accel::kDefaultAccel};  // NAME[:OPTION=VALUE...] (accel/accel_spec.h)
    bool counters = false;
    bool cpu = false;
    std::string device;
    std::string size;
    std::string view = "scene";
    std::string background;  // R,G,B: overrides the scene's
    std::optional<int> maxDepth;
    std::optional<int> spp;
    // The pixels rendered (at most one of these; cli_options.h): a crop window, pixel bounds, one
    // pixel (its values printed), or a tile of a render farm.
    std::string crop, pixelBounds, pixel, tile;
    std::optional<TileIndex> tileIndex;  // --tile, parsed
    std::string encoding = "auto";  // 8-bit outputs: srgb, linear, or auto (linear for CSE167 .test files)
    double exposure = 0.0;
    int threads = 0;
    std::vector<std::string> aovs;
    bool stats = false;
    bool json = false;
    bool quiet = false;  // no progress line, no summary: errors and warnings only
    std::string saveAccel, loadAccel;  // structure files (accel/accel_file.h)
    bool buildOnly = false;  // build and save the structure, render nothing
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

// The colour image's file: -o, which must name its format's extension, else the scene's `output`,
// which gets .png without one (CSE167's rule), else SCENE.png. With --out-dir, the scene's name (its
// `output` or SCENE.png) in that folder. Empty for --pixel without -o: the pixel's values are the output.
std::filesystem::path outputPath(const RenderArgs& args, const std::string& sceneFile, const Scene& scene) {
    const auto withPng = [](std::filesystem::path p) {
        if (!p.has_extension()) p += ".png";
        return p;
    };
    if (!args.output.empty()) {
        if (args.output == "-") throw Error("-o -: the image goes to a file, not to standard output: name one");
        if (!std::filesystem::path(args.output).has_filename() || std::filesystem::is_directory(args.output))
            throw Error("-o " + args.output + ": names a directory; name the image file");
        checkExtensionGiven(args.output, "-o");
        return args.output;
    }
    if (!args.pixel.empty() || args.buildOnly) return {};
    const std::filesystem::path name =
        !scene.output.empty() ? withPng(scene.output) : std::filesystem::path(std::filesystem::path(sceneFile).stem().string() + ".png");
    if (args.outDir.empty()) return name;
    return std::filesystem::path(args.outDir) / name.filename();
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
    o.primaryAovs = !args.aovs.empty() || !args.pixel.empty();
    if (!args.crop.empty()) o.window = parseCrop(args.crop, o.width, o.height);
    if (!args.pixelBounds.empty()) o.window = parsePixelBounds(args.pixelBounds, o.width, o.height);
    if (!args.pixel.empty()) o.window = parsePixel(args.pixel, o.width, o.height);
    if (args.tileIndex) o.window = tileWindow(*args.tileIndex, o.width, o.height);
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
    // The CPU's tracer is part of its build; a GPU render needs none, but the structure's arrays
    // in the kernel's layout (timed apart too: a tenth of the build of a 2M-triangle scene).
    if (!gpu) s.tracer = s.built->makeTracer(scene);
    if (showProgress && spec.family != accel::Family::Brute) clearProgressLine();
    report.accelStats = s.built->stats();
    if (gpu || !files.save.empty()) {
        const Clock::time_point t1 = Clock::now();
        s.data = s.built->gpuData();
        report.gpuDataMs = msSince(t1);
    }
    report.buildMs = msSince(t0);
    if (!files.save.empty()) {
        t0 = Clock::now();
        accel::saveAccelFile(files.save, spec, scene, *s.data, report.accelStats);
        report.accelFile = AccelFileReport{.path = files.save, .loaded = false, .ms = msSince(t0)};
    }
    return s;
}

// Renders with the structure `spec` names: on the GPU, with the pipelines of `kernels` (on its
// device), or on the CPU reference when there is none. Fills the build and render parts of
// `report`. On the GPU the kernel's pipeline is created on a thread while the structure is built
// (tens of ms on lavapipe), unless an earlier scene of the command created it.
Frame renderFrame(const Scene& scene, const RenderOptions& options, const accel::AccelSpec& spec,
                  gpu::KernelCache* kernels, AccelFiles& files, bool showProgress, RenderReport& report) {
    std::future<double> compiling;  // waits in its destructor
    const size_t pipelinesBefore = kernels ? kernels->size() : 0;
    if (kernels) {
        compiling = std::async(std::launch::async, [&] {
            return gpu::prepareKernel(scene, options, accel::kernelOf(spec), *kernels);
        });
    }
    const Structure structure = prepareStructure(scene, options, spec, files, kernels != nullptr, showProgress, report);

    Frame frame;
    const Clock::time_point t0 = Clock::now();
    if (structure.tracer) {
        frame = renderReference(scene, options, *structure.tracer,
                                showProgress ? RenderProgress(printRowProgress) : RenderProgress());
        report.renderMs = msSince(t0);
        return frame;
    }
    const double preparedMs = compiling.get();
    const size_t prepared = kernels->size() - pipelinesBefore;
    gpu::GpuRenderReport& rep = report.gpu.emplace();
    frame = gpu::renderOnGpu(kernels->context(), scene, options, *structure.data, &rep,
                             showProgress ? gpu::TileProgress(printTileProgress) : gpu::TileProgress(), kernels);
    rep.pipelineMs += preparedMs;
    rep.pipelinesCreated += uint32_t(prepared);
    report.renderMs = msSince(t0);
    if (rep.cappedRays > 0)
        std::fprintf(stderr, "warning: %llu rays reached the traversal's iteration cap and were ended "
                             "there; their pixels may be wrong\n",
                     (unsigned long long)rep.cappedRays);
    return frame;
}

// The Vulkan device of a render, opened on a thread while the first scene loads (the loader and the
// driver take tens of milliseconds to start) and kept for the scenes after it, with the kernels'
// pipelines: a scene that needs the same kernel with the same features as an earlier one does not
// wait for its pipeline again. Its errors surface when it is first needed, after the first scene's,
// as when it opened second.
class Device {
public:
    explicit Device(const RenderArgs& args) {
        if (args.cpu || args.buildOnly) return;
        opening_ = std::async(std::launch::async, [device = args.device] {
            return std::make_unique<gpu::VulkanContext>(
                gpu::ContextOptions{.validation = gpu::validationRequestedByEnvironment(), .device = device});
        });
    }
    const gpu::VulkanContext* get() {  // null for --cpu
        if (opening_.valid()) {
            ctx_ = opening_.get();
            kernels_.emplace(*ctx_);
        }
        return ctx_.get();
    }
    gpu::KernelCache* kernels() { return kernels_ ? &*kernels_ : nullptr; }  // once get() opened the device

private:
    std::future<std::unique_ptr<gpu::VulkanContext>> opening_;
    std::unique_ptr<gpu::VulkanContext> ctx_;
    std::optional<gpu::KernelCache> kernels_;  // destroyed before ctx_, whose device it uses
};

// XXH64 of a file's bytes, as 16 hex digits.
std::string fileHash(const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    char text[24];
    std::snprintf(text, sizeof text, "%016llx", (unsigned long long)hash64(bytes.data(), bytes.size()));
    return text;
}

// Where an EXR output lies in the whole image and what made it, so that `vkray assemble` can check
// that tiles belong together: the same scene (its file's bytes and its geometry, which includes
// the meshes), the same settings (everything that changes a pixel) and the same vkray.
ImageMeta outputMeta(const RenderArgs& args, const std::string& sceneFile, const Scene& scene,
                     const RenderOptions& options, const RenderReport& report) {
    const PixelWindow w = options.pixels();
    ImageMeta meta;
    meta.displayWidth = options.width;
    meta.displayHeight = options.height;
    meta.x0 = w.x0;
    meta.y0 = w.y0;
    char geometry[24];
    std::snprintf(geometry, sizeof geometry, "%016llx", (unsigned long long)accel::sceneGeometryHash(scene));
    const Camera& c = scene.camera;
    char settings[512];
    std::snprintf(settings, sizeof settings,
                  "size %dx%d spp %d maxdepth %d accel %s camera %.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g "
                  "background %.9g,%.9g,%.9g device %s",
                  options.width, options.height, options.spp, options.maxDepth, report.accel.c_str(), c.eye.x, c.eye.y,
                  c.eye.z, c.center.x, c.center.y, c.center.z, c.up.x, c.up.y, c.up.z, c.fovyDegrees, scene.background.x,
                  scene.background.y, scene.background.z, report.device.c_str());
    meta.attributes["vkray:version"] = std::string(VKRAY_VERSION) + " (revision " + VKRAY_REVISION + ")";
    meta.attributes["vkray:scene"] = std::filesystem::path(sceneFile).filename().string() + " file " +
                                     fileHash(sceneFile) + " geometry " + geometry;
    meta.attributes["vkray:settings"] = settings;
    if (const auto& t = args.tileIndex)
        meta.attributes["vkray:tile"] = std::to_string(t->index) + "/" + std::to_string(t->count);
    return meta;
}

// --pixel: the one pixel's values on stdout.
void printPixel(const Frame& frame, const RenderReport& report) {
    const glm::vec3 c = frame.color[0], n = frame.normal[0];
    std::printf("pixel %d,%d of %dx%d: colour %.6g %.6g %.6g", frame.x0, frame.y0, report.options.width,
                report.options.height, c.x, c.y, c.z);
    if (frame.primId[0] < 0) std::printf(", no hit");
    else std::printf(", depth %.6g, triangle %d, normal %.4f %.4f %.4f", frame.depth[0], frame.primId[0], n.x, n.y, n.z);
    if (report.gpu && report.options.countTraversal) {  // over every ray of the pixel
        const auto count = [](uint64_t n, const char* one, const char* many) {
            std::printf(", %llu %s", (unsigned long long)n, n == 1 ? one : many);
        };
        count(report.gpu->nodesVisited, "node", "nodes");
        count(report.gpu->leavesVisited, "leaf", "leaves");
        count(report.gpu->trianglesTested, "triangle test", "triangle tests");
    }
    std::printf("\n");
}

// The 8-bit encoding of --encoding and --exposure: auto is sRGB, but linear for CSE167 .test files,
// whose reference images hold linear levels.
Encoding outputEncoding(const RenderArgs& args, const std::string& sceneFile) {
    std::string name = args.encoding;
    if (name == "auto") name = std::filesystem::path(sceneFile).extension() == ".test" ? "linear" : "srgb";
    return parseEncoding(name, args.exposure);
}

void fillSceneReport(const std::string& sceneFile, const Scene& scene, const RenderOptions& options,
                     RenderReport& report) {
    report.scene = sceneFile;
    report.options = options;
    report.triangles = scene.triangles.size();
    report.materials = scene.materials.size();
    report.lights = scene.lights.size();
    report.origin = {scene.origin.x, scene.origin.y, scene.origin.z};
}

// Loads, renders and writes one scene of the command line; `written` holds the images written by
// the scenes before it, so that two scenes never write the same file.
RenderReport renderScene(const RenderArgs& args, const std::string& sceneFile, const accel::AccelSpec& spec,
                         const std::map<std::string, std::string>& aovFiles, AccelFiles& accelFiles, Device& device,
                         bool showProgress, std::map<std::filesystem::path, std::string>& written) {
    const Clock::time_point t0 = Clock::now();
    ParseOptions parse;
    if (showProgress) parse.progress = printLoadProgress;
    Scene scene = loadScene(sceneFile, parse);
    if (showProgress) clearProgressLine();
    RenderReport report;
    report.loadMs = msSince(t0);
    checkRenderable(scene, sceneFile);
    scene.camera = viewCamera(scene, args.view);
    if (!args.background.empty()) scene.background = parseColour(args.background, "--background");
    const RenderOptions options = resolveOptions(args, scene);
    const Encoding encoding = outputEncoding(args, sceneFile);
    const std::filesystem::path out = outputPath(args, sceneFile, scene);
    if (!out.empty()) {
        checkColorImagePath(out);  // refuse a bad output before spending minutes on the render
        if (const auto it = written.find(out); it != written.end())
            throw Error(sceneFile + ": its image " + out.string() + " is also " + it->second +
                        "'s (give the scenes different 'output' names)");
        written[out] = sceneFile;
    }
    if (accelFiles.load) {  // and a structure file for another scene
        const Clock::time_point t1 = Clock::now();
        accelFiles.load->checkScene(scene);
        accelFiles.loadMs += msSince(t1);
    }
    // The device before the build: a missing or unknown device fails before a long build.
    const Clock::time_point opening = Clock::now();
    const gpu::VulkanContext* ctx = device.get();
    if (ctx) {
        report.deviceMs = msSince(opening);
        report.device = ctx->info().name + " (" + ctx->info().driver + ")";
        gpu::checkSceneFits(*ctx, scene);
    } else {
        report.device = args.buildOnly ? "none (--build-only)" : "CPU reference (double precision)";
    }
    report.accel = spec.name;
    fillSceneReport(sceneFile, scene, options, report);
    if (args.buildOnly) {  // the GPU's arrays, as --load-accel will read them
        prepareStructure(scene, options, spec, accelFiles, true, showProgress, report);
        report.buildOnly = true;
        report.totalMs = msSince(t0);
        return report;
    }

    const Frame frame = renderFrame(scene, options, spec, device.kernels(), accelFiles, showProgress, report);
    // Only an EXR keeps the metadata: the scene file and geometry are hashed for those alone.
    bool anyExr = !out.empty() && imageFormatForPath(out) == ImageFormat::Exr;
    for (const auto& [name, file] : aovFiles) anyExr = anyExr || imageFormatForPath(file) == ImageFormat::Exr;
    const ImageMeta meta = anyExr ? outputMeta(args, sceneFile, scene, options, report) : ImageMeta{};
    const Clock::time_point writing = Clock::now();
    if (!out.empty()) writeColorImage(out, frame.width, frame.height, frame.color, meta, encoding);
    for (const auto& [name, file] : aovFiles) writeAov(file, frame, name, meta);
    report.writeMs = msSince(writing);

    report.output = out.string();
    report.aovs = aovFiles;
    report.totalMs = msSince(t0);
    if (!args.pixel.empty()) {
        printPixel(frame, report);
        std::printf("its centre ray, traced by the CPU reference (double precision, brute force):\n");
        for (const std::string& line : tracePixel(scene, options, frame.x0, frame.y0))
            std::printf("  %s\n", line.c_str());
    }
    return report;
}

// What several scenes in one call cannot share: one output file, one set of AOV files, one structure file.
void checkSceneList(const RenderArgs& args) {
    if (args.scenes.size() < 2) return;
    const auto refuse = [&](const std::string& flag, const std::string& why) {
        throw Error(flag + " with " + std::to_string(args.scenes.size()) + " scenes: " + why);
    };
    if (!args.output.empty()) refuse("-o", "it names one image; give --out-dir DIR for one image a scene");
    if (!args.aovs.empty()) refuse("--aov", "it names one file per AOV; render the scenes one at a time");
    if (!args.saveAccel.empty() || !args.loadAccel.empty())
        refuse(args.saveAccel.empty() ? "--load-accel" : "--save-accel", "a structure file belongs to one scene");
}

void runRender(const RenderArgs& args) {
    checkSceneList(args);
    if (!args.outDir.empty() && !std::filesystem::is_directory(args.outDir))
        throw Error("--out-dir " + args.outDir + ": no such folder (create it first)");
    const auto aovFiles = parseAovs(args.aovs);
    const accel::AccelSpec spec = accel::resolveAccel(args.accel);
    // A wrong structure file fails here, in milliseconds, before a big scene loads.
    AccelFiles accelFiles = openAccelFiles(args, spec);
    const bool showProgress = !args.json && !args.quiet && isatty(STDERR_FILENO);
    Device device(args);
    std::map<std::filesystem::path, std::string> written;
    std::vector<std::string> jsons;
    for (const std::string& sceneFile : args.scenes) {
        const RenderReport report =
            renderScene(args, sceneFile, spec, aovFiles, accelFiles, device, showProgress, written);
        if (args.json) jsons.push_back(reportJson(report));
        else if (!args.quiet && args.pixel.empty()) printReport(report, args.stats);
    }
    if (!args.json) return;
    if (jsons.size() == 1) {
        std::printf("%s\n", jsons[0].c_str());
        return;
    }
    std::printf("[");  // several scenes: an array of their reports
    for (size_t i = 0; i < jsons.size(); ++i) std::printf("%s%s", i ? ",\n" : "\n", jsons[i].c_str());
    std::printf("\n]\n");
}

}  // namespace

void registerRenderCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<RenderArgs>();
    auto* cmd = app.add_subcommand("render", "Render scenes or meshes to images");
    cmd->footer("-o names the format by its extension (a scene's own `output` without one is a PNG, as in CSE167).\n"
                "Flags that override the scene say so; docs/outputs.md describes the outputs, README.md the rest.");
    cmd->add_option("scenes", args->scenes, "Scene files (.scene, CSE167 .test) or meshes (.obj, .off)")->required();
    CLI::Option* output = cmd->add_option("-o,--output", args->output,
                                          "Image: .png, .bmp (8-bit), .exr, .pfm (float); default SCENE.png")
                              ->type_name("FILE");
    CLI::Option* outDir =
        cmd->add_option("--out-dir", args->outDir, "Folder for the images of several scenes, each under its name")
            ->type_name("DIR")
            ->excludes(output);
    cmd->add_option("--size", args->size, "Image size, e.g. 640x480 (overrides the scene's)")->type_name("WxH");
    addViewOption(*cmd, args->view);
    cmd->add_option("--maxdepth", args->maxDepth, "Ray depth, primary rays count as 1 (overrides the scene's)")
        ->type_name("N");
    cmd->add_option("--spp", args->spp, "Camera rays per pixel, averaged (overrides the scene's; default 1)")
        ->type_name("N");
    cmd->add_option("--background", args->background, "Radiance of rays that hit nothing (overrides the scene's)")
        ->type_name("R,G,B");
    std::vector<CLI::Option*> windows = {
        addFourNumberOption(*cmd, "--crop", args->crop, "Render only this part, fractions in [0,1] (pbrt's crop window)"),
        addFourNumberOption(*cmd, "--pixel-bounds", args->pixelBounds, "Render only pixel columns [X0,X1), rows [Y0,Y1)"),
        cmd->add_option("--pixel", args->pixel, "Render one pixel, print its values and trace its centre ray")
            ->type_name("X,Y"),
        cmd->add_option("--tile", args->tile, "Render band I (from 0) of N bands of rows, for `vkray assemble`")
            ->type_name("I/N")};
    for (CLI::Option* a : windows)
        for (CLI::Option* b : windows)
            if (a != b) a->excludes(b);
    cmd->add_option("--encoding", args->encoding, "8-bit outputs: srgb, linear, or auto (linear for .test scenes)")
        ->check(CLI::IsMember({"auto", "srgb", "linear"}).description(""))  // the description names them
        ->type_name("E");
    cmd->add_option("--exposure", args->exposure, "8-bit outputs: multiply by 2^EV before encoding")->type_name("EV");
    addAccelOption(*cmd, args->accel,
                   "Structure[:OPTION=VALUE...], default " + args->accel + "; `--accel help` lists them");
    CLI::Option* cpu = cmd->add_flag("--cpu", args->cpu, "Render with the CPU reference renderer (double precision)");
    CLI::Option* device =
        cmd->add_option("--device", args->device, "Vulkan device: index or name substring (`vkray devices`)")
            ->type_name("N|NAME");
    CLI::Option* counters =
        cmd->add_flag("--counters", args->counters, "GPU: count nodes, leaves, triangle tests a ray (slower kernel)");
    // GPU-only flags with --cpu would be silently ignored: refused instead.
    cpu->excludes(counters);
    cpu->excludes(device);
    cmd->add_option("--threads", args->threads, "CPU threads for the build and --cpu (0 = all cores)")->type_name("N");
    CLI::Option* aov =
        cmd->add_option("--aov", args->aovs, "Write an AOV: depth, primid or normal, to a .pfm or .exr (repeatable)")
            ->type_name("NAME=FILE");
    CLI::Option* saveAccel =
        cmd->add_option("--save-accel", args->saveAccel, "Write the built structure to FILE, for --load-accel")
            ->type_name("FILE");
    CLI::Option* buildOnly =
        cmd->add_flag("--build-only", args->buildOnly, "With --save-accel: build and save the structure, render nothing");
    buildOnly->needs(saveAccel);
    for (CLI::Option* o : {output, outDir, aov, cpu, counters}) buildOnly->excludes(o);
    for (CLI::Option* o : windows) buildOnly->excludes(o);
    cmd->add_option("--load-accel", args->loadAccel, "Read the structure from FILE instead of building it (GPU)")
        ->type_name("FILE");
    CLI::Option* stats = cmd->add_flag("--stats", args->stats, "Print scene, structure, kernel and timing statistics");
    CLI::Option* json = cmd->add_flag("--json", args->json, "Print the report as JSON");
    cmd->add_flag("--quiet", args->quiet, "No progress line and no summary: errors and warnings only")
        ->excludes(json)
        ->excludes(stats);
    cmd->callback([args, &exitCode] {
        if (!args->tile.empty()) args->tileIndex = parseTile(args->tile);
        runRender(*args);
        exitCode = 0;
    });
}

}  // namespace vkray::cli
