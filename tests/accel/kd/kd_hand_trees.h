// Hand-made kd-trees for rays lying in split planes, walked by the CPU traversals
// (kd_traversal_test.cpp) and by the GPU kernels (tests/gpu/kd_hand_trees_test.cpp). Each
// triangle sits where the builder's one-sided classification puts it (touching a plane from above:
// above only), and a decoy farther along the ray sits on the other side: a walk that takes only one
// side of an in-plane node returns the decoy, or for any hit nothing before tmax.
#pragma once

#include <glm/glm.hpp>

#include "accel/kd/kd_tree.h"
#include "geometry/ray.h"
#include "scene/scene.h"

namespace vkray::test {

struct HandTree {
    Scene scene;             // its triangles only
    accel::kd::KdTree tree;  // with node boxes and parent links (kd-backtrack's)
    geometry::Ray ray;       // lies in the split planes; its nearest hit is triangle 0
    double clearOf = 0.0;    // the ray meets only triangle 0 before this t
};

inline gpu::KdNodeExtra boxOf(glm::vec3 lo, glm::vec3 hi, uint32_t parent) {
    return gpu::KdNodeExtra{lo, parent, hi, 0};
}

// A ray in the plane x = 0, direction +y: triangle 0 touches the plane from above (an edge in it),
// hit at y = 0; triangle 1, the decoy, touches it from below at y = 2.
inline HandTree triangleTouchingThePlaneFromAbove() {
    HandTree h;
    h.scene.triangles = {{{0, 0, -1}, {0, 0, 1}, {1, 0, 0}, 0}, {{0, 2, -1}, {0, 2, 1}, {-1, 2, 0}, 0}};
    h.tree.header = gpu::KdTreeHeader{{-1, -1, -1}, 3, {1, 3, 1}, 2};
    h.tree.nodes = {gpu::KdNode::inner(0, 0.0f, 2), gpu::KdNode::leaf(0, 1), gpu::KdNode::leaf(1, 1)};
    h.tree.indices = {1, 0};
    h.tree.extra = {boxOf({-1, -1, -1}, {1, 3, 1}, VKRAY_KD_NO_PARENT), boxOf({-1, -1, -1}, {0, 3, 1}, 0),
                    boxOf({0, -1, -1}, {1, 3, 1}, 0)};
    h.ray = geometry::Ray{{0.0, -1.0, 0.25}, {0.0, 1.0, 0.0}};
    h.clearOf = 2.0;
    return h;
}

// A ray along the line where two split planes meet (x = 0 and y = 0, direction +z): four leaves
// hold it, and only the fourth side-mask pass (above in x and in y) reaches the nearest triangle.
inline HandTree rayAlongTwoSplitPlanes() {
    HandTree h;
    h.scene.triangles = {{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}, 0},     // x above, y above: hit at z = 1
                         {{0, 0, 2}, {-1, 0, 2}, {0, -1, 2}, 0},   // x below, y below: z = 2
                         {{0, 0, 3}, {-1, 0, 3}, {0, 1, 3}, 0},    // x below, y above: z = 3
                         {{0, 0, 4}, {1, 0, 4}, {0, -1, 4}, 0}};   // x above, y below: z = 4
    const glm::vec3 lo(-1, -1, -1), hi(1, 1, 5);
    h.tree.header = gpu::KdTreeHeader{lo, 7, hi, 4};
    // 0: x = 0; 1: (below) y = 0, leaves 2 and 3; 4: (above) y = 0, leaves 5 and 6.
    h.tree.nodes = {gpu::KdNode::inner(0, 0.0f, 4), gpu::KdNode::inner(1, 0.0f, 3), gpu::KdNode::leaf(0, 1),
                    gpu::KdNode::leaf(1, 1),        gpu::KdNode::inner(1, 0.0f, 6), gpu::KdNode::leaf(2, 1),
                    gpu::KdNode::leaf(3, 1)};
    h.tree.indices = {1, 2, 3, 0};
    h.tree.extra = {boxOf(lo, hi, VKRAY_KD_NO_PARENT),  boxOf(lo, {0, 1, 5}, 0),        boxOf(lo, {0, 0, 5}, 1),
                    boxOf({-1, 0, -1}, {0, 1, 5}, 1),   boxOf({0, -1, -1}, hi, 0),      boxOf({0, -1, -1}, {1, 0, 5}, 4),
                    boxOf({0, 0, -1}, hi, 4)};
    h.ray = geometry::Ray{{0.0, 0.0, -1.0}, {0.0, -0.0, 1.0}};
    h.clearOf = 2.5;
    return h;
}

}  // namespace vkray::test
