// `vkray assemble TILES... -o IMAGE`: the image that EXR tiles (`vkray render --crop/--tile`) make up
// together, after checking that they belong together and cover it exactly once (image/assemble.h).
// docs/outputs.md, "Assembling tiles".
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "core/error.h"
#include "image/assemble.h"
#include "image/image_io.h"

namespace vkray::cli {
namespace {

struct AssembleArgs {
    std::vector<std::string> tiles;
    std::string output;
    std::string encoding = "srgb";
    double exposure = 0.0;
    bool quiet = false;
};

void run(const AssembleArgs& args) {
    checkExtensionGiven(args.output, "-o");
    checkColorImagePath(args.output);
    const Encoding encoding = parseEncoding(args.encoding, args.exposure);
    const std::vector<std::filesystem::path> paths(args.tiles.begin(), args.tiles.end());
    const AssembledImage out = assembleTileFiles(paths);  // every check before anything is written
    writeImage(args.output, out.image, out.meta, encoding);
    if (!args.quiet)
        std::cout << "wrote " << args.output << ": " << out.image.width << "x" << out.image.height << " from "
                  << paths.size() << (paths.size() == 1 ? " tile\n" : " tiles\n");
}

}  // namespace

void registerAssembleCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<AssembleArgs>();
    CLI::App* cmd = app.add_subcommand(
        "assemble", "Put an image together from EXR tiles (render --crop/--tile), refusing tiles that do not "
                    "belong together or do not cover it exactly once");
    cmd->add_option("TILES", args->tiles, "The EXR tiles")->required();
    cmd->add_option("-o,--output", args->output, "The image to write (.exr keeps the attributes; .png, .bmp, .pfm)")
        ->required();
    cmd->add_option("--encoding", args->encoding, "8-bit outputs: srgb or linear")->capture_default_str();
    cmd->add_option("--exposure", args->exposure, "8-bit outputs: multiply by 2^EV before encoding");
    cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
    cmd->callback([args, &exitCode] {
        run(*args);
        exitCode = 0;
    });
}

}  // namespace vkray::cli
