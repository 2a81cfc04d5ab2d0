// bench_resume.h: what an incomplete report lacks, and whether a run may continue it.
#include "bench/bench_resume.h"

#include <algorithm>

#include "bench/bench_json.h"
#include "bench/bench_shard.h"
#include "core/error.h"

namespace fs = std::filesystem;

namespace vkray::bench {
namespace {

std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
    return out;
}

}  // namespace

std::string writtenBy(const BenchResults& r) {
    return "vkray " + r.vkrayVersion + (r.revision.empty() ? "" : " (revision " + r.revision + ")");
}

bool hasScene(const BenchResults& r, int index) {
    return std::any_of(r.scenes.begin(), r.scenes.end(), [&](const SceneResult& s) { return s.index == index; });
}

std::vector<std::string> missingScenes(const BenchResults& r) {
    std::vector<std::string> out;
    if (r.complete()) return out;
    const std::vector<SceneWork> work = shardWork(r.settings, r.shard);
    for (size_t i = 0; i < work.size() && i < r.settings.scenes.size(); ++i)
        if (!work[i].empty() && !hasScene(r, int(i))) out.push_back(r.settings.scenes[i]);
    return out;
}

std::string incompleteNotice(const BenchResults& r) {
    if (r.complete()) return "";
    const std::string out = "the run stopped before it finished: " + r.failure + ".";
    const std::vector<std::string> missing = missingScenes(r);
    if (missing.empty()) return out + " Every scene was measured, but the run did not end.";
    return out + " Not measured: " + joined(missing) + ". `vkray bench --resume` with the same options and --out " +
           "measures " + (missing.size() == 1 ? "it" : "them") + " and keeps the scenes here.";
}

std::optional<BenchResults> readResumableReport(const fs::path& dir) {
    if (!fs::exists(dir / "bench.json")) return std::nullopt;
    return readBenchReport(dir);
}

namespace {

[[noreturn]] void refuse(const fs::path& file, const std::string& what) {
    throw Error(FileLoc{file.string()}, "--resume: " + what + "; to start afresh, run without --resume or with another --out");
}

}  // namespace

void checkResumableSettings(const BenchResults& previous, const BenchResults& run, const fs::path& file) {
    if (!previous.shards.empty()) refuse(file, "a merged report, not the report of a run");
    if (writtenBy(previous) != writtenBy(run))
        refuse(file, "written by " + writtenBy(previous) + ", this is " + writtenBy(run));
    if (const auto diff = settingsDifference(previous.settings, run.settings))
        refuse(file, "other settings: " + *diff + " in this run");
    if (previous.shard.index != run.shard.index || previous.shard.count != run.shard.count)
        refuse(file, "measured shard " + shardText(previous.shard) + ", this run is shard " + shardText(run.shard));
    if (previous.configurationHash != run.configurationHash)
        refuse(file, "another configuration list (hash " + previous.configurationHash + ", this run's " +
                         run.configurationHash + ")");
}

void checkResumable(const BenchResults& previous, const BenchResults& run, const fs::path& file) {
    checkResumableSettings(previous, run, file);
    if (previous.device != run.device || previous.driver != run.driver)
        refuse(file, "measured on " + previous.device + " (" + previous.driver + "), this run's device is " +
                         run.device + " (" + run.driver + ")");
}

}  // namespace vkray::bench
