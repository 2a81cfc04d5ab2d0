// Comparison metrics on hand-made images whose RMSE, PSNR, max error and bad pixels are known,
// the inf/NaN rules of compare.h, mismatch errors, the diff image's colour classes, and the space two
// files are compared in (an 8-bit file decoded against a float one).
#include <cmath>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "core/error.h"
#include "image/compare.h"
#include "image/tone.h"

using namespace vkray;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

Image make(int w, int h, int c, std::vector<float> data) {
    Image im(w, h, c);
    im.data = std::move(data);
    return im;
}

}  // namespace

TEST(Compare, IdenticalImages) {
    const Image a = make(2, 1, 3, {0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f});
    const CompareStats s = compareImages(a, a, 0.0);
    EXPECT_EQ(s.rmse, 0.0);
    EXPECT_TRUE(std::isinf(s.psnr) && s.psnr > 0);
    EXPECT_EQ(s.maxError, 0.0);
    EXPECT_EQ(s.maxErrorX, -1);
    EXPECT_EQ(s.badPixels, 0);
    EXPECT_EQ(s.pixels, 2);
    EXPECT_EQ(s.badFraction, 0.0);
    EXPECT_EQ(s.nonFiniteMismatches, 0);
}

TEST(Compare, KnownMetricsOneChannel) {
    // Errors 0.1, 0, 0, 0.2 (the last at column 1, row 1): RMSE = sqrt((0.01 + 0.04) / 4).
    const Image a = make(2, 2, 1, {0.0f, 0.5f, 0.5f, 0.0f});
    const Image b = make(2, 2, 1, {0.1f, 0.5f, 0.5f, 0.2f});
    const CompareStats s = compareImages(a, b, 0.15);
    const double rmse = std::sqrt(0.0125);
    EXPECT_NEAR(s.rmse, rmse, 1e-7);
    EXPECT_NEAR(s.psnr, 20.0 * std::log10(1.0 / rmse), 1e-5);
    EXPECT_NEAR(s.psnr, 19.0309, 1e-4);
    EXPECT_NEAR(s.maxError, 0.2, 1e-7);
    EXPECT_EQ(s.maxErrorX, 1);
    EXPECT_EQ(s.maxErrorY, 1);
    EXPECT_EQ(s.badPixels, 1);
    EXPECT_EQ(s.pixels, 4);
    EXPECT_DOUBLE_EQ(s.badFraction, 0.25);
    EXPECT_EQ(compareImages(a, b, 0.05).badPixels, 2);
    EXPECT_EQ(compareImages(a, b, 0.25).badPixels, 0);
}

TEST(Compare, RmseCountsEveryChannelAndBadNeedsOneChannel) {
    // Pixel 0 differs by 0.3 in green only; pixel 1 by 0.1 in all three channels.
    const Image a = make(2, 1, 3, {0, 0, 0, 0, 0, 0});
    const Image b = make(2, 1, 3, {0, 0.3f, 0, 0.1f, 0.1f, 0.1f});
    const CompareStats s = compareImages(a, b, 0.2);
    EXPECT_NEAR(s.rmse, std::sqrt((0.09 + 3 * 0.01) / 6.0), 1e-7);
    EXPECT_EQ(s.badPixels, 1);
    EXPECT_EQ(s.maxErrorX, 0);
    EXPECT_NEAR(s.maxError, 0.3, 1e-7);
}

// 8-bit levels as a PNG reads them back (float(k / 255)): a difference of exactly two levels is
// not over a 2/255 threshold, three levels are.
TEST(Compare, ThresholdInEightBitLevelsIsStable) {
    for (int base = 0; base <= 252; ++base) {
        const Image a = make(3, 1, 1, {float(base) / 255.0f, float(base) / 255.0f, float(base) / 255.0f});
        const Image b = make(3, 1, 1, {float(base + 1) / 255.0f, float(base + 2) / 255.0f, float(base + 3) / 255.0f});
        const CompareStats s = compareImages(a, b, 2.0 / 255.0);
        ASSERT_EQ(s.badPixels, 1) << base;
        ASSERT_EQ(compareImages(b, a, 2.0 / 255.0).badPixels, 1) << base;
    }
}

TEST(Compare, NonFiniteRules) {
    // Depth-like AOV: pixel 0 both miss (+inf), pixel 1 miss vs hit, pixel 2 both NaN, pixel 3 hit
    // vs hit off by 0.5, pixel 4 +inf vs -inf.
    const Image a = make(5, 1, 1, {kInf, kInf, kNan, 2.0f, kInf});
    const Image b = make(5, 1, 1, {kInf, 4.0f, kNan, 2.5f, -kInf});
    const CompareStats s = compareImages(a, b, 0.1);
    EXPECT_EQ(s.nonFiniteMismatches, 2);
    EXPECT_EQ(s.badPixels, 3);  // pixels 1, 3, 4
    EXPECT_TRUE(std::isinf(s.maxError));
    EXPECT_EQ(s.maxErrorX, 1);  // the first infinite error
    // RMSE over the three comparable values: errors 0, 0, 0.5.
    EXPECT_NEAR(s.rmse, std::sqrt(0.25 / 3.0), 1e-7);

    // NaN against a number is a mismatch too.
    const CompareStats n = compareImages(make(1, 1, 1, {kNan}), make(1, 1, 1, {0.0f}), 1.0);
    EXPECT_EQ(n.nonFiniteMismatches, 1);
    EXPECT_EQ(n.badPixels, 1);
    EXPECT_EQ(n.rmse, 0.0);

    // Primid-like AOV: -1 vs 7 is an ordinary finite error.
    const CompareStats p = compareImages(make(1, 1, 1, {-1.0f}), make(1, 1, 1, {7.0f}), 0.5);
    EXPECT_EQ(p.maxError, 8.0);
    EXPECT_EQ(p.badPixels, 1);
}

TEST(Compare, MismatchesAreErrors) {
    const Image a(2, 2, 3), wider(3, 2, 3), grey(2, 2, 1);
    EXPECT_THROW(compareImages(a, wider, 0.0), Error);
    EXPECT_THROW(compareImages(a, grey, 0.0), Error);
    EXPECT_THROW(makeDiffImage(a, grey, 0.0), Error);
    EXPECT_THROW(compareImages(a, a, -1.0), Error);
    try {
        compareImages(a, wider, 0.0);
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("2x2 with 3 channels vs 3x2 with 3 channels"), std::string::npos) << e.what();
    }
}

TEST(Compare, DiffImageColourClasses) {
    // Pixel 0 equal (white), 1 tolerated (err 0.05 <= 0.1), 2 bad just over, 3 the worst, 4 inf vs finite.
    const Image a = make(5, 1, 1, {1.0f, 0.0f, 0.0f, 0.0f, kInf});
    const Image b = make(5, 1, 1, {1.0f, 0.05f, 0.1f + 1e-3f, 0.6f, 0.0f});
    const Image d = makeDiffImage(a, b, 0.1);
    ASSERT_EQ(d.width, 5);
    ASSERT_EQ(d.height, 1);
    ASSERT_EQ(d.channels, 3);
    // Equal: dim grey of a.
    EXPECT_FLOAT_EQ(d.at(0, 0, 0), 0.25f);
    EXPECT_FLOAT_EQ(d.at(0, 0, 1), 0.25f);
    // Tolerated: blue, 0.4 + 0.6 * 0.05 / 0.1.
    EXPECT_EQ(d.at(1, 0, 0), 0.0f);
    EXPECT_NEAR(d.at(1, 0, 2), 0.7f, 1e-6);
    // Bad: red, rising to yellow at the largest finite error.
    EXPECT_EQ(d.at(2, 0, 0), 1.0f);
    EXPECT_NEAR(d.at(2, 0, 1), 1e-3 / 0.5, 1e-4);
    EXPECT_EQ(d.at(3, 0, 0), 1.0f);
    EXPECT_FLOAT_EQ(d.at(3, 0, 1), 1.0f);
    EXPECT_EQ(d.at(3, 0, 2), 0.0f);
    // Non-finite mismatch: yellow.
    EXPECT_EQ(d.at(4, 0, 0), 1.0f);
    EXPECT_EQ(d.at(4, 0, 1), 1.0f);
    for (float v : d.data) EXPECT_TRUE(v >= 0.0f && v <= 1.0f);
}

namespace {

// A render-like linear image: a ramp over [0, 1.25] (past white, as highlights are), NaN in one value.
Image linearRamp() {
    Image im(64, 4, 3);
    for (size_t i = 0; i < im.data.size(); ++i) im.data[i] = float(i % 257) / 256.0f * 1.25f;
    im.data[5] = kNan;
    return im;
}

// `linear` as the levels / 255 an 8-bit file written with `e` reads back as.
Image asLevels(const Image& linear, const Encoding& e) {
    const LevelEncoder encode(e);
    Image out = linear;
    for (float& v : out.data) v = float(encode(v)) / 255.0f;
    return out;
}

// The largest linear error rounding to a level can make under `e`: half a step at the curve's steepest,
// the top level.
double halfLevelAtTop(const Encoding& e) {
    const double top = e.srgb ? srgbDecode(1.0) - srgbDecode(254.5 / 255.0) : 0.5 / 255.0;
    return top * std::exp2(-double(e.exposure));
}

}  // namespace

TEST(CompareSpace, SrgbPngAgainstItsExrAgreesWithinQuantisation) {
    for (const Encoding& e : {Encoding{}, Encoding{true, 1.0f}, Encoding::linear()}) {
        const Image exr = linearRamp();
        Image a = asLevels(exr, e), b = exr;
        const CompareSpace space = toCommonSpace(a, ImageFormat::Png, b, ImageFormat::Exr, e);
        EXPECT_TRUE(space.linear);
        EXPECT_TRUE(space.decoded);
        const CompareStats s = compareImages(a, b, 0.0);
        EXPECT_LE(s.maxError, halfLevelAtTop(e) + 1e-6) << space.description;
        EXPECT_EQ(s.nonFiniteMismatches, 0);  // NaN is 0 in both, as the 8-bit file stores it
    }
    // The words: which file was decoded with which curve, and what the float one was clamped to.
    Image a = asLevels(linearRamp(), Encoding{}), b = linearRamp();
    EXPECT_EQ(toCommonSpace(a, ImageFormat::Png, b, ImageFormat::Exr, Encoding{}).description,
              "linear radiance (A: sRGB PNG decoded; B: EXR clamped to [0, 1] as 8 bits hold it)");
    Image c = linearRamp(), d = asLevels(linearRamp(), Encoding{false, -1.0f});
    EXPECT_EQ(toCommonSpace(c, ImageFormat::Pfm, d, ImageFormat::Bmp, Encoding{false, -1.0f}).description,
              "linear radiance (A: PFM clamped to [0, 2] as 8 bits hold it; B: linear BMP at exposure -1 decoded)");
}

TEST(CompareSpace, WrongEncodingShowsAsADifference) {
    // The sRGB PNG taken for a linear one: its mid-tones are far too bright (what comparing the
    // levels as stored used to report without a word).
    const Image exr = linearRamp();
    Image a = asLevels(exr, Encoding{}), b = exr;
    toCommonSpace(a, ImageFormat::Png, b, ImageFormat::Exr, Encoding::linear());
    EXPECT_GT(compareImages(a, b, 0.0).rmse, 0.1);
}

TEST(CompareSpace, SameKindsCompareAsStored) {
    const Image levels = asLevels(linearRamp(), Encoding{});
    Image a = levels, b = levels;
    const CompareSpace eight = toCommonSpace(a, ImageFormat::Png, b, ImageFormat::Bmp, Encoding{});
    EXPECT_FALSE(eight.linear);
    EXPECT_FALSE(eight.decoded);
    EXPECT_EQ(eight.description, "8-bit levels as stored (A: PNG, B: BMP)");
    EXPECT_EQ(a.data, levels.data);
    const Image floats = linearRamp();
    Image c = floats, d = floats;
    const CompareSpace hdr = toCommonSpace(c, ImageFormat::Exr, d, ImageFormat::Pfm, Encoding{});
    EXPECT_TRUE(hdr.linear);
    EXPECT_FALSE(hdr.decoded);
    EXPECT_EQ(hdr.description, "linear values as stored (A: EXR, B: PFM)");
    EXPECT_EQ(c.data[6], floats.data[6]);
    EXPECT_GT(c.data[256], 1.0f);  // not clamped
    EXPECT_TRUE(std::isnan(c.data[5]));
}
