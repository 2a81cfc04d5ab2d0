// Spheres of the .scene format become triangles on load (docs/scene-format.md: `sphere x y z r`
// is tessellated under the current transform), so every accelerator and renderer sees only triangles.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene_builder.h"
#include "scene/transform.h"

namespace vkray {

// `spheresteps` bounds and default. 16 stacks x 32 slices = 960 triangles: smooth silhouettes at
// 640x480 while a brute-force renderer still copes with a handful of spheres.
constexpr int kMinSphereSteps = 3;
constexpr int kMaxSphereSteps = 512;
constexpr int kDefaultSphereSteps = 16;

// Number of triangles of a sphere with `steps` stacks and 2*steps slices: a fan of 2*steps
// triangles at each pole and two per quad in between, 4*steps*(steps-1).
constexpr int64_t sphereTriangleCount(int steps) { return 4 * int64_t(steps) * (steps - 1); }

// The unit sphere as triangles of unit vectors (each vertex is also its own normal), counter-
// clockwise seen from outside, ordered stack by stack from +y down, slice by slice around y.
std::vector<TriPoints> unitSphereTriangles(int steps);

// Appends the sphere (centre, radius in the object space of `toWorld`) with smooth normals: the
// analytic normal transformed by the inverse transpose. Returns false when a vertex does not fit
// a float (see SceneBuilder); triangles appended before that stay.
[[nodiscard]] bool appendSphere(SceneBuilder& out, const Transform& toWorld, const glm::dvec3& centre,
                                double radius, int steps, uint32_t material);

}  // namespace vkray
