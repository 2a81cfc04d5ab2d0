// SAH kd-tree construction over binned candidate planes (KdConfig::bins > 0), after Shevtsov,
// Soupikov and Kapustin, "Highly Parallel Fast KD-tree Construction for Interactive Ray Tracing of
// Dynamic Scenes", Eurographics 2007 (min-max binning), and Hunt, Mark and Stoll, "Fast kd-tree
// Construction with an Adaptive Error-Bounded Heuristic", IEEE Symposium on Interactive Ray Tracing
// 2006 (the SAH sampled at a few planes):
//  - each node keeps its triangles as references with their bounds inside it, in triangle order; no
//    event lists, no sorts;
//  - on each axis, N - 1 planes spaced evenly across the node, plus the two planes at its
//    triangles' outer bounds (the empty-space cuts the exact sweep finds), are the candidates;
//    each reference's low bound is counted in the bin of the planes at or below it and its high
//    bound in that of the planes below it, so prefix sums give each candidate's exact counts of
//    triangles below and above it, and the SAH of KdConfig, empty-space bonus and reference budget
//    included, chooses as the exact sweep does among those candidates;
//  - the classification, perfect splits (straddlers clipped to each child: Wald and Havran 2006,
//    section 4.3), depth limit and SAH termination are those of sah_kd_builder.h; triangles lying
//    in the chosen plane go below (the exact sweep tries both sides), except at the cut that takes
//    empty space off below the node's triangles;
//  - big nodes bin and split their references in parallel chunks, subtrees run as oneTBB tasks,
//    and a small subtree is built on one worker, its references on a stack and its nodes straight
//    in the flat layout (kd_build_tree.h). The counts are integers and the chunks keep their order,
//    so the tree is the same for any thread count.
#pragma once

#include <vector>

#include "accel/kd/sah_kd_builder.h"

namespace vkray::accel::kd {

// A subtree whose root holds fewer references than this is built on one worker (binned_kd_builder.cpp).
inline constexpr size_t kSmallSubtreeRefs = 512;

// The tree of buildSahKdTree for config.bins > 0 (it calls this); the times' phases read: sweepMs the
// binning, distributeMs the references split between the children (classification included),
// clipMs the straddlers clipped, eventsMs the root's references; classifyMs stays 0.
KdBuildResult buildBinnedKdTree(const std::vector<Triangle>& triangles, const KdConfig& config, int threads,
                                const BuildProgress& progress);

}  // namespace vkray::accel::kd
