// A small SVG plotting helper for report.html: one x-y plot with linear or log axes, "nice" tick
// values, series of markers and lines, a legend and <title> tooltips. The SVG is meant to be inlined
// in an HTML5 page, which needs no xmlns attribute, so the output holds no URL at all.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace vkray::bench {

// Text for XML/HTML content and attribute values: & < > " ' escaped.
std::string escapeXml(std::string_view text);

// A tick value as a short label: up to 4 significant digits, exponent form only for very large or
// very small values ("0.001", "250", "1.5e+06").
std::string formatTick(double v);

// Tick values from {1, 2, 5} x 10^k covering [lo, hi] with about `target` ticks, all of them
// inside [lo, hi] rounded outwards to the step (a linear axis).
std::vector<double> niceLinearTicks(double lo, double hi, int target = 6);

// Ticks of a log axis within [lo, hi] (lo > 0): the powers of ten when at least three fall inside
// (thinned to at most eight), else 1, 2, 5 x 10^k, else 1..9 x 10^k, else linear nice ticks.
std::vector<double> logTicks(double lo, double hi);

// One axis: a data interval mapped to [0, 1], and its ticks.
class Scale {
public:
    // [lo, hi] widened to whole tick steps; a degenerate interval is widened around its value.
    static Scale linear(double lo, double hi);
    // [lo, hi] (both > 0, else [1, 10]) widened to the nearest 1, 2, 5 x 10^k outside it, so
    // both ends are labelled: [0.0122, 0.075] becomes [0.01, 0.1].
    static Scale log(double lo, double hi);
    // Fitted to `values`: finite ones for linear (with 0 included when asked), positive finite
    // ones for log; [0, 1] or [1, 10] when there are none.
    static Scale linearFor(const std::vector<double>& values, bool includeZero);
    static Scale logFor(const std::vector<double>& values);

    bool isLog() const { return log_; }
    double lo() const { return lo_; }
    double hi() const { return hi_; }
    // 0 at lo, 1 at hi (linear in log10 v on a log axis); outside [lo, hi] beyond [0, 1]. A log
    // axis cannot place v <= 0: it returns NaN, and the plot handles such points itself.
    double unit(double v) const;
    bool contains(double v) const;

    const std::vector<double>& ticks() const { return ticks_; }
    // Explicit ticks (thread counts, say) instead of the computed ones; those outside are dropped.
    Scale& withTicks(std::vector<double> ticks);

private:
    Scale(bool log, double lo, double hi, std::vector<double> ticks);
    bool log_ = false;
    double lo_ = 0.0, hi_ = 1.0;
    std::vector<double> ticks_;
};

enum class Marker { None, Circle, Square, Triangle, Diamond };
enum class Line { None, Straight, Steps };  // Steps: across at the old y, then up or down

struct PlotPoint {
    double x = 0.0, y = 0.0;
    std::string tooltip;      // <title>: what a hover shows
    std::string label;        // when not empty, drawn near the marker, clear of every marker, line and
                              // label placed before it (emphasised points first); a leader line joins
                              // a label that had to move away
    bool emphasised = false;  // larger, with a dark ring (the Pareto front, say)
};

struct PlotSeries {
    std::string name;          // legend entry; empty: not in the legend
    std::string color = "#000000";
    Marker marker = Marker::Circle;
    Line line = Line::None;
    bool dashed = false;
    std::vector<PlotPoint> points;  // drawn in this order; lines join them in this order
};

struct PlotOptions {
    std::string title, xTitle, yTitle;
    int width = 720, height = 420;  // the whole picture, legend included
    // On a log y axis, points with y <= 0 are drawn on a separate row below the axis with this
    // label (for example "identical (0)"); when empty they are left out.
    std::string yZeroLabel;
    std::string cssClass = "plot";
};

// The <svg> element. Each marker is a <g class="point"> holding its <title> and its shape, so a
// reader (or a test) can count the points; points a log axis cannot place are left out.
std::string svgPlot(const PlotOptions& options, const Scale& x, const Scale& y, const std::vector<PlotSeries>& series);

}  // namespace vkray::bench
