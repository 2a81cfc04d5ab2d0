// The SAH cost of a kd split (KdConfig), shared by the exact sweep (sah_kd_builder.cpp) and the
// binned build (binned_kd_builder.cpp), so both builders price a candidate plane the same way.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include <glm/glm.hpp>

#include "accel/kd/kd_tree.h"

namespace vkray::accel::kd {

// A float split the GPU reads back unchanged: strictly inside the box (a split on the boundary cuts
// nothing) and not denormal (lavapipe flushes denormals to zero).
inline bool usableSplit(const Box& box, int axis, float pos) {
    return pos > box.lo[axis] && pos < box.hi[axis] &&
           (pos == 0.0f || std::abs(pos) >= std::numeric_limits<float>::min());
}

// The SAH cost of a split along one axis (KdConfig), with what depends only on the node and the axis
// set once per node. The children's surface areas are linear in the split position: the two faces
// across the axis (`caps`) plus the four along it (`sides` per unit of length), so a candidate costs
// a few multiplications instead of two boxes' areas. The products are formed as in KdConfig's
// formula, Ct + Ci * bonus / SA(N) * (SA(L) nL + SA(R) nR), left to right, so every candidate's cost
// is the same double whichever way a builder reaches it. Counts are signed: a signed integer
// converts to double in one instruction, an unsigned one does not.
struct AxisCost {
    double lo, hi, caps, sides, traversal, fullScale, emptyScale, minEmpty;

    AxisCost(const Box& box, int axis, double invArea, const KdConfig& config) {
        const glm::dvec3 e = glm::dvec3(box.hi) - glm::dvec3(box.lo);
        const double a = e[(axis + 1) % 3], b = e[(axis + 2) % 3];
        lo = box.lo[axis];
        hi = box.hi[axis];
        caps = 2.0 * a * b;
        sides = 2.0 * (a + b);
        traversal = config.traversalCost;
        fullScale = config.intersectionCost * 1.0 * invArea;
        emptyScale = config.intersectionCost * (1.0 - config.emptyBonus) * invArea;
        // The bonus only for empty space worth a level of the tree (KdConfig::emptyBonusMinFraction).
        minEmpty = config.emptyBonusMinFraction * (hi - lo);
    }

    double operator()(float pos, int64_t nBelow, int64_t nAbove) const {
        const double below = caps + sides * (double(pos) - lo);
        const double above = caps + sides * (hi - double(pos));
        const double emptyExtent = nBelow == 0 ? double(pos) - lo : nAbove == 0 ? hi - double(pos) : 0.0;
        const bool emptySide = (nBelow == 0 || nAbove == 0) && emptyExtent >= minEmpty;
        return traversal + (emptySide ? emptyScale : fullScale) * (below * double(nBelow) + above * double(nAbove));
    }
};

}  // namespace vkray::accel::kd
