// Entry point of the bvh family for accel/accel.cpp, and the whole build (builder, leaf collapse,
// flattening) for tests and benchmarks. The presets (bvh, bvh-fast, bvh-hq, bvh-sah, bvh-stackless,
// bvh-packet, bvh-sphere) and their overrides are resolved in accel/accel_spec.cpp; this file builds whatever
// Config it is given.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "accel/accel.h"
#include "accel/bvh/bvh.h"
#include "core/phase_log.h"

namespace vkray::accel {

// The GPU traversal of a BVH of `config` (its container) walked by `walk`.
Traversal bvhTraversal(const bvh::Config& config, BvhWalk walk);

// `walk`: how the kernel walks the tree. The CPU tracer walks it with parent links for
// BvhWalk::Stackless (bvh-stackless), else with a stack: a packet's hits are its rays' own.
std::unique_ptr<BuiltAccel> buildBvhAccel(const Scene& scene, const bvh::Config& config, BvhWalk walk,
                                          const BuildOptions& options);

}  // namespace vkray::accel

namespace vkray::bvh {

struct BuildResult {
    FlatBvh flat;
    std::vector<std::pair<std::string, double>> phases;  // (name, ms) in order
    double totalMs = 0.0;
    int reinsertIterations = 0;  // iterations the reinsertion ran (it may stop before Config's bound)
};

// Builds, collapses and flattens on a oneTBB arena of `threads` workers (0 = all cores).
BuildResult buildFlatBvh(std::span<const Triangle> triangles, const Config& config, int threads = 0,
                         BuildProgress progress = {});

}  // namespace vkray::bvh
