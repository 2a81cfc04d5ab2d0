// `vkray compare` through its CLI11 registration, as main() wires it: exit codes for the limits,
// the printed block and JSON, the diff image, the space an 8-bit and a float file are compared in, and
// errors for missing files and bad thresholds.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "image/image_io.h"
#include "run_cli.h"

namespace fs = std::filesystem;
using namespace vkray;

namespace {

fs::path out(const std::string& name) { return fs::path(VKRAY_TEST_OUTPUT_DIR) / ("compare_cli_" + name); }

using Result = test::CliResult;

Result runCompare(std::vector<std::string> args) {
    args.insert(args.begin(), "compare");
    return test::runVkray(std::move(args));
}

// Two 10x10 images: b differs from a by 10 levels (> 2/255) in the red channel of 3 pixels, and by
// one level (tolerated) in one more.
void writePair(const fs::path& a, const fs::path& b) {
    std::vector<glm::vec3> pa(100, glm::vec3(100.0f / 255.0f)), pb = pa;
    for (int k = 0; k < 3; ++k) pb[size_t(k)].r = 110.0f / 255.0f;
    pb[50].g = 101.0f / 255.0f;
    writeColorImage(a, 10, 10, pa, {}, Encoding::linear());  // levels stored as given
    writeColorImage(b, 10, 10, pb, {}, Encoding::linear());
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(CompareCli, PrintsMetricsAndPassesWithoutLimits) {
    writePair(out("a.png"), out("b.png"));
    const Result r = runCompare({out("a.png").string(), out("b.png").string()});
    EXPECT_EQ(r.exitCode, 0);
    EXPECT_TRUE(contains(r.stdoutText, "RMSE")) << r.stdoutText;
    EXPECT_TRUE(contains(r.stdoutText, "PSNR")) << r.stdoutText;
    EXPECT_TRUE(contains(r.stdoutText, "3 of 100 (3 %)")) << r.stdoutText;
    EXPECT_TRUE(contains(r.stdoutText, "at pixel (0, 0)")) << r.stdoutText;
    EXPECT_TRUE(contains(r.stdoutText, "no limits given")) << r.stdoutText;
}

TEST(CompareCli, LimitsSetTheExitCode) {
    writePair(out("la.png"), out("lb.png"));
    const std::string a = out("la.png").string(), b = out("lb.png").string();
    // RMSE = sqrt((3 * 100 + 1) / 300) / 255 ~ 0.0039.
    EXPECT_EQ(runCompare({a, b, "--max-rmse", "0.01", "--max-bad-fraction", "0.03"}).exitCode, 0);
    const Result rmse = runCompare({a, b, "--max-rmse", "0.001"});
    EXPECT_EQ(rmse.exitCode, 1);
    EXPECT_TRUE(contains(rmse.stdoutText, "FAIL: RMSE")) << rmse.stdoutText;
    EXPECT_TRUE(contains(rmse.stdoutText, "--max-rmse 0.001")) << rmse.stdoutText;
    const Result bad = runCompare({a, b, "--max-bad-fraction", "0.02"});
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_TRUE(contains(bad.stdoutText, "--max-bad-fraction 0.02")) << bad.stdoutText;
    EXPECT_FALSE(contains(bad.stdoutText, "FAIL: RMSE")) << bad.stdoutText;
    // A looser threshold makes every pixel tolerated.
    EXPECT_EQ(runCompare({a, b, "--threshold", "10/255", "--max-bad-fraction", "0"}).exitCode, 0);
    EXPECT_EQ(runCompare({a, b, "--threshold", "0.04", "--max-bad-fraction", "0"}).exitCode, 0);
    EXPECT_EQ(runCompare({a, b, "--threshold", "9/255", "--max-bad-fraction", "0"}).exitCode, 1);
}

TEST(CompareCli, JsonAndDiffImage) {
    writePair(out("ja.png"), out("jb.png"));
    const fs::path diff = out("diff.png");
    fs::remove(diff);
    const Result r = runCompare(
        {out("ja.png").string(), out("jb.png").string(), "--json", "--diff", diff.string(), "--max-rmse", "0.001"});
    EXPECT_EQ(r.exitCode, 1);
    const auto j = nlohmann::json::parse(r.stdoutText);
    EXPECT_EQ(j["bad_pixels"], 3);
    EXPECT_EQ(j["pixels"], 100);
    EXPECT_NEAR(j["bad_fraction"].get<double>(), 0.03, 1e-12);
    EXPECT_NEAR(j["max_error"].get<double>(), 10.0 / 255.0, 1e-6);
    EXPECT_NEAR(j["threshold"].get<double>(), 2.0 / 255.0, 1e-12);
    EXPECT_FALSE(j["pass"].get<bool>());
    EXPECT_EQ(j["failures"].size(), 1u);
    EXPECT_EQ(j["diff"], diff.string());
    const Image d = readImage(diff);
    EXPECT_EQ(d.width, 10);
    EXPECT_EQ(d.at(0, 0, 0), 1.0f);  // bad pixel: red/yellow
    EXPECT_EQ(d.at(0, 5, 0), 0.0f);  // pixel 50, tolerated: blue
    EXPECT_GT(d.at(0, 5, 2), 0.0f);

    const Result same = runCompare({out("ja.png").string(), out("ja.png").string(), "--json"});
    const auto js = nlohmann::json::parse(same.stdoutText);
    EXPECT_TRUE(js["psnr"].is_null());  // infinite
    EXPECT_EQ(js["rmse"], 0.0);
    EXPECT_TRUE(js["pass"].get<bool>());
}

// A render written as an sRGB PNG and as an EXR: compared in linear radiance, the PNG decoded, they
// agree within the PNG's quantisation (a level near white spans 0.009 in linear units).
TEST(CompareCli, SrgbPngAgainstItsExr) {
    std::vector<glm::vec3> render(64 * 4);
    for (size_t i = 0; i < render.size(); ++i)
        render[i] = glm::vec3(float(i) / 255.0f, float(i % 64) / 48.0f, 0.18f);  // up to 1.33: a highlight
    writeColorImage(out("render.exr"), 64, 4, render);
    writeColorImage(out("render.png"), 64, 4, render);  // sRGB, the default
    const std::string png = out("render.png").string(), exr = out("render.exr").string();
    const Result r = runCompare({png, exr, "--max-bad-fraction", "0"});
    EXPECT_EQ(r.exitCode, 0) << r.stdoutText;
    EXPECT_TRUE(contains(r.stdoutText,
                         "compared in linear radiance (A: sRGB PNG decoded; B: EXR clamped to [0, 1] as 8 bits hold it)"))
        << r.stdoutText;
    const auto j = nlohmann::json::parse(runCompare({exr, png, "--json"}).stdoutText);
    EXPECT_EQ(j["space"], "linear");
    EXPECT_EQ(j["eight_bit_encoding"], "srgb");
    EXPECT_EQ(j["compared_in"], "linear radiance (A: EXR clamped to [0, 1] as 8 bits hold it; B: sRGB PNG decoded)");
    EXPECT_LT(j["max_error"].get<double>(), 0.0045);

    // The same PNG taken for a linear one fails, and says what it assumed.
    const Result wrong = runCompare({png, exr, "--encoding", "linear", "--max-bad-fraction", "0"});
    EXPECT_EQ(wrong.exitCode, 1);
    EXPECT_TRUE(contains(wrong.stdoutText, "A: linear PNG decoded")) << wrong.stdoutText;
    // A PNG written linear at exposure -1 (the file does not say so) with the flags that wrote it.
    writeColorImage(out("render-lin.png"), 64, 4, render, {}, Encoding{false, -1.0f});
    EXPECT_EQ(runCompare({out("render-lin.png").string(), exr, "--encoding", "linear", "--exposure", "-1",
                          "--max-bad-fraction", "0"})
                  .exitCode,
              0);
    // Two PNGs: levels as stored, whatever --encoding says.
    const Result levels = runCompare({png, png, "--encoding", "linear", "--json"});
    const auto jl = nlohmann::json::parse(levels.stdoutText);
    EXPECT_EQ(jl["space"], "levels");
    EXPECT_TRUE(jl["eight_bit_encoding"].is_null());
    EXPECT_EQ(jl["compared_in"], "8-bit levels as stored (A: PNG, B: PNG)");
    EXPECT_THROW(runCompare({png, exr, "--encoding", "log"}), Error);
}

TEST(CompareCli, NonFiniteMismatchFailsRmseLimit) {
    Frame f;
    f.resize(2, 1);
    writeAov(out("d1.pfm"), f, "depth");
    f.depth[0] = 2.0f;
    writeAov(out("d2.pfm"), f, "depth");
    const Result r = runCompare({out("d1.pfm").string(), out("d2.pfm").string(), "--max-rmse", "1"});
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.stdoutText, "non-finite")) << r.stdoutText;
}

TEST(CompareCli, Errors) {
    writePair(out("ea.png"), out("eb.png"));
    EXPECT_THROW(runCompare({out("missing.png").string(), out("eb.png").string()}), Error);
    EXPECT_THROW(runCompare({out("ea.png").string(), out("eb.png").string(), "--threshold", "two"}), Error);
    writeColorImage(out("small.png"), 1, 1, {glm::vec3(0)});
    try {
        runCompare({out("ea.png").string(), out("small.png").string()});
        ADD_FAILURE() << "size mismatch accepted";
    } catch (const Error& e) {
        EXPECT_TRUE(contains(e.what(), "small.png")) << e.what();
        EXPECT_TRUE(contains(e.what(), "10x10")) << e.what();
    }
    EXPECT_THROW(runCompare({out("ea.png").string()}), CLI::ParseError);
    EXPECT_THROW(runCompare({out("ea.png").string(), out("eb.png").string(), "--max-bad-fraction", "2"}),
                 CLI::ParseError);
}
