// Entry point of the kd family for accel/accel.cpp: an SAH kd-tree (sah_kd_builder.h) walked by one
// of the three traversals — kd-stack, kd-restart or kd-backtrack (kd_traversal.h on the CPU,
// shaders/render_kd_<traversal>.comp on the GPU). docs/kdtree.md describes the whole family.
#pragma once

#include <memory>

#include "accel/accel.h"
#include "accel/kd/kd_tree.h"

namespace vkray::accel {

// The GPU traversal of the tree walked with `traversal`.
Traversal kdTraversal(kd::Traversal traversal);

// GpuAccelData::kdShortStack for `traversal`: the stack's entries for kd-shortstack, else 0.
uint32_t kdShortStack(kd::Traversal traversal, int shortStack);

// The tree as the GPU kernel of `traversal` reads it (what a built kd accelerator uploads):
// the header and nodes, the index list, and what only that traversal reads, which the tree must
// carry: ropes for kd-ropes (kd::buildRopes), node boxes and parent links for kd-backtrack
// (kd::deriveNodeExtras). `shortStack`: kd-shortstack's stack entries (AccelSpec::kdShortStack).
GpuAccelData kdGpuData(const kd::KdTree& tree, kd::Traversal traversal, int shortStack);

// `shortStack`: kd-shortstack's stack entries (AccelSpec::kdShortStack).
std::unique_ptr<BuiltAccel> buildKdAccel(const Scene& scene, const kd::KdConfig& config, kd::Traversal traversal,
                                         int shortStack, const BuildOptions& options);

}  // namespace vkray::accel
