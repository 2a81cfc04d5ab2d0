// The bar chart of report.html (see svg_bar_chart.h), drawn with svg_plot.h's scales and ticks.
#include "bench/svg_bar_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "bench/svg_elements.h"
#include "bench/svg_plot.h"

namespace vkray::bench {
namespace {

using svg::kCharWidth, svg::line, svg::num, svg::rect, svg::text;

constexpr double kRowHeight = 26.0;
constexpr double kBarHeight = 16.0;
constexpr double kLegendRow = 18.0;
constexpr double kWhiskerRow = 10.0;  // a reference's min–max, above the bars

double textWidth(const std::string& s) {
    size_t glyphs = 0;  // UTF-8: count the bytes that start a character
    for (char c : s) glyphs += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
    return kCharWidth * double(glyphs);
}

bool drawable(double v) { return std::isfinite(v) && v > 0.0; }

std::string lineStyle(const ReferenceLine& r) {
    return "stroke=\"" + escapeXml(r.color) + "\" stroke-width=\"2\"" + (r.dashed ? " stroke-dasharray=\"6 4\"" : "");
}

// The legend: swatches, then the reference lines, wrapped to the width; returns its height.
double legend(const BarChartOptions& o, const std::vector<ReferenceLine>& refs, double top, std::string& out) {
    double x = 12.0, y = top;
    auto entry = [&](const std::string& name, double keyWidth) {
        const double w = keyWidth + 6.0 + textWidth(name) + 18.0;
        if (x > 12.0 && x + w > double(o.width) - 12.0) x = 12.0, y += kLegendRow;
        const double at = x;
        x += w;
        return at;
    };
    for (const auto& [name, color] : o.swatches) {
        const double at = entry(name, 14.0);
        out += rect(at, y - 9.0, 14.0, 10.0, "fill=\"" + escapeXml(color) + "\"") + "\n";
        out += text(at + 20.0, y, name, "");
    }
    for (const ReferenceLine& r : refs) {
        const double at = entry(r.name, 24.0);
        out += line(at, y - 4.0, at + 24.0, y - 4.0, lineStyle(r));
        out += text(at + 30.0, y, r.name, "");
    }
    return o.swatches.empty() && refs.empty() ? 0.0 : y - top + kLegendRow;
}

// A horizontal min–max whisker at height y from x0 to x1, with a cap at each end not cut off by
// the axis.
std::string whisker(double x0, double x1, double y, bool cap0, bool cap1, const std::string& ink) {
    std::string out = line(x0, y, x1, y, ink);
    if (cap0) out += line(x0, y - 5.0, x0, y + 5.0, ink);
    if (cap1) out += line(x1, y - 5.0, x1, y + 5.0, ink);
    return out;
}

}  // namespace

std::string svgBarChart(const BarChartOptions& o, const std::vector<Bar>& allBars,
                        const std::vector<ReferenceLine>& allRefs) {
    std::vector<Bar> bars;
    std::vector<ReferenceLine> refs;
    std::copy_if(allBars.begin(), allBars.end(), std::back_inserter(bars), [](const Bar& b) { return drawable(b.value); });
    std::copy_if(allRefs.begin(), allRefs.end(), std::back_inserter(refs),
                 [](const ReferenceLine& r) { return drawable(r.value); });

    // The axis spans the bars with their spreads and the reference lines, not the references'
    // spreads: a baseline timed on a busy machine can spread several times its median, and would
    // squeeze the bars into a corner. Its whisker is cut at the axis end instead.
    std::vector<double> xs{0.0};
    double labelWidth = 0.0, valueWidth = 0.0;
    for (const Bar& b : bars) {
        xs.insert(xs.end(), {b.value, b.high});
        labelWidth = std::max(labelWidth, textWidth(b.label));
        valueWidth = std::max(valueWidth, textWidth(b.valueText));
    }
    for (const ReferenceLine& r : refs) xs.push_back(r.value);
    const Scale x = Scale::linearFor(xs, true);

    std::string body;
    const double legendTop = o.title.empty() ? 18.0 : 44.0;
    const double legendHeight = legend(o, refs, legendTop, body);
    const double whiskers = kWhiskerRow * double(refs.size());  // the references' spreads, above the bars
    const double top = legendTop + legendHeight + 2.0 + whiskers;
    const double left = 16.0 + labelWidth, right = double(o.width) - 14.0 - valueWidth;
    const double bottom = top + kRowHeight * double(std::max<size_t>(bars.size(), 1));
    const double height = bottom + 46.0;
    auto px = [&](double v) { return left + x.unit(std::clamp(v, x.lo(), x.hi())) * (right - left); };

    std::string out = "<svg class=\"" + escapeXml(o.cssClass) + "\" viewBox=\"0 0 " + std::to_string(o.width) + " " +
                      num(height) + "\" width=\"" + std::to_string(o.width) + "\" height=\"" + num(height) +
                      "\" role=\"img\" aria-label=\"" + escapeXml(o.title) +
                      "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    out += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    if (!o.title.empty()) out += text(12.0, 22.0, o.title, "font-size=\"13\" font-weight=\"bold\"");
    out += body;
    for (double t : x.ticks()) {  // the grid, then the tick labels below the axis
        out += line(px(t), top, px(t), bottom, "stroke=\"#e3e3e3\" stroke-width=\"1\"");
        out += line(px(t), bottom, px(t), bottom + 5.0, "stroke=\"#333\"");
        out += text(px(t), bottom + 17.0, formatTick(t), "text-anchor=\"middle\"");
    }
    const std::string ink = "stroke=\"#222\" stroke-width=\"1.3\"";
    std::string labels;  // drawn last, over the reference lines
    for (size_t i = 0; i < bars.size(); ++i) {
        const Bar& b = bars[i];
        const double cy = top + kRowHeight * (double(i) + 0.5);
        out += "<g class=\"bar\"><title>" + escapeXml(b.tooltip) + "</title>" +
               rect(left, cy - kBarHeight / 2.0, px(b.value) - left, kBarHeight, "fill=\"" + escapeXml(b.color) + "\"");
        const bool spread = b.high > b.low && std::isfinite(b.low) && std::isfinite(b.high);
        if (spread) out += whisker(px(b.low), px(b.high), cy, true, b.high <= x.hi(), ink);
        out += "</g>\n";
        labels += text(left - 6.0, cy + 4.0, b.label, "text-anchor=\"end\" class=\"label\"");
        const double after = std::max(px(b.value), spread ? px(b.high) : 0.0) + 6.0;
        labels += text(after, cy + 4.0, b.valueText,
                       "class=\"value\" stroke=\"#fff\" stroke-width=\"3\" paint-order=\"stroke\"");
    }
    for (size_t i = 0; i < refs.size(); ++i) {  // over the bars, so a long bar does not hide its line
        const ReferenceLine& r = refs[i];
        const double wy = top - whiskers + kWhiskerRow * (double(i) + 0.5);
        const std::string colour = "stroke=\"" + escapeXml(r.color) + "\" stroke-width=\"1.3\"";
        out += "<g class=\"reference\"><title>" + escapeXml(r.name) + "</title>" +
               line(px(r.value), wy, px(r.value), bottom, lineStyle(r));
        if (r.high > r.low && std::isfinite(r.low) && std::isfinite(r.high))
            out += whisker(px(r.low), px(r.high), wy, r.low >= x.lo(), r.high <= x.hi(), colour);
        out += "</g>\n";
    }
    out += labels;
    out += line(left, top, left, bottom, "stroke=\"#333\"");
    out += line(left, bottom, right, bottom, "stroke=\"#333\"");
    out += text((left + right) / 2.0, height - 10.0, o.xTitle, "text-anchor=\"middle\" class=\"axis-title\"");
    return out + "</svg>\n";
}

}  // namespace vkray::bench
