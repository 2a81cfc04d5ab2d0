// What the builders need of each triangle: its box and centroid, plus the bounds of both.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"
#include "scene/scene.h"

namespace vkray::bvh {

struct PrimitiveSet {
    BuildArray<Aabb> boxes;           // per triangle, in triangle-identity order
    BuildArray<glm::vec3> centroids;  // (p0 + p1 + p2) / 3
    std::vector<Sphere> spheres;       // sphere containers only: per triangle, its smallest sphere
    Aabb bounds;                       // of all boxes
    Aabb centroidBounds;               // of all centroids (Morton codes and SAH bins live in it)

    size_t size() const { return boxes.size(); }
};

// Boxes and centroids (and with `spheres`, the triangles' spheres) computed in parallel; the bounds
// are min/max reductions, exact in any order.
PrimitiveSet primitivesOf(std::span<const Triangle> triangles, bool spheres = false);

}  // namespace vkray::bvh
