// The one definition of the BVH's GPU node layout, shared by the host (C++, accel/bvh/flatten.cpp)
// and the kernel (GLSL, include/bvh_traversal.glsl), like gpu_layout.h: 16-byte slots, checked with
// static_assert on the C++ side.
//
// Layout: a 4-wide BVH collapsed from the binary tree (accel/bvh/flatten.cpp, gpuNodes), its nodes
// depth-first from the root (node 0). A node holds the boxes of up to four children, coordinates
// grouped by axis so the kernel tests all four with vector operations, and their references (Wald,
// Benthin and Boulos, "Getting Rid of Packets", RT 2008). One node read decides which children a
// ray enters, and a ray takes about half the steps of the binary tree: on llvmpipe every step pays
// for all branches of the loop body.
//
// The child boxes are compressed as Ylitie, Karras and Laine do ("Efficient Incoherent Ray
// Traversal on GPUs Through Compressed Wide BVHs", HPG 2017, section 3.1): per axis the node has a
// corner c (a float at or below its box's minimum) and a power-of-two step 2^e, and each child's planes are
// bytes q, the plane c + q 2^e, rounded outwards by the host (accel/bvh/quantize.h), so a child's
// byte box always holds its real box. Four texels a node instead of seven; the kernel tests the
// planes in the node's own grid (include/bvh_common.glsl).
//
// A reference is an inner node's index, or a leaf: the leaf bit, the triangle count - 1 and the
// leaf's first slot in the triangle buffer, which the host fills in leaf order
// (GpuAccelData.triangleOrder) so a leaf's triangles are contiguous. Unused child slots hold
// VKRAY_BVH_NO_CHILD.
//
// Every node has a parent link, parent << 2 | the node's slot in its parent, VKRAY_BVH_NO_PARENT for
// the root (after Hapala, Davidovic, Wald, Havran and Slusallek, "Efficient Stack-less BVH Traversal
// for Ray Tracing", SCCG 2011), for the stackless walk: bvh-stackless's rays, and every BVH kernel's
// shadow rays. A box node carries it in a spare word (GpuBvhNode.planesZ.z), so the walk's step
// reads it with the node; a sphere node has none to spare, and its links are the view
// VKRAY_BINDING_INDEX_TEXELS (R32UI), one a node.
#ifndef VKRAY_BVH_LAYOUT_H
#define VKRAY_BVH_LAYOUT_H

#include "shared/gpu_layout.h"

// Children per node.
#define VKRAY_BVH_WIDTH 4
// Traversal stack entries per ray (local memory): the children still to visit. A step pushes at
// most VKRAY_BVH_WIDTH - 1 entries, so a tree whose depth d has 3 d + 1 <= this never overflows
// it; the kernel flags an overflowing pixel as cut short instead of answering wrongly.
#define VKRAY_BVH_STACK_SIZE 96
// Most triangles a leaf holds (accel/bvh: leaf collapse).
#define VKRAY_BVH_MAX_LEAF_SIZE 8
// Hang guard per traversal (lavapipe has no watchdog), counting node steps, leaves and the pushes'
// passes: a traversal visits each node at most once, so only a corrupt tree or a ray inside a
// scene of hundreds of thousands of overlapping triangles reaches it; such a ray counts in
// GpuPixel.capped. A walk cut short by llvmpipe's loop budget resumes with its count
// (render_main.glsl, "Resumable pixels"), so the cap need not fit one dispatch: it is set well above
// the walks of the degenerate meshes of docs/bvh.md (20,000 triangles around one point, seen from
// inside, in the binned-SAH tree).
#define VKRAY_BVH_MAX_ITERATIONS 262144

// Child references: bit 31 set for a leaf, bits 28-30 its triangle count - 1, bits 0-27 its first
// slot; an inner node's index otherwise.
#define VKRAY_BVH_LEAF_BIT 0x80000000u
#define VKRAY_BVH_COUNT_SHIFT 28
#define VKRAY_BVH_COUNT_MASK 7u
#define VKRAY_BVH_FIRST_MASK 0x0FFFFFFFu
// Most triangles a BVH may hold: leaf slots must fit in 28 bits.
#define VKRAY_BVH_MAX_TRIANGLES 0x0FFFFFF0u
// An unused child slot: a leaf reference no tree can make (VKRAY_BVH_MAX_TRIANGLES keeps
// first + count below 2^28 - 1).
#define VKRAY_BVH_NO_CHILD 0xFFFFFFFFu
// The root's parent link; a link packs a node index in 30 bits and a slot in 2.
#define VKRAY_BVH_NO_PARENT 0xFFFFFFFFu
#define VKRAY_BVH_MAX_LINKED_NODES (1u << 30)
// Texels of VKRAY_BINDING_NODE_TEXELS (RGBA32UI) per node.
#define VKRAY_BVH_NODE_TEXELS 4
#define VKRAY_BVH_SPHERE_NODE_TEXELS 5

#ifdef __cplusplus
namespace vkray::gpu {
#define VKRAY_BVH_STRUCT(name) struct alignas(16) name
#else
#define VKRAY_BVH_STRUCT(name) struct name
#endif

// A child box's planes on axis a: corner[a] + q 2^(e_a - 127), q the byte of child k (bits 8k..8k+7)
// in that axis' word of lower or upper planes, e_a byte a of `exponents` (1..254).
VKRAY_BVH_STRUCT(GpuBvhNode) {  // 64 bytes: four 16-byte slots
    vec3 corner;     // the grid's corner
    uint exponents;  // bytes 0-2: x, y, z
    uvec4 planesXY;  // children 0-3: lower x, upper x, lower y, upper y planes, a byte each
    uvec4 planesZ;   // lower z, upper z, the node's parent link, 0
    uvec4 child;     // children 0-3: references, VKRAY_BVH_NO_CHILD where unused
};
#define VKRAY_BVH_EXPONENT_BIAS 127

// bvh-sphere (sphere containers, after Mahmuda 2017's box/sphere experiment): the same tree shape
// and references, each child bounded by a sphere instead of a box. The host rounds every radius
// up (accel/bvh/sphere_bounds.h); an unused slot's sphere is never tested.
VKRAY_BVH_STRUCT(GpuBvhSphereNode) {  // 80 bytes: five 16-byte slots
    vec4 centreX, centreY, centreZ;  // children 0-3: sphere centres
    vec4 radius;
    uvec4 child;
};

#ifdef __cplusplus
static_assert(sizeof(GpuBvhSphereNode) == 16 * VKRAY_BVH_SPHERE_NODE_TEXELS && offsetof(GpuBvhSphereNode, radius) == 48 &&
              offsetof(GpuBvhSphereNode, child) == 64);
static_assert(sizeof(GpuBvhNode) == 16 * VKRAY_BVH_NODE_TEXELS && offsetof(GpuBvhNode, exponents) == 12 &&
              offsetof(GpuBvhNode, planesXY) == 16 &&
              offsetof(GpuBvhNode, planesZ) == 32 && offsetof(GpuBvhNode, child) == 48);
static_assert(VKRAY_BVH_MAX_LEAF_SIZE - 1 <= VKRAY_BVH_COUNT_MASK, "leaf counts must fit their bits");
static_assert((VKRAY_BVH_MAX_TRIANGLES + VKRAY_BVH_MAX_LEAF_SIZE) <= VKRAY_BVH_FIRST_MASK,
              "no leaf reference may equal VKRAY_BVH_NO_CHILD");
}  // namespace vkray::gpu
#endif
#undef VKRAY_BVH_STRUCT

#endif  // VKRAY_BVH_LAYOUT_H
