// The SVG elements the report's plots are drawn with (svg_plot.cpp, svg_bar_chart.cpp): numbers
// to one decimal (a tenth of a pixel), text with its characters escaped, lines and rectangles.
#pragma once

#include <algorithm>
#include <cstdio>
#include <string>

#include "bench/svg_plot.h"

namespace vkray::bench::svg {

// The width of one character of the plots' 11 px sans-serif text, for margins and labels.
inline constexpr double kCharWidth = 6.2;

inline std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

inline std::string text(double x, double y, const std::string& s, const std::string& attrs) {
    return "<text x=\"" + num(x) + "\" y=\"" + num(y) + "\" " + attrs + ">" + escapeXml(s) + "</text>\n";
}

inline std::string line(double x1, double y1, double x2, double y2, const std::string& attrs) {
    return "<line x1=\"" + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) + "\" y2=\"" + num(y2) + "\" " +
           attrs + "/>\n";
}

inline std::string rect(double x, double y, double w, double h, const std::string& attrs) {
    return "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(std::max(0.0, w)) + "\" height=\"" +
           num(h) + "\" " + attrs + "/>";
}

}  // namespace vkray::bench::svg
