// The quality reference: a top-down binned SAH builder (Wald, "On fast Construction of SAH-based
// Bounding Volume Hierarchies", RT 2007). Each node bins its primitives' centroids into
// Config::sahBins bins per axis, evaluates the SAH at every bin boundary of all three axes and splits
// at the cheapest; it always splits down to single primitives, so the leaf collapse (shared with
// AAC) decides the leaves of both builders the same way.
#pragma once

#include "accel/bvh/bvh.h"
#include "core/phase_log.h"
#include "accel/bvh/primitives.h"

namespace vkray::bvh {

// Phase "sah_split" goes to `log`. Large nodes bin in parallel and subtrees build as oneTBB
// tasks; bins reduce by integer counts and min/max boxes, so the tree never depends on the thread
// count.
BinaryTree buildBinnedSah(const PrimitiveSet& prims, const Config& config, PhaseLog& log);

}  // namespace vkray::bvh
