// The SVG plotting helper: tick values and their placement on linear and log axes, labels, escaping,
// and that every point a plot is given appears once (or on the zero row of a log axis).
#include <algorithm>
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/svg_plot.h"

using namespace vkray::bench;

namespace {

size_t count(const std::string& haystack, const std::string& needle) {
    size_t n = 0;
    for (size_t at = haystack.find(needle); at != std::string::npos; at = haystack.find(needle, at + needle.size())) ++n;
    return n;
}

// The cy of every circle, in document order.
std::vector<double> circleYs(const std::string& svg) {
    std::vector<double> ys;
    static const std::regex cy(R"re(<circle cx="[-0-9.]+" cy="([-0-9.]+)")re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), cy); it != std::sregex_iterator(); ++it)
        ys.push_back(std::stod((*it)[1]));
    return ys;
}

void expectTicks(const std::vector<double>& got, const std::vector<double>& want) {
    ASSERT_EQ(got.size(), want.size());
    for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-12 * want[i]) << i;
}

}  // namespace

TEST(SvgPlot, LogScaleTicksAreDecadesEquallySpaced) {
    const Scale s = Scale::log(1.0, 1000.0);
    expectTicks(s.ticks(), {1, 10, 100, 1000});
    const double step = s.unit(10) - s.unit(1);
    EXPECT_NEAR(s.unit(100) - s.unit(10), step, 1e-12);
    EXPECT_NEAR(s.unit(1000) - s.unit(100), step, 1e-12);
    EXPECT_NEAR(s.unit(1), 0.0, 1e-12);
    EXPECT_NEAR(s.unit(1000), 1.0, 1e-12);
    EXPECT_TRUE(std::isnan(s.unit(0.0)));
}

TEST(SvgPlot, LogAxisEndsOnLabelledValues) {
    const Scale s = Scale::log(0.0122, 0.075);  // errors of a real bench run
    EXPECT_NEAR(s.lo(), 0.01, 1e-15);
    EXPECT_NEAR(s.hi(), 0.1, 1e-15);
    expectTicks(s.ticks(), {0.01, 0.02, 0.05, 0.1});
    const Scale one = Scale::log(20.0, 20.0);
    EXPECT_NEAR(one.lo(), 10.0, 1e-12);
    EXPECT_NEAR(one.hi(), 50.0, 1e-12);
}

TEST(SvgPlot, ShortLogRangesGetOneTwoFiveTicks) {
    expectTicks(logTicks(0.002, 0.5), {0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5});
    expectTicks(logTicks(3.0, 9.0), {3, 4, 5, 6, 7, 8, 9});
}

TEST(SvgPlot, LongLogRangesAreThinnedToPowersOfTen) {
    const std::vector<double> t = logTicks(1e-6, 1e6);
    EXPECT_LE(t.size(), 8u);
    EXPECT_GE(t.size(), 4u);
    for (double v : t) EXPECT_NEAR(std::log10(v), std::round(std::log10(v)), 1e-9) << v;
}

TEST(SvgPlot, LinearTicksAreNiceAndCoverTheRange) {
    expectTicks(niceLinearTicks(0.0, 7.3, 6), {0, 2, 4, 6, 8});
    const Scale s = Scale::linear(0.13, 0.87);
    EXPECT_LE(s.lo(), 0.13);
    EXPECT_GE(s.hi(), 0.87);
    EXPECT_DOUBLE_EQ(s.unit(s.lo()), 0.0);
    EXPECT_DOUBLE_EQ(s.unit(s.hi()), 1.0);
    EXPECT_EQ(formatTick(s.ticks()[1]), "0.2");  // steps of 0.2, without floating-point noise in the labels
    const Scale single = Scale::linear(5.0, 5.0);
    EXPECT_LT(single.lo(), 5.0);
    EXPECT_GT(single.hi(), 5.0);
}

TEST(SvgPlot, ExplicitTicksOutsideTheAxisAreDropped) {
    Scale s = Scale::linear(1.0, 16.0);
    s.withTicks({1, 2, 4, 8, 16, 64});
    expectTicks(s.ticks(), {1, 2, 4, 8, 16});
}

TEST(SvgPlot, TickLabelsAreShort) {
    EXPECT_EQ(formatTick(0.1 + 0.2), "0.3");
    EXPECT_EQ(formatTick(1500.0), "1500");
    EXPECT_EQ(formatTick(0.002), "0.002");
    EXPECT_EQ(formatTick(2.5e-6), "2.5e-06");
    EXPECT_EQ(formatTick(0.0), "0");
}

TEST(SvgPlot, EscapesText) { EXPECT_EQ(escapeXml("a<b & \"c\" 'd'>"), "a&lt;b &amp; &quot;c&quot; &#39;d&#39;&gt;"); }

TEST(SvgPlot, EveryPointIsDrawnWithItsTooltipAndZeroGoesBelowTheLogAxis) {
    PlotSeries s;
    s.name = "group <1>";
    s.color = "#0072B2";
    s.points = {{1, 0.1, "first", "", false}, {10, 0.01, "second", "on the front", true}, {100, 0.0, "identical", "", false}};
    PlotOptions options;
    options.xTitle = "ms";
    options.yTitle = "RMSE";
    options.yZeroLabel = "identical (0)";
    const std::string svg = svgPlot(options, Scale::logFor({1, 10, 100}), Scale::logFor({0.1, 0.01, 0.0}), {s});
    EXPECT_EQ(count(svg, "<g class=\"point"), 3u);
    EXPECT_EQ(count(svg, "<g class=\"point emphasised\">"), 1u);
    EXPECT_NE(svg.find("<title>second</title>"), std::string::npos);
    EXPECT_NE(svg.find(">on the front</text>"), std::string::npos);
    EXPECT_NE(svg.find(">identical (0)</text>"), std::string::npos);
    EXPECT_NE(svg.find(">group &lt;1&gt;</text>"), std::string::npos);  // legend, escaped
    EXPECT_EQ(svg.find("http"), std::string::npos);
    // SVG y grows downwards: 0.1 is drawn above 0.01, and 0 below both, under the axis.
    const std::vector<double> ys = circleYs(svg);
    ASSERT_GE(ys.size(), 3u);  // the legend's sample circle comes after the points
    EXPECT_LT(ys[0], ys[1]);
    EXPECT_GT(ys[2], ys[1] + 20.0);
}

TEST(SvgPlot, PointsALogAxisCannotPlaceAreLeftOut) {
    PlotSeries s;
    s.points = {{0.0, 1.0, "", "", false}, {2.0, 1.0, "", "", false}, {3.0, -1.0, "", "", false}};
    // x = 0 has no place on a log x axis; y = -1 has no zero row without a label.
    const std::string svg = svgPlot({}, Scale::log(1, 10), Scale::log(0.1, 10), {s});
    EXPECT_EQ(count(svg, "<g class=\"point"), 1u);
}

namespace {

struct LabelBox {
    double x0, y0, x1, y1;
    std::string text;
};

// Every point label's box as drawn: from its x and baseline, 10 px text of about 5.5 px a character.
std::vector<LabelBox> labelBoxes(const std::string& svg) {
    std::vector<LabelBox> boxes;
    static const std::regex label(R"re(<text x="([-0-9.]+)" y="([-0-9.]+)" class="label"[^>]*>([^<]*)</text>)re");
    for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label); it != std::sregex_iterator(); ++it) {
        const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
        boxes.push_back({x, y - 8.0, x + 5.5 * double((*it)[3].length()), y + 2.0, (*it)[3]});
    }
    return boxes;
}

bool overlap(const LabelBox& a, const LabelBox& b) {
    return std::min(a.x1, b.x1) > std::max(a.x0, b.x0) && std::min(a.y1, b.y1) > std::max(a.y0, b.y0);
}

}  // namespace

// Points close together, as the accelerators of one scene are (the same error, times a few percent
// apart): every one keeps its label, no two labels overlap, and those moved away from their point
// are joined to it by a leader line.
TEST(SvgPlot, LabelsOfCrowdedPointsDoNotOverlap) {
    PlotSeries s;
    s.color = "#0072B2";
    for (int i = 0; i < 10; ++i)
        s.points.push_back({100.0 + 2.0 * i, 0.01 * (1.0 + 0.01 * i), "tip " + std::to_string(i),
                            "accelerator-" + std::to_string(i), i == 0});
    s.points.push_back({1000.0, 0.0, "the reference", "CPU double", false});
    PlotOptions options;
    options.yZeroLabel = "identical (0)";
    const std::string svg = svgPlot(options, Scale::log(50, 2000), Scale::log(0.005, 0.05), {s});
    const std::vector<LabelBox> boxes = labelBoxes(svg);
    ASSERT_EQ(boxes.size(), s.points.size());
    for (const PlotPoint& p : s.points) EXPECT_NE(svg.find(">" + p.label + "</text>"), std::string::npos) << p.label;
    for (size_t i = 0; i < boxes.size(); ++i)
        for (size_t j = i + 1; j < boxes.size(); ++j)
            EXPECT_FALSE(overlap(boxes[i], boxes[j])) << boxes[i].text << " and " << boxes[j].text;
    EXPECT_GT(count(svg, "class=\"leader\""), 0u);
    EXPECT_EQ(count(svg, "<title>"), s.points.size());  // the hover text stays
    for (const LabelBox& b : boxes) {  // inside the picture
        EXPECT_GE(b.x0, 0.0);
        EXPECT_LE(b.x1, double(options.width));
        EXPECT_GE(b.y0, 0.0);
    }
}
