// What bench.md and report.html both show (report.h), built once from BenchResults as plain-text
// cells and sentences; each writer only renders them as Markdown or HTML, so the two cannot drift.
// Internal to host/bench.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "accel/accel_spec.h"
#include "bench/bench_results.h"

namespace vkray::bench {

// What an optional or unmeasured figure prints.
inline constexpr const char* kMissing = "—";
// The marker of the Pareto front and of the best delta.
inline constexpr const char* kStar = "★";

struct Table {
    std::string title;
    std::vector<std::string> columns;
    std::vector<bool> numeric;                   // per column: right-aligned
    std::vector<std::vector<std::string>> rows;
    std::vector<bool> marked;                    // per row: highlighted (carries a ★ in a cell too)
    std::vector<std::string> notes;              // shown below the table
    std::string whenEmpty;                       // shown instead of a table without rows
};

// Label and value pairs.
using Facts = std::vector<std::pair<std::string, std::string>>;

// A table with its title (a level-3 heading), rows and notes, as bench.md writes it
// (report_markdown.cpp) and as report.html does (report_html.cpp).
std::string markdownTable(const Table& t);
std::string htmlTable(const Table& t);

// The section a merged report (bench_merge.h) adds after the run's facts: one row per shard (node,
// device, driver, when, how many configurations) and which shard measured each configuration.
// Empty for a report that is not merged. report_shards.cpp.
std::string shardsMarkdown(const BenchResults& results);
std::string shardsHtml(const BenchResults& results);

// The run: device, driver, vkray version and revision, command line, date, repeats, threads.
Facts runFacts(const BenchResults& results);
// The scene: file, triangles, size, maxdepth, the reference render.
Facts sceneFacts(const SceneResult& scene);

// The tables of one scene, in report order: accelerators, build scaling, concurrent build, AAC
// delta sweep, error against run time.
Table acceleratorTable(const SceneResult& scene);
Table embreeTable(const SceneResult& scene);
Table buildScalingTable(const SceneResult& scene);
Table concurrentBuildTable(const SceneResult& scene);
Table deltaSweepTable(const SceneResult& scene);
Table errorTable(const SceneResult& scene);
std::vector<Table> sceneTables(const SceneResult& scene);

// The camera rays of every scene side by side, when the run has two or more scenes with accelerators
// (report_summary.cpp): one row per accelerator, a column per scene with its camera-ray rate over
// the scene's Embree rtcIntersect1 figure (over bvh's when a scene has no Embree figure but every
// scene ran bvh), and the geometric mean of those ratios; the highest mean marked.
std::optional<Table> summaryTable(const BenchResults& results);

// The family of an accelerator's name (tuning included); empty for a name this build does not know.
std::optional<accel::Family> familyOf(const std::string& accelName);

// What the report says an accelerator is, for one whose structure and traversal are not vkray's own
// (rayquery: the driver's); empty for every other.
std::string accelAbout(const std::string& accelName);
// Lines naming each such accelerator of the scene with what it is and, for a build timed on the
// device, that its build and structure are the driver's: the note under every table that lists the
// accelerators, the console summary's line and bench.json's "about".
std::vector<std::string> accelAboutNotes(const SceneResult& scene);

// Which traversal traces fastest, from the median trace times: the fastest BVH against the fastest
// kd traversal with their ratio, then the kd traversals among themselves; says what is missing
// when a family was not run.
std::string whoWins(const SceneResult& scene);

// The thread counts of the scene's build timings, ascending, and the one speed-ups are relative
// to (1 when measured, else the smallest).
std::vector<int> buildThreadCounts(const SceneResult& scene);
// median(base threads) / median(threads); empty when either is missing or not positive.
std::optional<double> buildSpeedup(const AccelResult& accel, int baseThreads, int threads);

// Index of the delta with the lowest build + trace total (medians); empty without deltas.
std::optional<size_t> bestDelta(const SceneResult& scene);

// ---- Number formatting (shared so every figure reads the same in both files) ------------------

// Milliseconds, rates and other magnitudes: 2 significant digits under 1, 1 decimal under 100,
// an integer above ("0.042", "12.3", "1234").
std::string formatNumber(double v);
// "12.3 (11.9–13.0)": the median with the min–max spread.
std::string formatSpread(const Spread& s);
// "2.40x"
std::string formatRatio(double r);
// "512 B", "12.3 KiB", "4.56 MiB", "1.20 GiB"
std::string formatBytes(uint64_t bytes);
// Per-ray counts: 2 decimals under 10, 1 above.
std::string formatPerRay(double v);
// The same of an accelerator's counter, "—" where its traversal has no counters (rayquery).
std::string perRayCell(const AccelResult& a, double v);
// RMSE with 3 significant digits ("0.0123", "1.23e-05"), exactly "0" when identical.
std::string formatRmse(double rmse);
// dB with 1 decimal, "identical" when empty.
std::string formatPsnr(const std::optional<double>& psnr);
// A fraction as a percentage with 2 decimals ("0.25 %").
std::string formatPercent(double fraction);
// A relative change with its sign, 1 decimal under 10 % ("+163 %", "−24 %", "+2.5 %", "0 %").
std::string formatChange(double fraction);
// Building both at once against the sum of the separate builds, medians in ms: "7.4 ms slower than
// the 4.5 ms sum (+163 %)", "7.0 ms faster than the 29.0 ms sum (−24 %)", "as fast as ...".
std::string concurrentAgainstSum(double concurrentMs, double sumMs);

}  // namespace vkray::bench
