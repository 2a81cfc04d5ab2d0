// Writers of `vkray bench`'s output folder: bench.json (every figure, machine-readable),
// bench.md (the tables), report.html (self-contained: images as data URIs, plots as inline SVG, no
// network access, no external assets) and images/ (the same pictures as PNG files).
#pragma once

#include <filesystem>
#include <string>

#include "bench/bench_results.h"

namespace vkray::bench {

std::string benchJson(const BenchResults& results);
std::string benchMarkdown(const BenchResults& results);
std::string benchHtml(const BenchResults& results);

// Writes all of the above into `dir` (created if missing); a vkray::Error names a file that cannot
// be written.
void writeBenchReport(const BenchResults& results, const std::filesystem::path& dir);

// Marks ErrorPoint::pareto: a point is on the front when no other point has both a total time and an
// RMSE at most its own with one of them strictly lower.
void markParetoFront(std::vector<ErrorPoint>& points);

}  // namespace vkray::bench
