// Flattening: the collapsed tree written depth-first in the GPU node layout (shared/bvh_layout.h),
// with the triangles reordered into leaf order so a leaf reads one contiguous run of the triangle
// buffer; within a leaf, triangles keep ascending original index.
#pragma once

#include "accel/bvh/bvh.h"
#include "accel/bvh/leaf_collapse.h"

namespace vkray::bvh {

// Subtrees near the root are written by parallel tasks at offsets known from the collapse, so
// the arrays are the same for any thread count.
FlatBvh flatten(const BinaryTree& tree, const CollapsedTree& collapsed);

}  // namespace vkray::bvh
