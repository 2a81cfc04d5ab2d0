// Flattening: the collapsed tree written depth-first (FlatNode), with the triangles reordered into
// leaf order so a leaf reads one contiguous run of the triangle buffer; within a leaf, triangles
// keep ascending original index. gpuNodes() turns that into the kernel's layout.
#pragma once

#include "accel/bvh/bvh.h"
#include "accel/bvh/leaf_collapse.h"

namespace vkray::bvh {

// Subtrees near the root are written by parallel tasks at offsets known from the collapse, so
// the arrays are the same for any thread count.
FlatBvh flatten(const BinaryTree& tree, const CollapsedTree& collapsed);

// The GPU layout (shared/bvh_layout.h): the binary tree collapsed into VKRAY_BVH_WIDTH-wide nodes,
// depth-first, each with its children's boxes (quantised: accel/bvh/quantize.h), references and
// parent link. The links are for the stackless walk (every BVH kernel's shadow rays, and
// bvh-stackless's closest hits): parent << 2 | slot, VKRAY_BVH_NO_PARENT for the root. Throws
// vkray::Error for more triangles than leaf references can address (VKRAY_BVH_MAX_TRIANGLES), or
// more nodes than a link can name.
std::vector<gpu::GpuBvhNode> gpuNodes(const FlatBvh& flat);
// The same wide nodes with their children's spheres (bvh-sphere; the tree must have spheres); their
// parent links, which have no spare word in the node, come from gpuParentLinks.
std::vector<gpu::GpuBvhSphereNode> gpuSphereNodes(const FlatBvh& flat);
std::vector<uint32_t> gpuParentLinks(const std::vector<gpu::GpuBvhSphereNode>& nodes);

// gpuNodes(flat).size() (and gpuSphereNodes'), counted without writing the nodes.
size_t gpuNodeCount(const FlatBvh& flat);

}  // namespace vkray::bvh
