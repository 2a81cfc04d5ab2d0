// A bench run that did not finish, and `vkray bench --resume`, which finishes it. A run saves its
// report after every scene it finishes, marked incomplete (BenchResults::failure) until the last;
// a run that fails or is interrupted saves the finished scenes with the failure. `--resume` reads
// that report back from --out, checks that it comes from the same run (vkray revision, device,
// settings, shard) and measures only the scenes it lacks. A scene is the unit: one that was cut
// short is measured again from its start.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench_results.h"

namespace vkray::bench {

// "vkray 1.2.0 (revision abc1234)": what wrote a report.
std::string writtenBy(const BenchResults& results);

// The scene files (as given) the run still has to measure, in run order: those of which its shard
// measures something and of which `results` has no figures. Empty for a complete run.
std::vector<std::string> missingScenes(const BenchResults& results);

// Whether `results` holds the figures of the run's scene `index` (BenchSettings::scenes).
bool hasScene(const BenchResults& results, int index);

// One sentence for the reports and the console about an incomplete run: why it stopped, which
// scenes it lacks and how to measure them. Empty for a complete run.
std::string incompleteNotice(const BenchResults& results);

// The report in `dir` that `--resume` continues; empty when `dir` has no bench.json (a run that
// saved nothing yet: it starts afresh). A bench.json that cannot be read throws vkray::Error.
std::optional<BenchResults> readResumableReport(const std::filesystem::path& dir);

// Refuses, with a vkray::Error naming `file` and the first difference, to continue `previous` with
// `run` (its facts and settings, no scenes yet) when the two would not make one run: a merged report,
// another vkray version or revision, another device or driver, other settings, another shard.
void checkResumable(const BenchResults& previous, const BenchResults& run, const std::filesystem::path& file);
// The same without the device, for a run whose device is not open yet (its scenes are checked first).
void checkResumableSettings(const BenchResults& previous, const BenchResults& run, const std::filesystem::path& file);

}  // namespace vkray::bench
