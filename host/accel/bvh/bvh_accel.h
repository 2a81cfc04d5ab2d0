// Entry point of the bvh family for accel/accel.cpp, and the whole build (builder, leaf collapse,
// flattening) for tests and benchmarks.
//
// Names: bvh-fast = AAC-Fast (delta 4, epsilon 0.2), bvh-hq = AAC-HQ (delta 20, epsilon 0.1), both
// Gu et al. 2013; bvh = the default preset (bvhDefaultConfig(), docs/bvh.md says why); bvh-sah =
// the binned-SAH reference. AccelSpec::aacDelta / aacEpsilon override the AAC presets when > 0.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "accel/accel.h"
#include "accel/bvh/bvh.h"
#include "accel/bvh/phase_log.h"

namespace vkray::accel {

std::unique_ptr<BuiltAccel> buildBvhAccel(const Scene& scene, const AccelSpec& spec, const BuildOptions& options);

}  // namespace vkray::accel

namespace vkray::bvh {

// The preset of plain `bvh`.
Config bvhDefaultConfig();

// The Config an accelerator spec asks for (throws vkray::Error for AAC overrides on bvh-sah or
// out-of-range values).
Config configFor(const accel::AccelSpec& spec);

struct BuildResult {
    FlatBvh flat;
    std::vector<std::pair<std::string, double>> phases;  // (name, ms) in order
    double totalMs = 0.0;
};

// Builds, collapses and flattens on a oneTBB arena of `threads` workers (0 = all cores).
BuildResult buildFlatBvh(std::span<const Triangle> triangles, const Config& config, int threads = 0,
                         PhaseLog::Progress progress = {});

}  // namespace vkray::bvh
