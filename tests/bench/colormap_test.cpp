// The heatmap colormap: viridis's end points and middle, clamping, brightness rising with the value
// (what makes a heatmap readable), and heatmapImage's shared scale with outliers clamped.
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "bench/colormap.h"
#include "core/error.h"

using namespace vkray;
using namespace vkray::bench;

namespace {

double luminance(DisplayColor c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

void expectSameColor(DisplayColor a, DisplayColor b) {
    EXPECT_FLOAT_EQ(a.r, b.r);
    EXPECT_FLOAT_EQ(a.g, b.g);
    EXPECT_FLOAT_EQ(a.b, b.b);
}

}  // namespace

TEST(Colormap, ViridisEndsAndMiddleAreMatplotlibs) {
    EXPECT_EQ(cssColor(viridis(0.0)), "#440154");
    EXPECT_EQ(cssColor(viridis(0.5)), "#21918c");
    EXPECT_EQ(cssColor(viridis(1.0)), "#fde725");
}

TEST(Colormap, OutOfRangeAndNanAreClamped) {
    expectSameColor(viridis(-3.0), viridis(0.0));
    expectSameColor(viridis(7.0), viridis(1.0));
    expectSameColor(viridis(std::numeric_limits<double>::quiet_NaN()), viridis(0.0));
}

TEST(Colormap, BrightnessRisesWithTheValue) {
    double previous = -1.0;
    for (int i = 0; i <= 100; ++i) {
        const double y = luminance(viridis(i / 100.0));
        EXPECT_GT(y, previous) << "t = " << i / 100.0;
        previous = y;
    }
}

TEST(Colormap, HeatmapUsesTheGivenScaleAndClampsOutliers) {
    const std::vector<uint32_t> values = {0, 50, 100, 100000, 25, 75};  // 3x2, top row first
    const Image im = heatmapImage(values, 3, 2, 100.0);
    ASSERT_EQ(im.width, 3);
    ASSERT_EQ(im.height, 2);
    ASSERT_EQ(im.channels, 3);
    auto pixel = [&](int x, int y) { return DisplayColor{im.at(x, y, 0), im.at(x, y, 1), im.at(x, y, 2)}; };
    expectSameColor(pixel(0, 0), viridis(0.0));
    expectSameColor(pixel(1, 0), viridis(0.5));
    expectSameColor(pixel(2, 0), viridis(1.0));
    expectSameColor(pixel(0, 1), viridis(1.0));  // the outlier shares the top colour
    expectSameColor(pixel(1, 1), viridis(0.25));
    expectSameColor(pixel(2, 1), viridis(0.75));
}

TEST(Colormap, HeatmapWithoutAPositiveScaleShowsZeroAgainstNonZero) {
    const Image im = heatmapImage({0, 3}, 2, 1, 0.0);
    expectSameColor({im.at(0, 0, 0), im.at(0, 0, 1), im.at(0, 0, 2)}, viridis(0.0));
    expectSameColor({im.at(1, 0, 0), im.at(1, 0, 1), im.at(1, 0, 2)}, viridis(1.0));
}

TEST(Colormap, HeatmapRejectsAMismatchedSize) {
    EXPECT_THROW(heatmapImage({1, 2, 3}, 2, 2, 3.0), Error);
    EXPECT_THROW(heatmapImage({}, 0, 0, 1.0), Error);
}
