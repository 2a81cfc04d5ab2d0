// Writers of `vkray bench`'s output folder: bench.json (every figure, machine-readable),
// bench.md (the tables), report.html (self-contained: images as data URIs, plots as inline SVG, no
// network access, no external assets) and images/ (the same pictures as PNG files).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_results.h"

namespace vkray::bench {

std::string benchJson(const BenchResults& results);
std::string benchMarkdown(const BenchResults& results);
std::string benchHtml(const BenchResults& results);

// What may make the run's figures unreliable, one sentence each, for the console (as warnings),
// bench.md, report.html and bench.json: fewer than 3 repeats, and a 1-minute load average above the
// machine's cores at the start or the end of the run (of a merged report: of any shard).
std::vector<std::string> runWarnings(const BenchResults& results);

// The console summary `vkray bench` prints: the device, then per scene Embree's camera-ray rates and
// one line per accelerator (build, trace, rates, the ratios to Embree and to bvh).
std::string benchSummary(const BenchResults& results);

// Writes all of the above into `dir` (created if missing); a vkray::Error names a file that cannot
// be written.
void writeBenchReport(const BenchResults& results, const std::filesystem::path& dir);

// Marks ErrorPoint::pareto: a point is on the front when no other point has both a total time and an
// RMSE at most its own with one of them strictly lower.
void markParetoFront(std::vector<ErrorPoint>& points);

}  // namespace vkray::bench
