// SVG plots for report.html (see svg_plot.h): scales and ticks first, then the drawing.
#include "bench/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>

#include "bench/svg_elements.h"

namespace vkray::bench {
namespace {

using svg::kCharWidth, svg::line, svg::num, svg::text;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// {1, 2, 5} x 10^k: the step nearest above `raw`, so that tick labels stay short.
double niceStep(double raw) {
    const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
    const double r = raw / magnitude;
    return (r <= 1.0 ? 1.0 : r <= 2.0 ? 2.0 : r <= 5.0 ? 5.0 : 10.0) * magnitude;
}

// m x 10^k for every m of `mantissas` and every k that can land in [lo, hi], ascending.
std::vector<double> decadeMultiples(double lo, double hi, const std::vector<double>& mantissas) {
    std::vector<double> out;
    const int kLo = int(std::floor(std::log10(lo))) - 1, kHi = int(std::ceil(std::log10(hi))) + 1;
    for (int k = kLo; k <= kHi; ++k)
        for (double m : mantissas) {
            const double v = m * std::pow(10.0, k);
            // The tolerance keeps a tick that sits exactly on an end despite rounding in pow.
            if (v >= lo * (1.0 - 1e-9) && v <= hi * (1.0 + 1e-9)) out.push_back(v);
        }
    return out;
}

// The largest {1, 2, 5} x 10^k at or below v > 0, and the smallest at or above: where a log axis
// ends, so that its ends carry labels.
double niceAtOrBelow(double v) {
    const double decade = std::pow(10.0, std::floor(std::log10(v)));
    for (double m : {5.0, 2.0, 1.0})
        if (m * decade <= v * (1.0 + 1e-9)) return m * decade;
    return 0.5 * decade;  // v just under a power of ten that log10 rounded up
}

double niceAtOrAbove(double v) {
    const double decade = std::pow(10.0, std::floor(std::log10(v)));
    for (double m : {1.0, 2.0, 5.0})
        if (m * decade >= v * (1.0 - 1e-9)) return m * decade;
    return 10.0 * decade;
}

// ---- Drawing ----------------------------------------------------------------------------------

constexpr double kInset = 10.0;     // between the axes and the outermost data, so markers stay clear
constexpr double kZeroRowGap = 24.0;
constexpr double kMarkerRadius = 4.0, kEmphasisedRadius = 6.0;

struct Layout {
    double left, right, top, bottom;  // the area of the data (the log part, when a zero row is drawn)
    double zeroRowY = kNaN;            // the row of y <= 0 on a log y axis; NaN: none
    double axisY;                      // where the x axis is drawn
    double legendX;
};

struct Placed {
    double x, y;
    const PlotPoint* point;
};

Layout layoutFor(const PlotOptions& o, const Scale& y, bool hasLegend, bool hasZeroRow) {
    size_t longest = o.yZeroLabel.size();
    for (double t : y.ticks()) longest = std::max(longest, formatTick(t).size());
    Layout l{};
    l.left = 34.0 + kCharWidth * double(longest);
    l.right = double(o.width) - (hasLegend ? 180.0 : 24.0);
    l.top = o.title.empty() ? 16.0 : 36.0;
    const double belowAxis = 48.0;  // tick labels and the axis title
    l.axisY = double(o.height) - belowAxis;
    l.bottom = hasZeroRow ? l.axisY - kZeroRowGap - 12.0 : l.axisY;
    if (hasZeroRow) l.zeroRowY = l.bottom + kZeroRowGap;
    l.legendX = l.right + 18.0;
    return l;
}

double toPixelX(const Layout& l, const Scale& x, double v) {
    return l.left + kInset + x.unit(v) * (l.right - l.left - 2.0 * kInset);
}

double toPixelY(const Layout& l, const Scale& y, double v) {
    return l.bottom - kInset - y.unit(v) * (l.bottom - l.top - 2.0 * kInset);
}

// Pixel positions of the points the axes can show; the rest are left out.
std::vector<Placed> place(const Layout& l, const Scale& x, const Scale& y, const PlotSeries& s) {
    std::vector<Placed> out;
    for (const PlotPoint& p : s.points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || (x.isLog() && p.x <= 0.0)) continue;
        double py;
        if (y.isLog() && p.y <= 0.0) {
            if (std::isnan(l.zeroRowY)) continue;
            py = l.zeroRowY;
        } else {
            py = toPixelY(l, y, p.y);
        }
        out.push_back({toPixelX(l, x, p.x), py, &p});
    }
    return out;
}

std::string markerShape(Marker m, double x, double y, double r, const std::string& paint) {
    switch (m) {
        case Marker::Circle:
            return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\" " + paint + "/>";
        case Marker::Square:
            return "<rect x=\"" + num(x - 0.9 * r) + "\" y=\"" + num(y - 0.9 * r) + "\" width=\"" + num(1.8 * r) +
                   "\" height=\"" + num(1.8 * r) + "\" " + paint + "/>";
        case Marker::Triangle:
            return "<path d=\"M" + num(x) + " " + num(y - 1.2 * r) + "L" + num(x + 1.1 * r) + " " + num(y + 0.8 * r) +
                   "L" + num(x - 1.1 * r) + " " + num(y + 0.8 * r) + "Z\" " + paint + "/>";
        case Marker::Diamond:
            return "<path d=\"M" + num(x) + " " + num(y - 1.3 * r) + "L" + num(x + 1.1 * r) + " " + num(y) + "L" +
                   num(x) + " " + num(y + 1.3 * r) + "L" + num(x - 1.1 * r) + " " + num(y) + "Z\" " + paint + "/>";
        case Marker::None:
            break;
    }
    return "";
}

std::string strokeAttrs(const PlotSeries& s) {
    return "fill=\"none\" stroke=\"" + escapeXml(s.color) + "\" stroke-width=\"1.8\"" +
           (s.dashed ? " stroke-dasharray=\"6 4\"" : "");
}

std::string seriesLine(const PlotSeries& s, const std::vector<Placed>& pts) {
    if (s.line == Line::None || pts.size() < 2) return "";
    // append, not "L" + ...: GCC 12 warns falsely on that concatenation (-Wrestrict, bug 105329).
    std::string d;
    auto to = [&](char command, double x, double y) { d.append(1, command).append(num(x)).append(" ").append(num(y)); };
    to('M', pts[0].x, pts[0].y);
    for (size_t i = 1; i < pts.size(); ++i) {
        if (s.line == Line::Steps) to('L', pts[i].x, pts[i - 1].y);
        to('L', pts[i].x, pts[i].y);
    }
    return "<path d=\"" + d + "\" " + strokeAttrs(s) + "/>\n";
}

std::string seriesMarkers(const PlotSeries& s, const std::vector<Placed>& pts) {
    if (s.marker == Marker::None) return "";
    std::string out;
    for (const Placed& p : pts) {
        const bool em = p.point->emphasised;
        const std::string paint = "fill=\"" + escapeXml(s.color) + "\"" +
                                  (em ? " stroke=\"#111\" stroke-width=\"1.6\"" : " stroke=\"#fff\" stroke-width=\"0.8\"");
        out += std::string("<g class=\"point") + (em ? " emphasised" : "") + "\"><title>" +
               escapeXml(p.point->tooltip) + "</title>" +
               markerShape(s.marker, p.x, p.y, em ? kEmphasisedRadius : kMarkerRadius, paint) + "</g>\n";
    }
    return out;
}

// ---- Point labels: each beside its marker, clear of every marker and of the labels placed before it.

constexpr double kLabelCharWidth = 5.8;  // of the 10 px labels: a little wide, so boxes do not touch
constexpr double kLabelHeight = 11.0;
constexpr double kLabelGap = 3.0;        // between a marker and the nearest edge of its label
constexpr double kRingStep = 13.0;       // how much further out each ring of candidate places lies

struct Box {
    double x0, y0, x1, y1;
    double overlap(const Box& o) const {
        const double w = std::min(x1, o.x1) - std::max(x0, o.x0), h = std::min(y1, o.y1) - std::max(y0, o.y0);
        return w > 0.0 && h > 0.0 ? w * h : 0.0;
    }
};

double markerRadius(const Placed& p) { return p.point->emphasised ? kEmphasisedRadius : kMarkerRadius; }

size_t glyphs(const std::string& s) {  // UTF-8: count the bytes that start a character
    return size_t(
        std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// The label's box when its nearest edge lies `distance` from the point's centre in direction
// (dx, dy), each of -1, 0, 1: right of the point, above and right of it, and so on.
Box labelBox(const Placed& p, double width, int dx, int dy, double distance) {
    const double d = dx != 0 && dy != 0 ? distance * 0.75 : distance;
    const double cx = p.x + dx * d, cy = p.y + dy * d;
    const double x0 = dx > 0 ? cx : dx < 0 ? cx - width : cx - width / 2.0;
    const double y0 = dy > 0 ? cy : dy < 0 ? cy - kLabelHeight : cy - kLabelHeight / 2.0;
    return {x0, y0, x0 + width, y0 + kLabelHeight};
}

// The candidate places nearest first; among them the first that overlaps nothing, else the one that
// overlaps least. Returns the box and whether it is away from the marker (and needs a leader line).
std::pair<Box, bool> placeLabel(const Placed& p, const Box& area, const std::vector<Box>& taken) {
    static constexpr int kDirections[8][2] = {{1, -1}, {1, 1}, {-1, -1}, {-1, 1}, {1, 0}, {-1, 0}, {0, -1}, {0, 1}};
    const double width = kLabelCharWidth * double(glyphs(p.point->label));
    Box best{};
    bool bestAway = false;
    double bestCost = std::numeric_limits<double>::infinity();
    for (int ring = 0; ring < 7; ++ring)
        for (const auto& [dx, dy] : kDirections) {
            const Box b = labelBox(p, width, dx, dy, markerRadius(p) + kLabelGap + ring * kRingStep);
            double cost = ring * 0.5;  // prefers the nearer of two equally crowded places
            if (b.x0 < area.x0 || b.x1 > area.x1 || b.y0 < area.y0 || b.y1 > area.y1) cost += 1e6;
            for (const Box& t : taken) cost += t.overlap(b);
            if (cost < bestCost) bestCost = cost, best = b, bestAway = ring > 0;
            if (cost == ring * 0.5) return {best, bestAway};
        }
    return {best, bestAway};
}

// The point on the box's edge nearest to (x, y).
std::pair<double, double> nearestOnBox(const Box& b, double x, double y) {
    return {std::clamp(x, b.x0, b.x1), std::clamp(y, b.y0, b.y1)};
}

// A series' line as boxes a label should not cover: one thin box per level or upright segment (a
// step line has only those), small boxes every few pixels along a slanted one.
void addLineObstacles(const PlotSeries& s, const std::vector<Placed>& pts, std::vector<Box>& taken) {
    if (s.line == Line::None) return;
    auto segment = [&](double x0, double y0, double x1, double y1) {
        constexpr double pad = 1.5;
        if (x0 == x1 || y0 == y1) {
            taken.push_back(
                {std::min(x0, x1) - pad, std::min(y0, y1) - pad, std::max(x0, x1) + pad, std::max(y0, y1) + pad});
            return;
        }
        const int n = int(std::ceil(std::hypot(x1 - x0, y1 - y0) / 4.0));
        for (int k = 0; k <= n; ++k) {
            const double x = x0 + (x1 - x0) * k / n, y = y0 + (y1 - y0) * k / n;
            taken.push_back({x - pad, y - pad, x + pad, y + pad});
        }
    };
    for (size_t i = 1; i < pts.size(); ++i) {
        if (s.line == Line::Steps) {
            segment(pts[i - 1].x, pts[i - 1].y, pts[i].x, pts[i - 1].y);
            segment(pts[i].x, pts[i - 1].y, pts[i].x, pts[i].y);
        } else {
            segment(pts[i - 1].x, pts[i - 1].y, pts[i].x, pts[i].y);
        }
    }
}

// Emphasised points are labelled first, so they get the places nearest to them.
std::string pointLabels(const Layout& l, const std::vector<PlotSeries>& series,
                        const std::vector<std::vector<Placed>>& placed) {
    std::vector<Box> taken;  // every marker, then every label as it is placed
    std::vector<const Placed*> labelled;
    for (size_t i = 0; i < series.size(); ++i)
        for (const Placed& p : placed[i]) {
            const double r = markerRadius(p) + 1.0;
            if (series[i].marker != Marker::None) taken.push_back({p.x - r, p.y - r, p.x + r, p.y + r});
            if (!p.point->label.empty()) labelled.push_back(&p);
        }
    for (size_t i = 0; i < series.size(); ++i) addLineObstacles(series[i], placed[i], taken);
    std::stable_sort(labelled.begin(), labelled.end(),
                     [](const Placed* a, const Placed* b) { return a->point->emphasised && !b->point->emphasised; });
    const double bottom = std::isnan(l.zeroRowY) ? l.axisY - 1.0 : l.zeroRowY + kLabelHeight;
    const Box area{l.left + 1.0, l.top - 12.0, l.right + 14.0, bottom};
    std::string out;
    for (const Placed* p : labelled) {
        const auto [box, away] = placeLabel(*p, area, taken);
        taken.push_back(box);
        if (away) {  // a leader line from the marker's edge to the label
            const auto [ex, ey] = nearestOnBox(box, p->x, p->y);
            const double len = std::hypot(ex - p->x, ey - p->y), r = markerRadius(*p) + 1.0;
            if (len > r)
                out += line(p->x + (ex - p->x) * r / len, p->y + (ey - p->y) * r / len, ex, ey,
                            "class=\"leader\" stroke=\"#999\" stroke-width=\"0.7\"");
        }
        out += text(box.x0, box.y1 - 2.0, p->point->label,
                    "class=\"label\" font-size=\"10\" stroke=\"#fff\" stroke-width=\"3\" paint-order=\"stroke\"");
    }
    return out;
}

std::string axes(const PlotOptions& o, const Layout& l, const Scale& x, const Scale& y) {
    std::string out;
    const std::string grid = "stroke=\"#e3e3e3\" stroke-width=\"1\"";
    const std::string ink = "stroke=\"#333\" stroke-width=\"1\"";
    for (double t : x.ticks()) {
        const double px = toPixelX(l, x, t);
        out += line(px, l.top, px, l.bottom, grid);
        out += line(px, l.axisY, px, l.axisY + 5.0, ink);
        out += text(px, l.axisY + 17.0, formatTick(t), "text-anchor=\"middle\"");
    }
    for (double t : y.ticks()) {
        const double py = toPixelY(l, y, t);
        out += line(l.left, py, l.right, py, grid);
        out += line(l.left - 5.0, py, l.left, py, ink);
        out += text(l.left - 8.0, py + 4.0, formatTick(t), "text-anchor=\"end\"");
    }
    if (!std::isnan(l.zeroRowY)) {
        // A row of its own below a gap in the y axis: 0 has no place on a log scale.
        out += line(l.left, l.zeroRowY, l.right, l.zeroRowY, "stroke=\"#bbb\" stroke-dasharray=\"3 3\"");
        out += text(l.left - 8.0, l.zeroRowY + 4.0, o.yZeroLabel, "text-anchor=\"end\"");
    }
    out += line(l.left, l.top, l.left, l.bottom, ink);
    out += line(l.left, l.axisY, l.right, l.axisY, ink);
    out += text((l.left + l.right) / 2.0, double(o.height) - 10.0, o.xTitle, "text-anchor=\"middle\" class=\"axis-title\"");
    const double cy = (l.top + l.bottom) / 2.0;
    out += "<text x=\"14\" y=\"" + num(cy) + "\" transform=\"rotate(-90 14 " + num(cy) +
           ")\" text-anchor=\"middle\" class=\"axis-title\">" + escapeXml(o.yTitle) + "</text>\n";
    return out;
}

std::string legend(const Layout& l, const std::vector<PlotSeries>& series) {
    std::string out;
    double y = l.top + 8.0;
    for (const PlotSeries& s : series) {
        if (s.name.empty()) continue;
        if (s.line != Line::None || s.marker == Marker::None)
            out += line(l.legendX, y, l.legendX + 22.0, y, strokeAttrs(s));
        if (s.marker != Marker::None)
            out += markerShape(s.marker, l.legendX + 11.0, y, kMarkerRadius, "fill=\"" + escapeXml(s.color) + "\"");
        out += text(l.legendX + 30.0, y + 4.0, s.name, "");
        y += 18.0;
    }
    return out;
}

}  // namespace

std::string escapeXml(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;
            default: out += c;
        }
    }
    return out;
}

std::string formatTick(double v) {
    if (v == 0.0) return "0";
    char buf[48];
    const double a = std::abs(v);
    if (a >= 1e6 || a < 1e-4) {
        std::snprintf(buf, sizeof buf, "%.3g", v);
        return buf;
    }
    // Four significant digits, then trailing zeros dropped: 0.3000 -> 0.3, 250.0 -> 250.
    const int decimals = std::max(0, 3 - int(std::floor(std::log10(a))));
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
    std::string s = buf;
    if (s.find('.') != std::string::npos) {
        s.erase(s.find_last_not_of('0') + 1);
        if (s.back() == '.') s.pop_back();
    }
    return s;
}

std::vector<double> niceLinearTicks(double lo, double hi, int target) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
    if (!(hi > lo)) return {lo};
    const double step = niceStep((hi - lo) / double(std::max(1, target - 1)));
    const double first = std::floor(lo / step + 1e-9), last = std::ceil(hi / step - 1e-9);
    std::vector<double> ticks;
    // Multiples of the step computed from integers, so 0.1 + 0.2 noise never reaches a label.
    for (double k = first; k <= last; k += 1.0) ticks.push_back(k == 0.0 ? 0.0 : k * step);
    return ticks;
}

std::vector<double> logTicks(double lo, double hi) {
    if (!(lo > 0.0) || !(hi >= lo) || !std::isfinite(hi)) return {};
    std::vector<double> decades = decadeMultiples(lo, hi, {1.0});
    if (decades.size() >= 3) {
        const size_t stride = (decades.size() + 7) / 8;
        std::vector<double> thinned;
        for (size_t i = 0; i < decades.size(); i += stride) thinned.push_back(decades[i]);
        return thinned;
    }
    if (auto t = decadeMultiples(lo, hi, {1.0, 2.0, 5.0}); t.size() >= 3) return t;
    if (auto t = decadeMultiples(lo, hi, {1, 2, 3, 4, 5, 6, 7, 8, 9}); t.size() >= 2) return t;
    std::vector<double> t = niceLinearTicks(lo, hi, 4);
    std::erase_if(t, [&](double v) { return v < lo || v > hi; });
    return t;
}

Scale::Scale(bool log, double lo, double hi, std::vector<double> ticks)
    : log_(log), lo_(lo), hi_(hi), ticks_(std::move(ticks)) {}

Scale Scale::linear(double lo, double hi) {
    if (!std::isfinite(lo) || !std::isfinite(hi)) lo = 0.0, hi = 1.0;
    if (hi < lo) std::swap(lo, hi);
    if (hi == lo) {
        const double pad = lo == 0.0 ? 1.0 : 0.5 * std::abs(lo);
        lo -= pad;
        hi += pad;
    }
    std::vector<double> ticks = niceLinearTicks(lo, hi);
    return Scale(false, ticks.front(), ticks.back(), ticks);
}

Scale Scale::log(double lo, double hi) {
    if (!(lo > 0.0) || !(hi > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) lo = 1.0, hi = 10.0;
    if (hi < lo) std::swap(lo, hi);
    double a = niceAtOrBelow(lo), b = niceAtOrAbove(hi);
    if (a == b) {  // one value, itself a 1-2-5 value: one step either side
        a = niceAtOrBelow(0.999 * a);
        b = niceAtOrAbove(1.001 * b);
    }
    return Scale(true, a, b, logTicks(a, b));
}

Scale Scale::linearFor(const std::vector<double>& values, bool includeZero) {
    std::vector<double> v;
    for (double x : values)
        if (std::isfinite(x)) v.push_back(x);
    if (includeZero) v.push_back(0.0);
    if (v.empty()) return linear(0.0, 1.0);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return linear(*lo, *hi);
}

Scale Scale::logFor(const std::vector<double>& values) {
    std::vector<double> v;
    for (double x : values)
        if (std::isfinite(x) && x > 0.0) v.push_back(x);
    if (v.empty()) return log(1.0, 10.0);
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return log(*lo, *hi);
}

double Scale::unit(double v) const {
    if (!log_) return (v - lo_) / (hi_ - lo_);
    if (!(v > 0.0)) return kNaN;
    return (std::log10(v) - std::log10(lo_)) / (std::log10(hi_) - std::log10(lo_));
}

bool Scale::contains(double v) const {
    const double u = unit(v);
    return u >= -1e-9 && u <= 1.0 + 1e-9;  // NaN fails both
}

Scale& Scale::withTicks(std::vector<double> ticks) {
    std::erase_if(ticks, [&](double t) { return !contains(t); });
    ticks_ = std::move(ticks);
    return *this;
}

std::string svgPlot(const PlotOptions& o, const Scale& x, const Scale& y, const std::vector<PlotSeries>& series) {
    const bool hasLegend = std::any_of(series.begin(), series.end(), [](const PlotSeries& s) { return !s.name.empty(); });
    bool hasZeroRow = false;
    if (y.isLog() && !o.yZeroLabel.empty())
        for (const PlotSeries& s : series)
            for (const PlotPoint& p : s.points) hasZeroRow = hasZeroRow || (std::isfinite(p.y) && p.y <= 0.0);
    const Layout l = layoutFor(o, y, hasLegend, hasZeroRow);

    std::vector<std::vector<Placed>> placed;
    for (const PlotSeries& s : series) placed.push_back(place(l, x, y, s));

    std::string out = "<svg class=\"" + escapeXml(o.cssClass) + "\" viewBox=\"0 0 " + std::to_string(o.width) + " " +
                      std::to_string(o.height) + "\" width=\"" + std::to_string(o.width) + "\" height=\"" +
                      std::to_string(o.height) + "\" role=\"img\" aria-label=\"" + escapeXml(o.title) +
                      "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    out += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
    if (!o.title.empty()) out += text(l.left, 22.0, o.title, "font-size=\"13\" font-weight=\"bold\"");
    out += axes(o, l, x, y);
    // Lines under markers, labels on top, so neither hides a point.
    for (size_t i = 0; i < series.size(); ++i) out += seriesLine(series[i], placed[i]);
    for (size_t i = 0; i < series.size(); ++i) out += seriesMarkers(series[i], placed[i]);
    out += pointLabels(l, series, placed);
    out += legend(l, series);
    out += "</svg>\n";
    return out;
}

}  // namespace vkray::bench
