// Bounding spheres for bvh-sphere (bvh.h, Config::Container::Sphere): a triangle's smallest
// enclosing sphere, the smallest sphere enclosing two spheres, and the merged radius AAC's distance
// ranks pairs by. Centres and radii are computed in double and stored in float with the radius
// rounded up against the stored centre, so a sphere holds what it bounds exactly (the traversals
// then only widen for their own rounding).
#pragma once

#include <algorithm>
#include <cmath>

#include "accel/bvh/bvh.h"
#include "scene/scene.h"

namespace vkray::bvh {

// The smallest sphere holding the triangle: on its longest edge as a diameter when the triangle
// has an angle of 90 degrees or more (degenerate triangles included), else its circumsphere.
Sphere triangleSphere(const Triangle& t);

// The smallest sphere holding both (either one when it holds the other).
Sphere mergeSpheres(const Sphere& a, const Sphere& b);

// The radius mergeSpheres(a, b) has, before rounding: max(ra, rb, (|ca - cb| + ra + rb) / 2). For
// ranking candidate pairs only.
inline float mergedRadius(float ax, float ay, float az, float ar, float bx, float by, float bz, float br) {
    const float dx = bx - ax, dy = by - ay, dz = bz - az;
    const float d = std::sqrt(dx * dx + dy * dy + dz * dz);
    return std::max(std::max(ar, br), 0.5f * (d + ar + br));
}

}  // namespace vkray::bvh
