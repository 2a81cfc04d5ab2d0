// `vkray bench --merge DIR...`: the reports of the shards of one run (`vkray bench --shard I/N`,
// bench_shard.h) as the one report an unsharded run writes — every configuration, each with the
// figures of the shard that measured it — plus which shard, node and device measured what.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench_results.h"

namespace vkray::bench {

// Reads DIR/bench.json (and DIR/images/) of every folder and merges them. Throws vkray::Error, one
// line naming the file and the difference, for: a folder without a readable bench.json, a merged
// report given as a shard, another vkray version or revision, other settings, another shard count or
// configuration list, a shard given twice, missing shards ("missing shards 1, 3 of 4") and incomplete
// ones (bench_resume.h: named with the scenes they lack), a shard without a configuration it should
// have measured.
//
// What is not one shard's figure: the Pareto front is marked again over all the points of a scene,
// and the scene's Embree summary is the median (min-max) of every shard's Embree samples together,
// so every accelerator's ratio to Embree divides by that one merged figure, whichever shard measured
// the accelerator.
BenchResults mergeBenchReports(const std::vector<std::filesystem::path>& dirs, const std::string& commandLine);

}  // namespace vkray::bench
