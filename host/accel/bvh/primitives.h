// What the builders need of each triangle: its box and centroid, plus the bounds of both.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"
#include "scene/scene.h"

namespace vkray::bvh {

struct PrimitiveSet {
    std::vector<Aabb> boxes;           // per triangle, in triangle-identity order
    std::vector<glm::vec3> centroids;  // (p0 + p1 + p2) / 3
    Aabb bounds;                       // of all boxes
    Aabb centroidBounds;               // of all centroids (Morton codes and SAH bins live in it)

    size_t size() const { return boxes.size(); }
};

// Boxes and centroids computed in parallel; the bounds are min/max reductions, exact in any order.
PrimitiveSet primitivesOf(std::span<const Triangle> triangles);

}  // namespace vkray::bvh
