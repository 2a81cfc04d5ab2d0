// The wide node's child boxes as bytes in a grid of the node's own (shared/bvh_layout.h,
// GpuBvhNode; Ylitie, Karras and Laine, "Efficient Incoherent Ray Traversal on GPUs Through
// Compressed Wide BVHs", HPG 2017, section 3.1): per axis a float corner at or below the children's
// minimum (aligned with a flat child where that helps) and a power-of-two step whose 255 steps reach
// their maximum; each plane rounded outwards to the grid, so a byte box always holds the child's box.
#pragma once

#include <span>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"

namespace vkray::bvh {

// The node of up to VKRAY_BVH_WIDTH children: boxes[k] bounds the child of reference child[k]
// (unused slots: VKRAY_BVH_NO_CHILD, their planes 0). Every box must be non-empty and finite. Its
// parent link (planesZ.z) is VKRAY_BVH_NO_PARENT: gpuNodes (flatten.h) links the tree's nodes.
gpu::GpuBvhNode quantizedNode(std::span<const Aabb> boxes, const gpu::uvec4& child);

// Child k's box as the kernel's planes, in double, where every such plane is exact.
struct GridBox {
    glm::dvec3 lo, hi;

    bool contains(const Aabb& b) const {
        return glm::all(glm::lessThanEqual(lo, glm::dvec3(b.lo))) &&
               glm::all(glm::greaterThanEqual(hi, glm::dvec3(b.hi)));
    }
};
GridBox gridBox(const gpu::GpuBvhNode& node, int k);
// The grid's step on axis a: 2^(e_a - VKRAY_BVH_EXPONENT_BIAS).
double gridStep(const gpu::GpuBvhNode& node, int a);

}  // namespace vkray::bvh
