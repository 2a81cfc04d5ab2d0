// `vkray gen KIND --triangles N [--seed S] -o FILE.scene`: writes a small, complete .scene (size,
// camera, lights, a floor, materials) whose `generate` line makes the procedural mesh on load
// (scene/generators.h). The scaling scenes of scenes/scaling/ are made by it.
#include <cstdint>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "core/file_output.h"
#include "scene/generators.h"

namespace vkray::cli {
namespace {

struct GenArgs {
    std::string kind;
    int64_t triangles = 0;
    int64_t seed = 1;
    std::string output;
    bool force = false;
    bool quiet = false;
};

// What each kind is made of, for the file's comment, and the material it gets: chosen so the
// render shows the structure (soft colours, a highlight) without needing deep ray trees.
struct KindLook {
    const char* description;
    const char* material;
};

KindLook lookOf(GeneratorKind kind) {
    switch (kind) {
        case GeneratorKind::Spheres:
            return {"A grid of tessellated spheres of random radius and height",
                    "ambient 0.05 0.04 0.04\ndiffuse 0.75 0.35 0.2\nspecular 0.4 0.4 0.4\nshininess 60\n"
                    "reflect 0.2 0.2 0.2\n"};
        case GeneratorKind::Soup:
            return {"A soup of random, overlapping triangles",
                    "ambient 0.04 0.05 0.06\ndiffuse 0.3 0.5 0.75\nspecular 0.3 0.3 0.3\nshininess 40\n"
                    "reflect 0 0 0\n"};
        case GeneratorKind::Terrain:
            return {"A fractal terrain (diamond-square midpoint displacement)",
                    "ambient 0.04 0.05 0.03\ndiffuse 0.45 0.55 0.3\nspecular 0 0 0\n"};
        case GeneratorKind::Burst:
            return {"Random triangles that all share one centroid (every Morton code equal): a stress case",
                    "ambient 0.05 0.05 0.05\ndiffuse 0.6 0.6 0.65\nspecular 0.2 0.2 0.2\nshininess 30\n"};
    }
    return {"", ""};
}

std::string sceneText(const GeneratorSpec& spec, const std::string& command, const std::string& imageName) {
    const KindLook look = lookOf(spec.kind);
    const int64_t count = generatedTriangleCount(spec);
    std::ostringstream s;
    s << "# Made by: " << command << "\n"
      << "# " << look.description << ":\n"
      << "# " << count << " triangles (" << spec.triangles << " asked for, rounded up to the kind's structure)"
      << " and a floor of 2.\n"
      << "# The `generate` line at the end makes the mesh when the scene loads (same seed, same triangles\n"
      << "# on every machine); it stands in x, z -1..1, y 0..1.\n\n"
      << "size 640 480\n"
      << "output " << imageName << "\n"
      << "maxdepth 3\n"
      << "camera 0 1.7 3.2  0 0.25 0  0 1 0  40\n\n"
      << "directional 0.4 1 0.7  0.5 0.5 0.48\n"
      << "attenuation 1 0.05 0.02\n"
      << "point -2.5 3 2.5  0.5 0.5 0.55\n\n"
      << "# Floor: y = -0.002, a hair below the mesh's lowest points so the two never coincide.\n"
      << "vertex -4 -0.002 -4\nvertex 4 -0.002 -4\nvertex 4 -0.002 4\nvertex -4 -0.002 4\n"
      << "ambient 0.05 0.05 0.05\ndiffuse 0.6 0.6 0.6\nspecular 0 0 0\n"
      << "tri 0 3 2\ntri 0 2 1\n\n"
      << look.material
      << "generate " << generatorName(spec.kind) << " " << spec.triangles << " " << spec.seed << "\n";
    return s.str();
}

void run(const GenArgs& args, int& exitCode) {
    const std::optional<GeneratorKind> kind = generatorKindFromName(args.kind);
    if (!kind) throw Error("gen: unknown kind '" + args.kind + "' (expected one of: " + generatorNames() + ")");
    if (args.triangles < 1 || args.triangles > kMaxGeneratedTriangles)
        throw Error("gen: --triangles " + std::to_string(args.triangles) + " is outside 1.." +
                    std::to_string(kMaxGeneratedTriangles));
    if (args.seed < 0) throw Error("gen: --seed " + std::to_string(args.seed) + " is negative");
    const std::filesystem::path out(args.output);
    if (out.extension() != ".scene") throw Error("gen: -o " + args.output + ": the output must be a .scene file");
    // A scene file may be someone's work: never replaced unless asked.
    if (!args.force && std::filesystem::exists(out))
        throw Error("gen: -o " + args.output + ": the file exists (--force replaces it)");

    const GeneratorSpec spec{*kind, args.triangles, uint64_t(args.seed)};
    const std::string command = "vkray gen " + args.kind + " --triangles " + std::to_string(args.triangles) +
                                " --seed " + std::to_string(args.seed) + " -o " + out.filename().string();
    const std::string text = sceneText(spec, command, out.stem().string() + ".png");
    writeFileText(out, text);
    if (!args.quiet)
        std::cout << "wrote " << args.output << ": " << args.kind << ", " << generatedTriangleCount(spec)
                  << " triangles + 2 floor, seed " << args.seed << "\n";
    exitCode = 0;
}

}  // namespace

void registerGenCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<GenArgs>();
    CLI::App* cmd = app.add_subcommand(
        "gen", "Write a .scene with a procedural mesh (" + generatorNames() + ") for scaling measurements");
    cmd->add_option("kind", args->kind, "What to generate: " + generatorNames())->required();
    cmd->add_option("--triangles", args->triangles, "Triangle count (rounded up to the kind's structure)")
        ->required();
    cmd->add_option("--seed", args->seed, "Random seed (the same seed makes the same triangles)")
        ->capture_default_str();
    cmd->add_option("-o,--output", args->output, "The .scene file to write")->required();
    cmd->add_flag("--force", args->force, "Replace the .scene file if it exists");
    cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
    cmd->callback([args, &exitCode] { run(*args, exitCode); });
}

}  // namespace vkray::cli
