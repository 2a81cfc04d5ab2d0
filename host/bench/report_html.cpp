// report.html: one self-contained HTML5 file (report.h). The tables are report_tables.h's, the
// plots report_plots.h's inline SVG, the pictures PNG data URIs; the style sheet is inline, there is
// no script and no URL, so the page works offline, attached to a mail or opened from a CI artifact.
#include <algorithm>
#include <cctype>
#include <optional>
#include <string>

#include "bench/bench_resume.h"
#include "bench/report.h"
#include "bench/report_images.h"
#include "bench/report_plots.h"
#include "bench/report_tables.h"
#include "bench/svg_plot.h"

namespace vkray::bench {
namespace {

constexpr const char* kStyle = R"(
body { font: 14px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; color: #222; max-width: 1360px;
       margin: 1.5em auto; padding: 0 1em; }
h1 { font-size: 1.7em; margin-bottom: .3em; }
h2 { margin-top: 2.2em; border-bottom: 2px solid #ddd; padding-bottom: .2em; }
h3 { margin: 1.6em 0 .4em; }
h4 { margin: 1em 0 .3em; font-family: ui-monospace, monospace; }
nav a { margin-right: 1em; }
.scroll { overflow-x: auto; overflow-y: hidden; max-width: 100%;
          background: linear-gradient(to right, #fff 40%, rgba(255,255,255,0)) left / 32px 100% no-repeat local,
                      linear-gradient(to left, #fff 40%, rgba(255,255,255,0)) right / 32px 100% no-repeat local,
                      linear-gradient(to right, rgba(0,0,0,.18), rgba(0,0,0,0)) left / 10px 100% no-repeat scroll,
                      linear-gradient(to left, rgba(0,0,0,.18), rgba(0,0,0,0)) right / 10px 100% no-repeat scroll; }
table { border-collapse: collapse; font-size: 13px; margin: .3em 0; }
th, td { border: 1px solid #d8d8d8; padding: 3px 6px; vertical-align: top; }
thead th { background: #f3f3f3; text-align: left; }
td.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
td.num .spread { display: block; color: #666; font-size: 11px; }
td:first-child { white-space: nowrap; }
tr.marked td { background: #fff4c8; font-weight: 600; }
table.facts th, table.facts td { border: none; padding: 1px 12px 1px 0; background: none; text-align: left; }
table.facts th { color: #555; font-weight: 600; white-space: nowrap; }
table.facts td { overflow-wrap: anywhere; }
.plots { display: flex; flex-wrap: wrap; gap: 14px; }
.notes { color: #555; font-size: 12px; margin: .3em 0 1em; padding-left: 1.2em; }
.verdict { background: #eef4fc; border-left: 4px solid #3b7dd8; padding: .5em .9em; }
.warning { background: #fdf0e6; border-left: 4px solid #d55e00; padding: .5em .9em; margin: .5em 0; }
.missing { color: #777; font-style: italic; }
.incomplete { background: #fbe3e4; border: 2px solid #b2182b; padding: .6em .9em; margin: .5em 0; }
.images { display: flex; flex-wrap: wrap; gap: 14px; align-items: flex-start; }
.pair { display: flex; gap: 14px; align-items: flex-start; }
figure { margin: 0; }
figcaption { font-size: 12px; color: #444; }
figure.scale { max-width: 360px; }
img.px { image-rendering: crisp-edges; image-rendering: pixelated; max-width: 100%; height: auto;
         border: 1px solid #ccc; display: block; }
svg.plot { max-width: 100%; height: auto; border: 1px solid #e4e4e4; }
svg .label { fill: #222; }
svg .axis-title { fill: #333; font-size: 12px; }
)";

// Small pictures are shown at a whole multiple of their size (about 256 px wide), so a 64x48
// render stays sharp and visible; large ones at their own size.
int displayScale(int width) { return width > 0 ? std::max(1, 256 / width) : 1; }

std::string factTable(const Facts& facts) {
    std::string out = "<table class=\"facts\">\n";
    for (const auto& [label, value] : facts)
        out += "<tr><th>" + escapeXml(label) + "</th><td>" + escapeXml(value) + "</td></tr>\n";
    return out + "</table>\n";
}

// A number cell; "12.3 (11.9–13.0)", a median with its spread, shows the spread on a line of its own
// below, so the wide tables stay narrow enough for a laptop's screen.
std::string numberCell(const std::string& cell) {
    const size_t open = cell.find(" (");
    if (open == std::string::npos || cell.back() != ')' || cell.find("–", open) == std::string::npos)
        return escapeXml(cell);
    return escapeXml(cell.substr(0, open)) + " <span class=\"spread\">" + escapeXml(cell.substr(open + 1)) + "</span>";
}

// A column title may break after a slash followed by a word ("triangles/ray", not "Mrays/s"), so
// narrow columns stay narrow.
std::string headerCell(const std::string& title) {
    const std::string t = escapeXml(title);
    std::string out;
    for (size_t i = 0; i < t.size(); ++i) {
        out += t[i];
        const bool word = i + 2 < t.size() && std::isalpha(static_cast<unsigned char>(t[i + 2]));
        if (t[i] == '/' && word) out += "<wbr>";
    }
    return out;
}


const ReportImage* findImage(const std::vector<ReportImage>& images, size_t scene, const std::string& accel,
                             ImageRole role) {
    for (const ReportImage& im : images)
        if (im.scene == scene && im.accel == accel && im.role == role) return &im;
    return nullptr;
}

std::string figure(const ReportImage* im, const std::string& caption, const std::string& missing) {
    if (!im) return "<figure><p class=\"missing\">" + escapeXml(missing) + "</p></figure>\n";
    const int w = im->width * displayScale(im->width);
    return "<figure><img class=\"px\" width=\"" + std::to_string(w) + "\" alt=\"" + escapeXml(caption) +
           "\" src=\"data:image/png;base64," + base64(im->png) + "\"><figcaption>" + escapeXml(caption) + " (" +
           std::to_string(im->width) + "x" + std::to_string(im->height) + ")</figcaption></figure>\n";
}

// The colour bar of one kind of heatmap with its caption; empty when no accelerator has its counts.
std::string colourBar(const SceneResult& s, HeatmapRays rays, const std::string& what) {
    const HeatmapScale scale = heatmapScale(s, rays);
    if (!scale.any) return "";
    return "<figure class=\"scale\">" + colourBarSvg(scale) + "<figcaption>Nodes visited per pixel by " + what +
           ", one scale for every accelerator of this scene: 0 to " + formatTick(scale.max) +
           ", the 99th percentile of all their pixels (largest: " + std::to_string(scale.largest) +
           "); brighter pixels share the top colour.</figcaption></figure>\n";
}

std::string imagesSection(const SceneResult& s, size_t si, const std::vector<ReportImage>& images) {
    std::string out = "<h3>Images</h3>\n";
    out += "<p>Each accelerator's render, its difference from the reference (dark grey: identical; blue: within "
           "2/255; red to yellow: larger errors, yellow the largest), and two heatmaps side by side: the nodes "
           "visited by all rays of each pixel (camera, shadow, reflected and refracted rays: a mirror or glass "
           "object lights up where its pixels trace many rays), and by the camera ray alone (the walk the "
           "camera-ray rates above time). Each kind of heatmap has a scale of its own.</p>\n";
    // The colour bars beside the reference, above the heatmaps they read.
    out += "<div class=\"images\">" +
           figure(findImage(images, si, "", ImageRole::Reference),
                  "reference: CPU, double precision (" + s.referenceAccel + ")", "no reference image") +
           colourBar(s, HeatmapRays::All, "all rays") + colourBar(s, HeatmapRays::Camera, "camera rays") + "</div>\n";
    for (const AccelResult& a : s.accels) {
        // Two pairs, each in a box of its own: a window too narrow for all four wraps between the
        // pairs, so the render stays beside its difference and the two heatmaps side by side.
        out += "<h4>" + escapeXml(a.accel) + "</h4>\n<div class=\"images\">\n<div class=\"pair\">\n";
        out += figure(findImage(images, si, a.accel, ImageRole::Render), a.accel + ": render", "no render");
        out += figure(findImage(images, si, a.accel, ImageRole::Difference), a.accel + ": difference",
                      "no difference image");
        out += "</div>\n<div class=\"pair\">\n";
        out += figure(findImage(images, si, a.accel, ImageRole::Heatmap), a.accel + ": nodes per pixel, all rays",
                      "no per-pixel counts");
        out += figure(findImage(images, si, a.accel, ImageRole::PrimaryHeatmap),
                      a.accel + ": nodes per pixel, camera rays", "no per-pixel counts of camera rays");
        out += "</div></div>\n";
    }
    return out;
}

// A plot, or the sentence that says why there is none.
std::string plotOrReason(const std::string& svg, const std::string& reason) {
    return svg.empty() ? "<p class=\"missing\">" + escapeXml(reason) + "</p>\n" : "<figure>" + svg + "</figure>\n";
}

std::string scalingReason(const SceneResult& s) {
    const std::vector<int> counts = buildThreadCounts(s);
    if (counts.empty()) return "No scaling plot: no build timings were measured.";
    return "No scaling plot: the builds ran at one thread count only (" + std::to_string(counts.front()) +
           (counts.front() == 1 ? " thread" : " threads") + "), so there is nothing to scale against.";
}

std::string sceneSection(const SceneResult& s, size_t si, const std::vector<ReportImage>& images) {
    std::string out = "<section id=\"scene-" + std::to_string(si + 1) + "\">\n<h2>" + escapeXml(s.name) + "</h2>\n";
    out += factTable(sceneFacts(s));
    out += "<p class=\"verdict\"><strong>Who wins:</strong> " + escapeXml(whoWins(s)) + "</p>\n";
    out += htmlTable(acceleratorTable(s));
    out += htmlTable(embreeTable(s));
    out += plotOrReason(cameraRayChartSvg(s), "No camera-ray chart: no accelerator has a camera-ray rate.");
    out += imagesSection(s, si, images);
    out += htmlTable(buildScalingTable(s));
    out += plotOrReason(scalingPlotSvg(s), scalingReason(s));
    out += htmlTable(concurrentBuildTable(s));
    out += htmlTable(deltaSweepTable(s));
    if (!s.deltas.empty()) out += "<div class=\"plots\">" + deltaPlotSvg(s) + "</div>\n";
    out += htmlTable(errorTable(s));
    if (!s.errorPoints.empty())
        out += "<p>Every point is labelled with its configuration; hover over one for its figures. Emphasised "
               "points, joined by the step line, are on the Pareto front; configurations identical to the "
               "reference sit on the row below the axis.</p>\n" +
               plotOrReason(errorPlotSvg(s), "");
    return out + "</section>\n";
}

std::string warnings(const BenchResults& r) {
    std::string out;
    for (const std::string& w : runWarnings(r))
        out += "<p class=\"warning\"><strong>Warning:</strong> " + escapeXml(w) + "</p>\n";
    return out;
}

// The summary across scenes, when the run has one (report_tables.h).
std::string summarySection(const BenchResults& r) {
    const std::optional<Table> t = summaryTable(r);
    if (!t) return "";
    return "<section id=\"summary\">\n<h2>Summary</h2>\n" + htmlTable(*t) + "</section>\n";
}

std::string sceneLinks(const BenchResults& r) {
    if (r.scenes.size() < 2) return "";
    std::string out = "<nav>";
    if (summaryTable(r)) out += "<a href=\"#summary\">Summary</a> ";
    out += "Scenes: ";
    for (size_t i = 0; i < r.scenes.size(); ++i)
        out += "<a href=\"#scene-" + std::to_string(i + 1) + "\">" + escapeXml(r.scenes[i].name) + "</a>";
    return out + "</nav>\n";
}

}  // namespace

std::string htmlTable(const Table& t) {
    std::string out = "<h3>" + escapeXml(t.title) + "</h3>\n";
    if (t.rows.empty()) return out + "<p class=\"missing\">" + escapeXml(t.whenEmpty) + "</p>\n";
    auto isNumeric = [&](size_t i) { return i < t.numeric.size() && t.numeric[i]; };
    out += "<div class=\"scroll\"><table>\n<thead><tr>";
    for (const std::string& c : t.columns) out += "<th>" + headerCell(c) + "</th>";
    out += "</tr></thead>\n<tbody>\n";
    for (size_t r = 0; r < t.rows.size(); ++r) {
        out += r < t.marked.size() && t.marked[r] ? "<tr class=\"marked\">" : "<tr>";
        for (size_t i = 0; i < t.rows[r].size(); ++i)
            out += isNumeric(i) ? "<td class=\"num\">" + numberCell(t.rows[r][i]) + "</td>"
                                : "<td>" + escapeXml(t.rows[r][i]) + "</td>";
        out += "</tr>\n";
    }
    out += "</tbody>\n</table></div>\n";
    if (!t.notes.empty()) {
        out += "<ul class=\"notes\">\n";
        for (const std::string& n : t.notes) out += "<li>" + escapeXml(n) + "</li>\n";
        out += "</ul>\n";
    }
    return out;
}

std::string benchHtml(const BenchResults& results, const std::vector<ReportImage>& images) {
    std::string out = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
                      "<title>vkray bench: " + escapeXml(results.device) + "</title>\n<style>" + kStyle +
                      "</style>\n</head>\n<body>\n<h1>vkray bench</h1>\n";
    if (!results.complete())
        out += "<p class=\"incomplete\"><strong>Incomplete:</strong> " + escapeXml(incompleteNotice(results)) + "</p>\n";
    out += factTable(runFacts(results));
    out += warnings(results);
    out += shardsHtml(results);  // a merged report's shards, right after the run's facts
    out += sceneLinks(results);
    out += summarySection(results);
    if (results.scenes.empty()) out += "<p class=\"missing\">No scene was run.</p>\n";
    for (size_t i = 0; i < results.scenes.size(); ++i) out += sceneSection(results.scenes[i], i, images);
    return out + "</body>\n</html>\n";
}

std::string benchHtml(const BenchResults& results) { return benchHtml(results, reportImages(results)); }

}  // namespace vkray::bench
