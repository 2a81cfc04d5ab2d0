// `vkray convert IN OUT`: any image vkray reads (PNG, BMP, PFM, EXR) to any it writes, e.g. an EXR
// render to an sRGB PNG for viewing, or a PFM AOV to EXR; an 8-bit image to a float one is decoded to
// linear values. docs/outputs.md, "Converting images".
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "core/error.h"
#include "image/image_io.h"
#include "image/tone.h"

namespace vkray::cli {
namespace {

struct ConvertArgs {
    std::string input, output;
    std::string encoding = "srgb";
    double exposure = 0.0;
    bool normalize = false;
    bool quiet = false;
};

void run(const ConvertArgs& args, bool encodingGiven) {
    checkExtensionGiven(args.output, "OUT");
    checkColorImagePath(args.output);  // a bad name is refused before anything is read
    const ImageFormat inFormat = readImageFormat(args.input);
    const bool eightIn = isEightBit(inFormat), eightOut = isEightBit(imageFormatForPath(args.output));
    // 8-bit to 8-bit: the input holds encoded levels already, by default copied as they are.
    const std::string name = encodingGiven || !(eightIn && eightOut) ? args.encoding : "linear";
    const Encoding encoding = parseEncoding(name, args.exposure);
    ImageMeta meta;
    Image image = readImage(args.input, &meta);
    // 8-bit to float: the levels decoded to the linear values they encode (the file does not say how).
    const bool decode = eightIn && !eightOut;
    if (decode) image = decodeLevels(image, encoding);
    if (args.normalize) image = normalizedForViewing(image);
    writeImage(args.output, image, meta, encoding);
    if (args.quiet) return;
    std::cout << "wrote " << args.output << ": " << image.width << "x" << image.height << ", " << image.channels
              << (image.channels == 1 ? " channel" : " channels") << " from " << args.input;
    if (decode)
        std::cout << " (decoded as " << name << ", exposure " << args.exposure << (args.normalize ? ", normalized" : "")
                  << ")";
    else if (eightOut)
        std::cout << " (encoding " << name << ", exposure " << args.exposure << (args.normalize ? ", normalized" : "")
                  << ")";
    else if (args.normalize)
        std::cout << " (normalized)";
    std::cout << "\n";
}

}  // namespace

void registerConvertCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<ConvertArgs>();
    CLI::App* cmd = app.add_subcommand(
        "convert", "Convert an image (PNG, BMP, PFM, EXR) to another format, e.g. an EXR render to an sRGB PNG");
    cmd->add_option("IN", args->input, "The image to read (PNG, BMP, PFM or EXR, recognised by its content)")
        ->required();
    cmd->add_option("OUT", args->output, "The image to write (.png, .bmp, .pfm or .exr)")->required();
    CLI::Option* encoding = cmd->add_option("--encoding", args->encoding,
                                            "The 8-bit side's encoding, srgb or linear (default: srgb): how an 8-bit OUT "
                                            "is encoded, or how an 8-bit IN is decoded to a float OUT; from 8-bit to "
                                            "8-bit the levels are copied as they are unless it is given");
    cmd->add_option("--exposure", args->exposure,
                    "With --encoding: multiply by 2^EV before encoding (divide after decoding)");
    cmd->add_flag("--normalize", args->normalize,
                  "Map the finite values linearly to [0, 1] (lowest to highest, over all channels) and inf/NaN to 0: "
                  "for viewing a depth or primid AOV");
    cmd->add_flag("--quiet", args->quiet, "Print nothing but errors");
    cmd->callback([args, encoding, &exitCode] {
        run(*args, encoding->count() > 0);
        exitCode = 0;
    });
}

}  // namespace vkray::cli
