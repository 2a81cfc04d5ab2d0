// From linear values to 8-bit levels: the sRGB curve (IEC 61966-2-1) and exposure of Encoding, the
// linear encoding's exact old levels, HDR files untouched by any encoding, parseEncoding's errors,
// and the normalisation of `vkray convert --normalize`.
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/error.h"
#include "image/image_io.h"
#include "image/tone.h"

namespace fs = std::filesystem;
using namespace vkray;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

fs::path out(const std::string& name) { return fs::path(VKRAY_TEST_OUTPUT_DIR) / ("tone_" + name); }

int level(const Image& im, int x, int c = 0) { return int(std::lround(im.at(x, 0, c) * 255.0f)); }

}  // namespace

TEST(Tone, SrgbCurveLevels) {
    const LevelEncoder srgb(Encoding{});
    EXPECT_EQ(srgb(0.0f), 0);
    EXPECT_EQ(srgb(1.0f), 255);
    EXPECT_EQ(srgb(0.5f), 188);      // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
    EXPECT_EQ(srgb(0.18f), 118);     // middle grey: 0.4614
    EXPECT_EQ(srgb(0.001f), 3);      // linear segment: 12.92 * 0.001 = 0.0129
    EXPECT_EQ(srgb(0.0031308f), 10);  // where the two pieces meet: 0.04045
    EXPECT_EQ(srgb(kNan), 0);
    EXPECT_EQ(srgb(kInf), 255);
    EXPECT_EQ(srgb(-0.5f), 0);
    EXPECT_NEAR(srgbEncode(0.0031308), 0.04045, 1e-5);
    EXPECT_NEAR(1.055 * std::pow(0.0031308, 1.0 / 2.4) - 0.055, 0.04045, 1e-5);  // continuous there
}

TEST(Tone, ExposureScalesBeforeEncoding) {
    EXPECT_EQ(LevelEncoder(Encoding{true, 1.0f})(0.25f), 188);   // 0.25 * 2 = 0.5
    EXPECT_EQ(LevelEncoder(Encoding{false, -1.0f})(1.0f), 128);  // 0.5, linear
    EXPECT_EQ(LevelEncoder(Encoding{false, 2.0f})(0.2f), 204);   // 0.8
    EXPECT_EQ(LevelEncoder(Encoding{false, 3.0f})(0.2f), 255);   // 1.6, clamped
}

// decodeLevels undoes LevelEncoder: every level decodes to a value that encodes back to it.
TEST(Tone, DecodeLevelsInvertsTheEncoder) {
    for (const Encoding& e : {Encoding{}, Encoding::linear(), Encoding{true, 1.5f}, Encoding{false, -2.0f}}) {
        Image levels(256, 1, 1);
        for (int k = 0; k <= 255; ++k) levels.data[size_t(k)] = float(k) / 255.0f;
        const Image linear = decodeLevels(levels, e);
        const LevelEncoder encode(e);
        for (int k = 0; k <= 255; ++k) EXPECT_EQ(encode(linear.data[size_t(k)]), k) << "level " << k;
    }
    EXPECT_NEAR(srgbDecode(srgbEncode(0.18)), 0.18, 1e-12);
    EXPECT_NEAR(srgbDecode(0.04045), 0.0031308, 1e-6);  // where the two pieces meet
    EXPECT_THROW(decodeLevels(Image(1, 1, 1), Encoding{true, 100.0f}), Error);
}

// Encoding::linear() stores exactly the levels vkray stored before encodings existed.
TEST(Tone, LinearIsRound255OfTheClampedValue) {
    const LevelEncoder linear(Encoding::linear());
    for (int k = 0; k <= 255; ++k) EXPECT_EQ(linear(float(k) / 255.0f), k);
    EXPECT_EQ(linear(0.5f), 128);
    EXPECT_EQ(linear(0.499f / 255.0f), 0);
}

// The lookup of LevelEncoder gives the formula's level for every input: around each of the 255
// level boundaries (the floats within 64 ulps of where the formula steps, found here by its own
// bisection), over a million random values in [0, 1.25], and at the special values; for both
// encodings and several exposures.
TEST(Tone, LookupMatchesTheFormula) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.25f);
    const auto bits = [](float f) { return std::bit_cast<uint32_t>(f); };
    for (const bool srgb : {true, false})
        for (const float exposure : {0.0f, 1.5f, -2.3f, 0.1f}) {
            SCOPED_TRACE(std::string(srgb ? "srgb" : "linear") + " exposure " + std::to_string(exposure));
            const LevelEncoder e(Encoding{srgb, exposure});
            const auto check = [&](float c) { ASSERT_EQ(int(e(c)), int(e.direct(c))) << "c = " << c; };
            for (const float c : {0.0f, -0.0f, -1.0f, kNan, kInf, -kInf, 1e-45f, 1e-38f, 1.0f, 2.0f}) check(c);
            for (int k = 1; k <= 255; ++k) {  // the least positive float of level k or more
                uint32_t lo = 0, hi = bits(8.0f);
                while (hi - lo > 1) {
                    const uint32_t mid = lo + (hi - lo) / 2;
                    (e.direct(std::bit_cast<float>(mid)) >= k ? hi : lo) = mid;
                }
                for (uint32_t b = hi - std::min<uint32_t>(hi, 64); b <= hi + 64; ++b) check(std::bit_cast<float>(b));
            }
            for (int i = 0; i < 1000000; ++i) check(u(rng));
        }
}

TEST(Tone, EncodingAppliesTo8BitFilesOnly) {
    const std::vector<glm::vec3> rgb = {{0.5f, 0.18f, 2.0f}, {0.25f, kNan, -1.0f}};
    writeColorImage(out("srgb.png"), 2, 1, rgb);  // the default: sRGB
    const Image png = readImage(out("srgb.png"));
    EXPECT_EQ(level(png, 0, 0), 188);
    EXPECT_EQ(level(png, 0, 1), 118);
    EXPECT_EQ(level(png, 0, 2), 255);
    EXPECT_EQ(level(png, 1, 1), 0);
    writeColorImage(out("ev.bmp"), 2, 1, rgb, {}, Encoding{true, 1.0f});
    EXPECT_EQ(level(readImage(out("ev.bmp")), 1, 0), 188);
    for (const char* name : {"raw.pfm", "raw.exr"}) {
        writeColorImage(out(name), 2, 1, rgb, {}, Encoding{true, 3.0f});
        const Image hdr = readImage(out(name));
        EXPECT_EQ(hdr.at(0, 0, 0), 0.5f) << name;
        EXPECT_EQ(hdr.at(0, 0, 2), 2.0f) << name;
        EXPECT_TRUE(std::isnan(hdr.at(1, 0, 1))) << name;
    }
}

TEST(Tone, ParseEncoding) {
    EXPECT_TRUE(parseEncoding("srgb", 0).srgb);
    const Encoding e = parseEncoding("linear", -2.5);
    EXPECT_FALSE(e.srgb);
    EXPECT_EQ(e.exposure, -2.5f);
    try {
        parseEncoding("gamma", 0);
        ADD_FAILURE() << "gamma accepted";
    } catch (const Error& err) {
        EXPECT_NE(std::string(err.what()).find("--encoding 'gamma': expected srgb or linear"), std::string::npos);
    }
    EXPECT_THROW(parseEncoding("srgb", 100), Error);
    EXPECT_THROW(parseEncoding("srgb", std::nan("")), Error);
    EXPECT_THROW(writeColorImage(out("bad.png"), 1, 1, {glm::vec3(0)}, {}, Encoding{true, kInf}), Error);
}

TEST(Tone, NormalizedForViewing) {
    Image depth(4, 1, 1);
    depth.data = {2.0f, kInf, 4.0f, 3.0f};
    const Image n = normalizedForViewing(depth);
    EXPECT_EQ(n.data, (std::vector<float>{0.0f, 0.0f, 1.0f, 0.5f}));
    Image flat(2, 1, 1);
    flat.data = {7.0f, kNan};
    EXPECT_EQ(normalizedForViewing(flat).data, (std::vector<float>{1.0f, 0.0f}));
    Image none(1, 1, 1);
    none.data = {kInf};
    EXPECT_EQ(normalizedForViewing(none).data, (std::vector<float>{0.0f}));
}
