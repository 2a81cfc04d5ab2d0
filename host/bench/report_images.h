// The pictures of a bench report, encoded once as PNG and used twice: as data URIs in report.html
// and as files in images/ (report.h). Internal to host/bench.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "bench/bench_results.h"

namespace vkray::bench {

// Heatmap: nodes visited by all rays of each pixel; PrimaryHeatmap: by its camera ray alone.
enum class ImageRole { Reference, Render, Difference, Heatmap, PrimaryHeatmap };

struct ReportImage {
    size_t scene = 0;       // index into BenchResults::scenes
    std::string accel;      // empty for the reference
    ImageRole role = ImageRole::Reference;
    std::string fileName;   // unique in the report: "<scene>_<accel>_diff.png"
    int width = 0, height = 0;
    std::vector<unsigned char> png;
};

// The per-pixel counts a heatmap shows: of all rays of each pixel (AccelResult::nodesPerPixel) or of
// its camera ray alone (primaryNodesPerPixel).
enum class HeatmapRays { All, Camera };
const std::vector<uint32_t>& heatmapCounts(const AccelResult& accel, HeatmapRays rays);

// The shared heatmap scale of one scene and kind of heatmap, so accelerators compare: the 99th
// percentile of every accelerator's nodes per pixel (one outlier pixel cannot wash out the
// picture), at least 1. Each kind has its own: all rays count several times what camera rays do.
struct HeatmapScale {
    double max = 1.0;        // the top of the colour bar
    uint32_t largest = 0;    // the largest value of any pixel, for the caption
    bool any = false;        // some accelerator has per-pixel counts
};
HeatmapScale heatmapScale(const SceneResult& scene, HeatmapRays rays = HeatmapRays::All);

// The value below which p percent of the values lie (nearest rank); 0 for no values.
uint32_t percentile(std::vector<uint32_t> values, double p);

// Per scene: the reference, then per accelerator its render, its difference image and its
// traversal-cost heatmaps (all rays, camera rays). Images that are empty or malformed are left out (the HTML says so).
std::vector<ReportImage> reportImages(const BenchResults& results);

// RFC 4648 base64 with padding, for data URIs.
std::string base64(const std::vector<unsigned char>& bytes);

// report.html with images already encoded by reportImages (writeBenchReport encodes them once
// for both the page and images/); benchHtml(results) is this with reportImages(results).
std::string benchHtml(const BenchResults& results, const std::vector<ReportImage>& images);

}  // namespace vkray::bench
