// report.html's plots (see report_plots.h), drawn with svg_plot.h.
#include "bench/report_plots.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "bench/colormap.h"
#include "bench/report_tables.h"
#include "bench/svg_bar_chart.h"
#include "bench/svg_plot.h"

namespace vkray::bench {
namespace {

// Okabe and Ito's colour-blind-safe palette (its yellow left out: too pale on white).
const std::vector<std::string> kPalette = {"#0072B2", "#E69F00", "#009E73", "#D55E00", "#CC79A7", "#56B4E9", "#000000"};
const std::vector<Marker> kMarkers = {Marker::Circle, Marker::Square, Marker::Triangle, Marker::Diamond};

std::string paletteColor(size_t i) { return kPalette[i % kPalette.size()]; }
Marker paletteMarker(size_t i) { return kMarkers[i % kMarkers.size()]; }

// Every field given (GCC's -Wmissing-field-initializers flags designated initializers that leave
// some out).
PlotSeries series(std::string name, std::string color, Marker marker, Line line, bool dashed = false) {
    return {std::move(name), std::move(color), marker, line, dashed, {}};
}

PlotPoint point(double x, double y, std::string tooltip = {}, std::string label = {}, bool emphasised = false) {
    return {x, y, std::move(tooltip), std::move(label), emphasised};
}

PlotOptions plotOptions(std::string title, std::string xTitle, std::string yTitle, int width, int height,
                        std::string cssClass) {
    PlotOptions o;
    o.title = std::move(title);
    o.xTitle = std::move(xTitle);
    o.yTitle = std::move(yTitle);
    o.width = width;
    o.height = height;
    o.cssClass = std::move(cssClass);
    return o;
}

std::string errorTooltip(const ErrorPoint& p) {
    std::string s = p.label + " (" + p.group + "): " + p.precision;
    if (p.maxDepth > 0) s += ", maxdepth " + std::to_string(p.maxDepth);
    s += "\ntotal " + formatNumber(p.totalMs()) + " ms (build " + formatNumber(p.buildMs) + " + trace " +
         formatNumber(p.traceMs) + ")\nRMSE " + formatRmse(p.error.rmse) + ", PSNR " + formatPsnr(p.error.psnr) +
         (p.error.psnr ? " dB" : "") + ", primary mismatch " + formatPercent(p.error.primaryMismatch);
    if (p.pareto) s += "\non the Pareto front";
    return s;
}

// The front as a staircase from the fastest point to the most accurate one.
PlotSeries paretoFrontSeries(const std::vector<ErrorPoint>& points) {
    std::vector<const ErrorPoint*> front;
    for (const ErrorPoint& p : points)
        if (p.pareto) front.push_back(&p);
    std::sort(front.begin(), front.end(), [](const ErrorPoint* a, const ErrorPoint* b) {
        return a->totalMs() != b->totalMs() ? a->totalMs() < b->totalMs() : a->error.rmse > b->error.rmse;
    });
    PlotSeries s = series("Pareto front", "#555555", Marker::None, Line::Steps);
    for (const ErrorPoint* p : front) s.points.push_back(point(p->totalMs(), p->error.rmse));
    return s;
}

}  // namespace

std::string errorPlotSvg(const SceneResult& scene) {
    if (scene.errorPoints.empty()) return "";
    std::vector<PlotSeries> plotted{paretoFrontSeries(scene.errorPoints)};
    std::map<std::string, size_t> seriesOfGroup;
    std::vector<double> times, errors;
    for (const ErrorPoint& p : scene.errorPoints) {
        auto [it, added] = seriesOfGroup.try_emplace(p.group, plotted.size());
        if (added) {
            const size_t k = seriesOfGroup.size() - 1;  // groups in order of first appearance
            plotted.push_back(series(p.group, paletteColor(k), paletteMarker(k), Line::None));
        }
        plotted[it->second].points.push_back(point(p.totalMs(), p.error.rmse, errorTooltip(p), p.label, p.pareto));
        times.push_back(p.totalMs());
        errors.push_back(p.error.rmse);
    }
    PlotOptions options = plotOptions("Error against run time", "build + trace time, ms (log scale)",
                                      "RMSE against the reference (log scale)", 960, 520, "plot error-plot");
    options.yZeroLabel = "identical (0)";
    return svgPlot(options, Scale::logFor(times), Scale::logFor(errors), plotted);
}

std::string scalingPlotSvg(const SceneResult& scene) {
    const std::vector<int> counts = buildThreadCounts(scene);
    if (counts.size() < 2) return "";
    const int base = counts.front(), most = counts.back();
    PlotSeries ideal = series("ideal (linear)", "#999999", Marker::None, Line::Straight, true);
    ideal.points = {point(double(base), 1.0), point(double(most), double(most) / double(base))};
    std::vector<PlotSeries> plotted{ideal};
    std::vector<double> speedups{1.0, double(most) / double(base)};
    for (const AccelResult& a : scene.accels) {
        if (a.build.empty() || a.buildOnDevice) continue;  // the driver's build on the device: no CPU threads
        const size_t k = plotted.size() - 1;
        PlotSeries s = series(a.accel, paletteColor(k), paletteMarker(k), Line::Straight);
        for (const ThreadTiming& t : a.build) {
            const std::optional<double> up = buildSpeedup(a, base, t.threads);
            if (!up) continue;
            s.points.push_back(point(double(t.threads), *up,
                                     a.accel + ", " + std::to_string(t.threads) + " threads: " + formatSpread(t.ms) +
                                         " ms, " + formatRatio(*up)));
            speedups.push_back(*up);
        }
        plotted.push_back(std::move(s));
    }
    const PlotOptions options =
        plotOptions("Build scaling", "threads",
                    "speed-up over " + std::to_string(base) + (base == 1 ? " thread" : " threads"), 640, 380,
                    "plot scaling-plot");
    Scale x = Scale::linear(double(base), double(most));
    x.withTicks(std::vector<double>(counts.begin(), counts.end()));
    return svgPlot(options, x, Scale::linearFor(speedups, true), plotted);
}

namespace {

// One panel of the delta sweep: one time against delta, on an axis of its own.
std::string deltaPanel(const std::vector<DeltaResult>& deltas, const char* what, Spread DeltaResult::*ms, size_t colour,
                       Marker marker) {
    PlotSeries s = series("", paletteColor(colour), marker, Line::Straight);
    std::vector<double> xs, ys;
    for (const DeltaResult& d : deltas) {
        const Spread& t = d.*ms;
        s.points.push_back(point(double(d.delta), t.median,
                                 "delta " + std::to_string(d.delta) + ": " + what + " " + formatSpread(t) + " ms"));
        xs.push_back(double(d.delta));
        ys.push_back(t.median);
    }
    const PlotOptions options = plotOptions(std::string("AAC delta sweep: ") + what + " time",
                                            "delta (AAC leaf-range size)", std::string(what) + " ms (medians)", 560,
                                            340, std::string("plot delta-plot delta-") + what);
    return svgPlot(options, Scale::linearFor(xs, false), Scale::linearFor(ys, false), {s});
}

}  // namespace

std::string deltaPlotSvg(const SceneResult& scene) {
    if (scene.deltas.empty()) return "";
    std::vector<DeltaResult> deltas = scene.deltas;
    std::sort(deltas.begin(), deltas.end(), [](const DeltaResult& a, const DeltaResult& b) { return a.delta < b.delta; });
    return deltaPanel(deltas, "build", &DeltaResult::buildMs, 0, Marker::Circle) +
           deltaPanel(deltas, "trace", &DeltaResult::traceMs, 1, Marker::Square);
}

namespace {

// Camera-ray Mrays/s of `rays` traced in the median of `ms`, with the spread of the rates: the
// fastest run gives the highest rate.
Bar rateBar(double rays, const Spread& ms) {
    Bar b;
    b.value = mraysPerSecond(rays, ms.median).value_or(0.0);
    b.low = mraysPerSecond(rays, ms.max).value_or(b.value);
    b.high = mraysPerSecond(rays, ms.min).value_or(b.value);
    return b;
}

std::string rateSpreadText(const Bar& b) {
    return formatNumber(b.value) + " Mrays/s (" + formatNumber(b.low) + "–" + formatNumber(b.high) + ")";
}

ReferenceLine embreeLine(const std::string& name, double rays, const Spread& ms, std::string color, bool dashed) {
    const Bar b = rateBar(rays, ms);
    return {name + ": " + rateSpreadText(b), b.value, b.low, b.high, std::move(color), dashed};
}

}  // namespace

std::string cameraRayChartSvg(const SceneResult& scene) {
    const double rays = double(scene.width) * double(scene.height);
    const std::string bvhColour = paletteColor(0), kdColour = paletteColor(1), otherColour = "#999999";
    std::vector<Bar> bars;
    bool bvh = false, kd = false, other = false;
    for (const AccelResult& a : scene.accels) {
        if (!a.primaryMrays()) continue;
        Bar b = rateBar(rays, a.primaryOnlyMs);
        b.value = *a.primaryMrays();
        b.label = a.accel;
        const std::optional<double> overEmbree = primaryVsEmbree(scene, a);
        b.valueText = formatNumber(b.value) + (overEmbree ? " · " + formatRatio(*overEmbree) + " Embree" : "");
        b.tooltip = a.accel + ": camera rays " + rateSpreadText(b) + ", " + formatSpread(a.primaryOnlyMs) + " ms" +
                    (overEmbree ? ", " + formatRatio(*overEmbree) + " Embree rtcIntersect1" : "");
        const std::optional<accel::Family> family = familyOf(a.accel);
        b.color = family == accel::Family::Bvh ? bvhColour : family == accel::Family::Kd ? kdColour : otherColour;
        bvh = bvh || b.color == bvhColour;
        kd = kd || b.color == kdColour;
        other = other || b.color == otherColour;
        bars.push_back(std::move(b));
    }
    if (bars.empty()) return "";
    BarChartOptions o;
    o.title = "Camera rays: Mrays/s per accelerator";
    o.xTitle = "camera rays, Mrays/s (bars and lines: medians; error bars and whiskers: min–max of the runs)";
    o.width = 900;
    if (bvh) o.swatches.emplace_back("BVH", bvhColour);
    if (kd) o.swatches.emplace_back("kd-tree", kdColour);
    if (other) o.swatches.emplace_back("other", otherColour);
    std::vector<ReferenceLine> refs;
    const EmbreeResult& e = scene.embree;
    if (!e.version.empty()) {
        refs.push_back(embreeLine(e.version + " rtcIntersect1", rays, e.singleMs, "#222222", true));
        refs.push_back(embreeLine(e.version + " rtcIntersect16", rays, e.packetMs, "#009E73", true));
    }
    return svgBarChart(o, bars, refs);
}

std::string colourBarSvg(const HeatmapScale& scale) {
    constexpr int kSteps = 64;
    constexpr double kLeft = 12.0, kWidth = 320.0, kTop = 4.0, kHeight = 16.0;
    std::string out = "<svg class=\"colour-bar\" viewBox=\"0 0 360 44\" width=\"360\" height=\"44\" role=\"img\" "
                      "aria-label=\"colour bar, nodes per pixel\" font-family=\"sans-serif\" font-size=\"11\">\n";
    auto num = [](double v) { return formatTick(std::round(v * 10.0) / 10.0); };
    for (int i = 0; i < kSteps; ++i)
        out += "<rect x=\"" + num(kLeft + kWidth * i / kSteps) + "\" y=\"" + num(kTop) + "\" width=\"" +
               num(kWidth / kSteps + 0.5) + "\" height=\"" + num(kHeight) + "\" fill=\"" +
               cssColor(viridis((i + 0.5) / kSteps)) + "\"/>\n";
    std::vector<double> ticks = niceLinearTicks(0.0, scale.max, 5);
    // The end is labelled on its own ("≥ max": brighter pixels share the top colour), so drop a
    // nice tick that would sit on top of that label. Counts are whole numbers: no tick at 0.5.
    std::erase_if(ticks, [&](double t) { return t > 0.85 * scale.max || t != std::floor(t); });
    ticks.push_back(scale.max);
    for (double t : ticks) {
        const double x = kLeft + kWidth * t / scale.max;
        const std::string label = (t == scale.max ? "≥ " : "") + formatTick(t);
        out += "<line x1=\"" + num(x) + "\" y1=\"" + num(kTop + kHeight) + "\" x2=\"" + num(x) + "\" y2=\"" +
               num(kTop + kHeight + 4.0) + "\" stroke=\"#333\"/>\n";
        out += "<text x=\"" + num(x) + "\" y=\"" + num(kTop + kHeight + 16.0) + "\" text-anchor=\"middle\">" +
               escapeXml(label) + "</text>\n";
    }
    return out + "</svg>\n";
}

}  // namespace vkray::bench
