// `vkray render SCENE...`: the flags, turned into a render::RenderRequest for a render session
// (render/render_session.h: load, render on the GPU or the CPU reference with --cpu, write the image
// and the requested AOVs), and what the session reports, printed.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_spec.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "cli/render_printing.h"
#include "core/error.h"
#include "frame/frame.h"
#include "image/image_io.h"
#include "image/image_meta.h"
#include "render/render_request.h"
#include "render/render_session.h"
#include "scene/scene.h"

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

// The 8-bit encoding of --encoding and --exposure: auto is sRGB, but linear for CSE167 .test files,
// whose reference images hold linear levels.
Encoding outputEncoding(const RenderArgs& args, const std::string& sceneFile) {
    std::string name = args.encoding;
    if (name == "auto") name = std::filesystem::path(sceneFile).extension() == ".test" ? "linear" : "srgb";
    return parseEncoding(name, args.exposure);
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

render::RenderRequest makeRequest(const RenderArgs& args) {
    render::RenderRequest r;
    r.aovs = parseAovs(args.aovs);
    r.accel = accel::resolveAccel(args.accel);
    r.view = args.view;
    r.cpu = args.cpu;
    r.device = args.device;
    r.buildOnly = args.buildOnly;
    r.saveAccel = args.saveAccel;
    r.loadAccel = args.loadAccel;
    r.tile = args.tileIndex;
    r.tracePixel = !args.pixel.empty();
    r.settings = [&args](const std::string& sceneFile, const Scene& scene) {
        render::SceneSettings s;
        if (!args.background.empty()) s.background = parseColour(args.background, "--background");
        s.options = resolveOptions(args, scene);
        s.encoding = outputEncoding(args, sceneFile);
        s.output = outputPath(args, sceneFile, scene);
        return s;
    };
    if (!args.json && !args.quiet && isatty(STDERR_FILENO)) r.progress = progressLine();
    r.warn = [](const std::string& message) { std::fprintf(stderr, "warning: %s\n", message.c_str()); };
    return r;
}

void runRender(const RenderArgs& args) {
    checkSceneList(args);
    if (!args.outDir.empty() && !std::filesystem::is_directory(args.outDir))
        throw Error("--out-dir " + args.outDir + ": no such folder (create it first)");
    // A wrong structure file fails here, in milliseconds, before a big scene loads.
    render::RenderSession session(makeRequest(args));
    std::vector<std::string> jsons;
    for (const std::string& sceneFile : args.scenes) {
        const render::SceneRender r = session.render(sceneFile);
        if (!args.pixel.empty()) {
            printPixel(r.frame, r.report);
            std::printf("its centre ray, traced by the CPU reference (double precision, brute force):\n");
            for (const std::string& line : r.centreRay) std::printf("  %s\n", line.c_str());
        }
        if (args.json) jsons.push_back(reportJson(r.report));
        else if (!args.quiet && args.pixel.empty()) printReport(r.report, args.stats);
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
