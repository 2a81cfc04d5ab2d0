// bench.json both ways: the writer of report.h with the report's image file names, and the reader
// `vkray bench --merge` uses (bench_merge.h). Internal to host/bench.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_results.h"
#include "bench/report_images.h"

namespace vkray::bench {

// bench.json naming each picture's file in images/ (and, in a report that keeps its pixels, the
// PFM beside each: pixelsFileName).
std::string benchJson(const BenchResults& results, const std::vector<ReportImage>& images);

// What a picture "<x>.png" is drawn from, as a PFM "<x>.pfm" beside it: a render's or difference
// image's linear floats, a heatmap's nodes per pixel (1 channel, exact below 2^24).
std::string pixelsFileName(const std::string& pngFileName);

// Whether a report keeps its pictures' pixels, so that a merge can draw them again exactly (and
// the heatmaps of a scene on one scale), and `--resume` its finished scenes' pictures (bench_resume.h):
// the reports of `--shard I/N` with N > 1, and incomplete ones.
inline bool keepsPixels(const BenchResults& r) { return r.shard.count > 1 || !r.complete(); }

// Reads DIR/bench.json (and the pixels it names under DIR/images/, where it kept them) back into the
// results it was written from: every figure, and the images a report shows. Throws vkray::Error
// naming the file and what is wrong with it (missing, not JSON, a key missing or of the wrong type).
BenchResults readBenchReport(const std::filesystem::path& dir);

}  // namespace vkray::bench
