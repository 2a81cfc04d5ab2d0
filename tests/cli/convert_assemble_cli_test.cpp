// `vkray convert`, `vkray assemble` and the --quiet of `compare` and `gen`, through their CLI11
// registrations as main() wires them: files written, what they hold, what is printed, and errors.
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cli/commands.h"
#include "core/error.h"
#include "image/image_io.h"
#include "run_cli.h"

namespace fs = std::filesystem;
using namespace vkray;

namespace {

fs::path out(const std::string& name) { return fs::path(VKRAY_TEST_OUTPUT_DIR) / ("convert_cli_" + name); }

using Result = test::CliResult;
using test::runVkray;

std::string errorOf(const std::vector<std::string>& args) {
    try {
        runVkray(args);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

int level(const Image& im, int x, int y, int c) { return int(std::lround(im.at(x, y, c) * 255.0f)); }

#define EXPECT_HAS(s, part) EXPECT_NE((s).find(part), std::string::npos) << (s)

}  // namespace

TEST(ConvertCli, ExrToSrgbPngAndBackToFloat) {
    const std::vector<glm::vec3> rgb = {{0.5f, 0.18f, 4.0f}, {0.25f, 0.0f, 1.0f}};
    writeColorImage(out("r.exr"), 2, 1, rgb);
    const Result r = runVkray({"convert", out("r.exr").string(), out("r.png").string()});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_HAS(r.stdoutText, "encoding srgb, exposure 0");
    const Image png = readImage(out("r.png"));
    EXPECT_EQ(level(png, 0, 0, 0), 188);
    EXPECT_EQ(level(png, 0, 0, 1), 118);
    EXPECT_EQ(level(png, 0, 0, 2), 255);
    runVkray({"convert", out("r.exr").string(), out("lin.png").string(), "--encoding", "linear", "--exposure", "-1"});
    EXPECT_EQ(level(readImage(out("lin.png")), 0, 0, 0), 64);  // 0.25
    EXPECT_EQ(level(readImage(out("lin.png")), 0, 0, 2), 255);
    runVkray({"convert", out("r.exr").string(), out("r.pfm").string(), "--quiet"});
    EXPECT_EQ(readImage(out("r.pfm")).data, readImage(out("r.exr")).data);  // floats untouched
    // An 8-bit input's levels are copied unchanged by default.
    runVkray({"convert", out("r.png").string(), out("r.bmp").string()});
    EXPECT_EQ(readImage(out("r.bmp")).data, png.data);
    // To a float file the levels are decoded (sRGB unless told otherwise): the linear values back,
    // within a level, and clamped as the PNG holds them.
    const Result back = runVkray({"convert", out("r.png").string(), out("back.exr").string()});
    EXPECT_HAS(back.stdoutText, "decoded as srgb, exposure 0");
    const Image exr = readImage(out("back.exr"));
    EXPECT_NEAR(exr.at(0, 0, 0), 0.5f, 0.003f);
    EXPECT_NEAR(exr.at(0, 0, 1), 0.18f, 0.002f);
    EXPECT_EQ(exr.at(0, 0, 2), 1.0f);
    runVkray({"convert", out("lin.png").string(), out("lin.pfm").string(), "--encoding", "linear", "--exposure", "-1"});
    EXPECT_FLOAT_EQ(readImage(out("lin.pfm")).at(0, 0, 0), 2.0f * 64.0f / 255.0f);  // level 64, times 2
}

TEST(ConvertCli, DepthAovNormalizedForViewing) {
    Frame f;
    f.resize(3, 1);
    f.depth = {2.0f, std::numeric_limits<float>::infinity(), 6.0f};
    writeAov(out("depth.pfm"), f, "depth");
    runVkray({"convert", out("depth.pfm").string(), out("depth.exr").string()});
    EXPECT_EQ(readImage(out("depth.exr")).at(1, 0), std::numeric_limits<float>::infinity());
    runVkray({"convert", out("depth.exr").string(), out("depth.png").string(), "--normalize", "--encoding", "linear"});
    const Image png = readImage(out("depth.png"));
    EXPECT_EQ(level(png, 0, 0, 0), 0);    // nearest
    EXPECT_EQ(level(png, 1, 0, 0), 0);    // a miss: black
    EXPECT_EQ(level(png, 2, 0, 0), 255);  // farthest
    runVkray({"convert", out("depth.exr").string(), out("depth-clamped.png").string(), "--encoding", "linear"});
    EXPECT_EQ(level(readImage(out("depth-clamped.png")), 1, 0, 0), 255);  // without --normalize: clamped
}

TEST(ConvertCli, Errors) {
    writeColorImage(out("e.exr"), 1, 1, {glm::vec3(0.5f)});
    EXPECT_HAS(errorOf({"convert", out("e.exr").string(), out("e.jpg").string()}), "supported: .png, .bmp, .pfm, .exr");
    EXPECT_HAS(errorOf({"convert", out("none.exr").string(), out("e.png").string()}), "none.exr: cannot open");
    EXPECT_HAS(errorOf({"convert", out("e.exr").string(), out("e.png").string(), "--encoding", "log"}),
               "--encoding 'log'");
    EXPECT_HAS(errorOf({"convert", out("e.exr").string(), out("e.png").string(), "--exposure", "99"}), "--exposure 99");
}

TEST(AssembleCli, TilesToExrAndPng) {
    const int w = 4, h = 2;
    std::vector<glm::vec3> whole(size_t(w * h));
    for (size_t k = 0; k < whole.size(); ++k) whole[k] = glm::vec3(float(k) * 0.1f, 0.5f, float(k));
    std::vector<std::string> tiles;
    for (int i = 0; i < 2; ++i) {  // two 2x2 halves, left and right
        std::vector<glm::vec3> half;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < 2; ++x) half.push_back(whole[size_t(y * w + 2 * i + x)]);
        ImageMeta m{w, h, 2 * i, 0, {{"vkray:version", "0.1.0"}, {"vkray:tile", std::to_string(i) + "/2"}}};
        tiles.push_back(out("tile" + std::to_string(i) + ".exr").string());
        writeColorImage(tiles.back(), 2, 2, half, m);
    }
    std::vector<std::string> args = {"assemble", tiles[1], tiles[0], "-o", out("whole.exr").string()};
    const Result r = runVkray(args);
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_HAS(r.stdoutText, "4x2 from 2 tiles");
    ImageMeta meta;
    const Image im = readImage(out("whole.exr"), &meta);
    for (int k = 0; k < w * h; ++k) EXPECT_EQ(im.at(k % w, k / w, 2), float(k));
    EXPECT_EQ(meta.attributes, (std::map<std::string, std::string>{{"vkray:version", "0.1.0"}}));
    args[4] = out("whole.png").string();
    args.push_back("--quiet");
    EXPECT_EQ(runVkray(args).stdoutText, "");
    EXPECT_EQ(level(readImage(out("whole.png")), 0, 0, 1), 188);  // 0.5, sRGB

    fs::remove(out("partial.exr"));
    EXPECT_HAS(errorOf({"assemble", tiles[0], "-o", out("partial.exr").string()}), "missing tile 1 of 2");
    EXPECT_FALSE(fs::exists(out("partial.exr")));  // nothing written
}

TEST(QuietCli, CompareAndGenPrintNothing) {
    writeColorImage(out("qa.png"), 2, 2, std::vector<glm::vec3>(4, glm::vec3(0.2f)));
    writeColorImage(out("qb.png"), 2, 2, std::vector<glm::vec3>(4, glm::vec3(0.8f)));
    const Result fail = runVkray({"compare", out("qa.png").string(), out("qb.png").string(), "--quiet",
                                  "--max-rmse", "0.01"});
    EXPECT_EQ(fail.exitCode, 1);
    EXPECT_EQ(fail.stdoutText, "");
    const Result pass = runVkray({"compare", out("qa.png").string(), out("qa.png").string(), "--quiet",
                                  "--max-rmse", "0"});
    EXPECT_EQ(pass.exitCode, 0);
    EXPECT_EQ(pass.stdoutText, "");
    EXPECT_THROW(runVkray({"compare", out("qa.png").string(), out("qa.png").string(), "--quiet", "--json"}),
                 CLI::ParseError);
    const Result gen = runVkray({"gen", "soup", "--triangles", "10", "--force", "--quiet", "-o",
                                 out("g.scene").string()});
    EXPECT_EQ(gen.exitCode, 0);
    EXPECT_EQ(gen.stdoutText, "");
    EXPECT_TRUE(fs::exists(out("g.scene")));
}
