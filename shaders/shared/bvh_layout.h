// The one definition of the BVH's GPU node layout, shared by the host (C++, accel/bvh/flatten.cpp)
// and the kernel (GLSL, include/bvh_traversal.glsl), like gpu_layout.h: 16-byte slots, checked with
// static_assert on the C++ side.
//
// Layout: depth-first. A node's left child is the next node in the array, so an inner node stores
// only its right child; a leaf stores a range of the triangle buffer, which the host fills in leaf
// order (GpuAccelData.triangleOrder) so a leaf's triangles are contiguous.
#ifndef VKRAY_BVH_LAYOUT_H
#define VKRAY_BVH_LAYOUT_H

#include "shared/gpu_layout.h"

// Traversal stack entries per ray (local memory): the far children still to visit. Near-child-first
// traversal pushes at most one entry per level, so a tree no deeper than this never overflows it;
// the host reports the tree's depth (stats: max_depth) and the kernel flags an overflowing pixel
// as cut short instead of answering wrongly.
#define VKRAY_BVH_STACK_SIZE 64
// Most triangles a leaf holds (accel/bvh: leaf collapse). The kernel tests a leaf's triangles four
// per loop iteration, so a leaf costs at most two iterations of lavapipe's loop budget.
#define VKRAY_BVH_MAX_LEAF_SIZE 8
// Hang guard per traversal (lavapipe has no watchdog): a traversal visits each node at most once,
// so only a corrupt tree or a scene of hundreds of thousands of overlapping triangles reaches it;
// such a ray counts in GpuPixel.capped.
#define VKRAY_BVH_MAX_ITERATIONS 16384

#ifdef __cplusplus
namespace vkray::gpu {
#define VKRAY_BVH_STRUCT(name) struct alignas(16) name
#else
#define VKRAY_BVH_STRUCT(name) struct name
#endif

VKRAY_BVH_STRUCT(GpuBvhNode) {  // 32 bytes: two 16-byte slots
    vec3 lo;            // 12 bytes: bounding box, min corner
    uint rightOrFirst;  // 4 bytes: inner node: index of the right child (the left is this + 1);
                        //          leaf: first triangle of the leaf in the triangle buffer
    vec3 hi;            // 12 bytes: bounding box, max corner
    uint count;         // 4 bytes: leaf: number of triangles (1..VKRAY_BVH_MAX_LEAF_SIZE); inner: 0
};

#ifdef __cplusplus
static_assert(sizeof(GpuBvhNode) == 32 && offsetof(GpuBvhNode, lo) == 0 &&
              offsetof(GpuBvhNode, rightOrFirst) == 12 && offsetof(GpuBvhNode, hi) == 16 &&
              offsetof(GpuBvhNode, count) == 28);
}  // namespace vkray::gpu
#endif
#undef VKRAY_BVH_STRUCT

#endif  // VKRAY_BVH_LAYOUT_H
