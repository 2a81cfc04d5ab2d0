// `vkray compare A B`: difference metrics between two images (PNG, BMP, PFM or EXR; see
// image/compare.h for the metrics and their inf/NaN rules). Two 8-bit files are compared as stored
// (levels / 255), two float files as their raw values, an 8-bit file with a float one in linear
// radiance, the 8-bit one decoded with --encoding/--exposure (toCommonSpace). Exit code 1 when a
// limit given with --max-rmse or --max-bad-fraction is exceeded, so scripts and CI can gate on it.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "image/compare.h"
#include "image/image_io.h"

namespace vkray::cli {
namespace {

struct CompareArgs {
    std::string a, b;
    std::string threshold = "2/255";  // two 8-bit levels: GPU float vs CPU double rounding may move
                                      // a channel by one level; more than two is a real difference
    double maxRmse = 0.0, maxBadFraction = 0.0;
    std::string diff;
    std::string encoding = "srgb";  // of an 8-bit file compared with a float one
    double exposure = 0.0;
    bool json = false;
    bool quiet = false;  // no output: the exit status alone
};

// "0.01" or a fraction "2/255" (8-bit levels are the natural unit for PNG).
double parseThreshold(const std::string& text) {
    auto number = [&](std::string_view s) {
        double v = 0.0;
        const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
        if (s.empty() || ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v))
            throw Error("--threshold: '" + text + "' is not a number or a fraction like 2/255");
        return v;
    };
    const std::string_view s = text;
    const size_t slash = s.find('/');
    const double v = slash == std::string_view::npos ? number(s) : number(s.substr(0, slash)) / number(s.substr(slash + 1));
    if (!(v >= 0.0) || !std::isfinite(v)) throw Error("--threshold: '" + text + "' must be a finite number >= 0");
    return v;
}

std::string fmt(double v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

nlohmann::json finiteOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

// What a comparison found, for printing.
struct Outcome {
    int width = 0, height = 0, channels = 0;
    CompareSpace space;
    CompareStats stats;
    double threshold = 0.0;
    bool hasMaxRmse = false, hasMaxBad = false;
    std::vector<std::string> failures;  // the limits exceeded; empty: pass
};

std::vector<std::string> failuresOf(const CompareArgs& args, const Outcome& o) {
    const CompareStats& s = o.stats;
    std::vector<std::string> failures;
    if (o.hasMaxRmse) {
        // A non-finite mismatch is left out of the RMSE (compare.h) but means an infinite error:
        // it must not pass an RMSE gate silently.
        if (s.nonFiniteMismatches > 0)
            failures.push_back("--max-rmse " + fmt(args.maxRmse) + ": " + std::to_string(s.nonFiniteMismatches) +
                               " channel value(s) inf or NaN in only one image (an infinite error)");
        if (s.rmse > args.maxRmse)
            failures.push_back("RMSE " + fmt(s.rmse) + " > --max-rmse " + fmt(args.maxRmse));
    }
    if (o.hasMaxBad && s.badFraction > args.maxBadFraction)
        failures.push_back("bad fraction " + fmt(s.badFraction) + " > --max-bad-fraction " + fmt(args.maxBadFraction));
    return failures;
}

void printJson(const CompareArgs& args, const Outcome& o) {
    const CompareStats& s = o.stats;
    nlohmann::json j;
    j["a"] = args.a;
    j["b"] = args.b;
    j["width"] = o.width;
    j["height"] = o.height;
    j["channels"] = o.channels;
    j["space"] = o.space.linear ? "linear" : "levels";
    j["compared_in"] = o.space.description;
    j["eight_bit_encoding"] = o.space.decoded ? nlohmann::json(args.encoding) : nlohmann::json(nullptr);
    j["rmse"] = s.rmse;
    j["psnr"] = finiteOrNull(s.psnr);           // null: infinite (identical images)
    j["max_error"] = finiteOrNull(s.maxError);  // null: infinite (a non-finite mismatch)
    j["max_error_at"] = s.maxErrorX >= 0 ? nlohmann::json{s.maxErrorX, s.maxErrorY} : nlohmann::json(nullptr);
    j["threshold"] = o.threshold;
    j["bad_pixels"] = s.badPixels;
    j["pixels"] = s.pixels;
    j["bad_fraction"] = s.badFraction;
    j["non_finite_mismatches"] = s.nonFiniteMismatches;
    j["diff"] = args.diff.empty() ? nlohmann::json(nullptr) : nlohmann::json(args.diff);
    j["max_rmse"] = o.hasMaxRmse ? nlohmann::json(args.maxRmse) : nlohmann::json(nullptr);
    j["max_bad_fraction"] = o.hasMaxBad ? nlohmann::json(args.maxBadFraction) : nlohmann::json(nullptr);
    j["failures"] = o.failures;
    j["pass"] = o.failures.empty();
    std::cout << j.dump(2) << '\n';
}

void printText(const CompareArgs& args, const Outcome& o) {
    const CompareStats& s = o.stats;
    std::cout << "compare " << args.a << " " << args.b << ": " << o.width << "x" << o.height << ", " << o.channels
              << (o.channels == 1 ? " channel\n" : " channels\n");
    std::cout << "  compared in " << o.space.description << "\n";
    std::cout << "  RMSE        " << fmt(s.rmse) << "\n";
    std::cout << "  PSNR        " << fmt(s.psnr) << " dB\n";
    std::cout << "  max error   " << fmt(s.maxError);
    if (s.maxErrorX >= 0) std::cout << " at pixel (" << s.maxErrorX << ", " << s.maxErrorY << ")";
    std::cout << "\n";
    std::cout << "  bad pixels  " << s.badPixels << " of " << s.pixels << " (" << fmt(100.0 * s.badFraction)
              << " %) differ by more than " << fmt(o.threshold) << " (" << args.threshold << ") in a channel\n";
    if (s.nonFiniteMismatches > 0)
        std::cout << "  non-finite  " << s.nonFiniteMismatches
                  << " channel value(s) inf or NaN in only one image: bad pixels, left out of the RMSE\n";
    if (!args.diff.empty()) std::cout << "  diff image  written to " << args.diff << "\n";
    if (!o.hasMaxRmse && !o.hasMaxBad)
        std::cout << "  result      no limits given (--max-rmse, --max-bad-fraction)\n";
    else if (o.failures.empty())
        std::cout << "  result      pass\n";
    for (const std::string& f : o.failures) std::cout << "  result      FAIL: " << f << "\n";
}

void run(const CompareArgs& args, bool hasMaxRmse, bool hasMaxBad, int& exitCode) {
    Outcome o;
    o.threshold = parseThreshold(args.threshold);
    o.hasMaxRmse = hasMaxRmse;
    o.hasMaxBad = hasMaxBad;
    const Encoding eightBit = parseEncoding(args.encoding, args.exposure);
    const ImageFormat formatA = readImageFormat(args.a), formatB = readImageFormat(args.b);
    Image a = readImage(args.a);
    Image b = readImage(args.b);
    o.space = toCommonSpace(a, formatA, b, formatB, eightBit);
    try {
        o.stats = compareImages(a, b, o.threshold);
    } catch (const Error& e) {
        throw Error("cannot compare " + args.a + " with " + args.b + ": " + e.what());
    }
    o.width = a.width;
    o.height = a.height;
    o.channels = a.channels;
    // The difference image's colours are display values: stored as they are, not sRGB-encoded.
    if (!args.diff.empty()) writeImage(args.diff, makeDiffImage(a, b, o.threshold), {}, Encoding::linear());
    o.failures = failuresOf(args, o);
    exitCode = o.failures.empty() ? 0 : 1;
    if (args.quiet) return;
    if (args.json)
        printJson(args, o);
    else
        printText(args, o);
    std::cout.flush();
}

}  // namespace

void registerCompareCommand(CLI::App& app, int& exitCode) {
    auto args = std::make_shared<CompareArgs>();
    CLI::App* cmd = app.add_subcommand(
        "compare", "Image difference metrics (RMSE, PSNR, max error, pixels over a threshold) of two PNG/BMP/PFM/EXR "
                   "files; exits 1 when over --max-rmse or --max-bad-fraction");
    cmd->add_option("A", args->a, "First image (the reference)")->required();
    cmd->add_option("B", args->b, "Second image")->required();
    cmd->add_option("--threshold", args->threshold,
                    "A pixel is bad when a channel differs by more than this (a number or a fraction like 2/255)")
        ->capture_default_str();
    CLI::Option* maxRmse = cmd->add_option("--max-rmse", args->maxRmse, "Fail (exit 1) when the RMSE is larger")
                               ->check(CLI::NonNegativeNumber);
    CLI::Option* maxBad =
        cmd->add_option("--max-bad-fraction", args->maxBadFraction,
                        "Fail (exit 1) when a larger fraction of the pixels is bad")
            ->check(CLI::Range(0.0, 1.0));
    cmd->add_option("--encoding", args->encoding,
                    "How an 8-bit file (PNG, BMP) compared with a float one (PFM, EXR) was encoded: srgb or linear; "
                    "it is decoded to linear radiance (two 8-bit files are compared as stored)")
        ->capture_default_str();
    cmd->add_option("--exposure", args->exposure, "The exposure (EV) that 8-bit file was written with");
    cmd->add_option("--diff", args->diff, "Write a difference image here (PNG, BMP, PFM or EXR by extension)");
    CLI::Option* json = cmd->add_flag("--json", args->json, "Print the figures as JSON");
    cmd->add_flag("--quiet", args->quiet, "Print nothing: the exit status alone says pass (0) or fail (1)")
        ->excludes(json);
    cmd->callback([args, maxRmse, maxBad, &exitCode] {
        run(*args, maxRmse->count() > 0, maxBad->count() > 0, exitCode);
    });
}

}  // namespace vkray::cli
