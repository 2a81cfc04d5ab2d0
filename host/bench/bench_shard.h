// Splitting `vkray bench` over several processes or machines (docs/cluster.md): the run's
// configurations — its units of measurement, each a row or a point of the report — in the order an
// unsharded run measures them, and which of them `--shard I/N` measures. Merging the shards back is
// bench_merge.h's.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bench/bench_results.h"
#include "bench/bench_runner.h"

namespace vkray::bench {

// The settings the options describe, with the build thread counts resolved for this machine
// (bench_runner.h, defaultThreadCounts).
BenchSettings benchSettings(const BenchOptions& options);

// One unit of measurement of one scene. Labels, per scene in this order: "reference" (the CPU
// double-precision reference's timings: the "CPU double" point), "accel NAME" for each --accel,
// "concurrent BVH+KD" (when the accelerators hold a BVH and a kd-tree), "aac-delta D" for each
// --deltas value, "maxdepth-sweep" (unless --maxdepths none).
struct Configuration {
    enum class Kind { Reference, Accel, Concurrent, Delta, MaxDepthSweep };
    int scene = 0;       // index into BenchSettings::scenes
    std::string label;
    Kind kind = Kind::Reference;
    std::string accel{};  // Kind::Accel: the accelerator
    int delta = 0;       // Kind::Delta: the AAC delta
};

// Configuration k of a run's list belongs to shard k mod N (round-robin), so each shard gets a share
// of every scene and of every kind of work.
inline int shardOfConfiguration(size_t k, int count) { return int(k % size_t(count)); }

// Every configuration of the run the settings describe, in run order.
std::vector<Configuration> configurationList(const BenchSettings& settings);

// A hash of the list (scene files and labels): shards of one run carry the same one. 16 hex digits.
std::string configurationHash(const std::vector<Configuration>& list);

inline bool inShard(size_t k, const ShardSpec& shard) { return shardOfConfiguration(k, shard.count) == shard.index; }

// "I/N" with 0 <= I < N <= 10000; `option` names the flag in the error.
ShardSpec parseShard(const std::string& text, const std::string& option = "--shard");
std::string shardText(const ShardSpec& shard);  // "1/4"

// What one shard does of one scene.
struct SceneWork {
    bool reference = false;              // report the reference's timings (the "CPU double" point)
    std::vector<std::string> accels;     // in --accel order
    bool concurrent = false;
    std::vector<int> deltas;
    bool maxDepthSweep = false;
    std::vector<std::string> labels;     // all of the above, in run order
    bool empty() const { return labels.empty(); }
    // Everything but the concurrent build compares an image with the reference.
    bool needsReferenceImage() const {
        return reference || !accels.empty() || !deltas.empty() || maxDepthSweep;
    }
};

// Per scene of the settings, what `shard` measures of it (an unsharded run: 0/1, everything).
std::vector<SceneWork> shardWork(const BenchSettings& settings, const ShardSpec& shard);

// bench.json's "settings" object, and back; fromJson throws vkray::Error naming the missing or
// malformed key.
nlohmann::ordered_json settingsJson(const BenchSettings& settings);
BenchSettings settingsFromJson(const nlohmann::ordered_json& json);

// The first setting in which two runs differ, as "repeat is 1 here, 3" (`mine`'s, then `theirs`);
// empty when they are equal. Shards merge, and a run resumes, only with equal settings.
std::optional<std::string> settingsDifference(const BenchSettings& mine, const BenchSettings& theirs);

}  // namespace vkray::bench
