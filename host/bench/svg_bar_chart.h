// A horizontal bar chart for report.html, beside svg_plot.h's x-y plots: one bar per category with
// its min–max spread as an error bar and its figure written beside it, and reference figures (a
// baseline) as vertical lines, each with its own min–max as a whisker above the bars. Horizontal,
// so long category names ("bvh:bvh-reinsert-iterations=2") read without rotation.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace vkray::bench {

struct Bar {
    std::string label;               // left of the bar
    double value = 0.0;              // the bar's length (a median)
    double low = 0.0, high = 0.0;    // the error bar; none when both equal value
    std::string valueText;           // right of the error bar
    std::string tooltip;             // <title>: what a hover shows
    std::string color = "#0072B2";
};

struct ReferenceLine {
    std::string name;                // its legend entry
    double value = 0.0;              // the line
    double low = 0.0, high = 0.0;    // its whisker; none when both equal value
    std::string color = "#333333";
    bool dashed = true;
};

struct BarChartOptions {
    std::string title, xTitle;
    int width = 760;
    // Legend entries for the bars' colours: name, colour.
    std::vector<std::pair<std::string, std::string>> swatches;
    std::string cssClass = "plot bar-chart";
};

// The <svg> element: the x axis starts at 0 and spans the bars' spreads and the reference lines (a
// reference's whisker beyond it is cut at its end, without a cap); each bar is a <g class="bar"> holding its <title>, its
// <rect> and its error bar, each reference a <g class="reference">, so a reader (or a test) can count
// them. Bars and references that are not finite and positive are left out.
std::string svgBarChart(const BarChartOptions& options, const std::vector<Bar>& bars,
                        const std::vector<ReferenceLine>& references);

}  // namespace vkray::bench
