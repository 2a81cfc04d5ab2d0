// SAH kd-tree construction in O(N log N) after Wald and Havran, "On building fast kd-Trees for Ray
// Tracing, and on doing that in O(N log N)", IEEE Symposium on Interactive Ray Tracing 2006:
//  - one event list per axis, sorted once (section 5.1); each split partitions the lists in order
//    and only the triangles that straddle the plane get new events, sorted and merged (5.2-5.3);
//  - "perfect splits" (4.3): a straddling triangle is clipped to each child's box, and its clipped
//    bounds (not its bounding box) give its events below;
//  - the SAH of KdConfig with the empty-space bonus, termination when no split is cheaper than a leaf
//    (section 3), and a maximum depth (pbrt's 8 + 1.3 log2 N by default).
//
// Classification (Wald and Havran 4.2 and 5.1; docs/kdtree.md, "Which side a triangle goes to"):
//  - A triangle whose clipped part ends at the split plane goes below only, one that starts at it
//    above only: a triangle that merely touches the plane is referenced on one side, never both.
//  - A triangle whose clipped part is flat in the split plane (lying in it, or meeting the node only
//    in an edge or a point there) goes to the side the SAH prefers (ties: below), never nowhere.
//  - A ray lying in a split plane may need either side: the traversals walk it once per choice of
//    side at such planes (kd_traversal.h, "in-plane rays").
//  - Clipped bounds are computed in double and rounded outwards to float; splits are floats.
//  - Degenerate (zero-area) triangles are left out: the ray-triangle test never reports them.
//
// Independent subtrees are built as oneTBB tasks inside a task arena of `threads` workers; every
// decision depends only on the node's own data, so the tree is identical for any thread count.
#pragma once

#include <cstddef>
#include <vector>

#include "core/phase_log.h"
#include "accel/kd/kd_tree.h"
#include "scene/scene.h"

namespace vkray::accel::kd {

// A subtree whose root has fewer events than this on an axis is built on one worker, straight in
// the flat layout, its event lists on a stack (sah_kd_builder.cpp).
inline constexpr size_t kSmallSubtreeEvents = 1024;
// Of the small subtrees' nodes, every this-many-th a worker builds is timed phase by phase
// (KdBuildTimes).
inline constexpr uint64_t kSampledSmallNodes = 64;

// Wall-clock milliseconds of the build's steps; the splitting's phases are worker time, summed over
// the workers (so they add up to at most treeMs times the workers; the rest is task scheduling and
// waiting). Nodes of kSmallSubtreeEvents or more are timed phase by phase; the smaller subtrees as
// a whole (smallMs), and their share of each phase is estimated from one node in kSampledSmallNodes
// of theirs timed phase by phase (timing every small node cost more than some phases).
struct KdBuildTimes {
    double eventsMs = 0.0;   // bounds, initial events, the three sorts
    double treeMs = 0.0;     // recursive SAH splitting
    double sweepMs = 0.0;       // worker time: the plane sweeps (Wald and Havran 4.2)
    double classifyMs = 0.0;    // worker time: side marks and straddlers (5.2)
    double clipMs = 0.0;        // worker time: straddlers clipped, their new events (4.3)
    double distributeMs = 0.0;  // worker time: the lists split in order, new events merged in (5.2-5.3)
    double leavesMs = 0.0;      // worker time: leaves made
    double smallMs = 0.0;       // worker time: subtrees under kSmallSubtreeEvents (their phases in those above)
    double flattenMs = 0.0;  // the GPU arrays
    double totalMs = 0.0;
};

struct KdBuildResult {
    KdTree tree;
    KdBuildTimes times;
};

// `threads`: workers of the task arena, 0 = all cores. `progress` (may be empty) hears phase names
// and fractions, from one thread at a time.
KdBuildResult buildSahKdTree(const std::vector<Triangle>& triangles, const KdConfig& config, int threads = 0,
                             const BuildProgress& progress = {});

}  // namespace vkray::accel::kd
