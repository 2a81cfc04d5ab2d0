// The inline SVG plots of report.html, one function per plot, each from one scene's results.
// Internal to host/bench.
#pragma once

#include <string>

#include "bench/bench_results.h"
#include "bench/report_images.h"

namespace vkray::bench {

// Error against run time: x = build + trace ms (log), y = RMSE (log; 0 on an "identical (0)" row
// below the axis), one colour and marker per group, the Pareto front joined by a step line and
// emphasised, every point labelled with its configuration (svg_plot.h keeps the labels apart) and
// with a tooltip. Empty when the scene has no error points.
std::string errorPlotSvg(const SceneResult& scene);

// Build speed-up against threads, one line per accelerator, the ideal linear speed-up dashed.
// Empty when fewer than two thread counts were measured.
std::string scalingPlotSvg(const SceneResult& scene);

// Build and trace ms against the AAC delta (as in Figure 5.1 of A. F. Mahmuda, "Bounding Volume Hierarchy
// Construction Using Agglomerative Clustering for Faster Ray Tracing", 2017): two plots side by side,
// build and trace, each on a y axis of its own (a build can be a thousandth of a trace: on one axis
// it would lie flat on zero). Empty without a sweep.
std::string deltaPlotSvg(const SceneResult& scene);

// Camera rays per accelerator: one bar per accelerator of its camera-ray Mrays/s (median, the min–max
// of its runs as an error bar, the rate and its ratio to Embree written beside it), BVHs and kd
// traversals in colours of their own, and Embree rtcIntersect1 and rtcIntersect16 on the same rays
// as reference lines with their spreads as whiskers above the bars. Empty when no accelerator has a camera-ray rate.
std::string cameraRayChartSvg(const SceneResult& scene);

// The heatmap's colour bar with its numbers, 0 to scale.max.
std::string colourBarSvg(const HeatmapScale& scale);

}  // namespace vkray::bench
