// Ray-triangle intersection in double precision, watertight after Woop, Benthin and Wald,
// "Watertight Ray/Triangle Intersection", JCGT 2(1), 2013: a ray through an edge or a vertex shared
// by two triangles of a closed mesh hits at least one of them, never neither.
//
// Edge cases, by definition:
// - a hit needs t strictly inside (tmin, tmax), and above its own rounding error (16 ulps of the
//   vertices' distances along the ray): a ray starting on a triangle's plane never hits it;
// - a point on an edge or a vertex counts as inside (both triangles of a shared edge report it);
// - a ray parallel to the triangle's plane misses (its projected triangle has zero area, det = 0,
//   or the origin lies outside it), and so does a ray lying in the plane whenever that projected
//   area rounds to exactly zero (always so for axis-aligned planes and rays);
// - a degenerate triangle (collinear vertices: zero area, exactly tested) never hits.
#pragma once

#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "geometry/ray.h"

namespace vkray::geometry {

using TriangleVertices = std::array<glm::dvec3, 3>;

struct TriangleHit {
    double t = 0.0;
    double b0 = 0.0, b1 = 0.0, b2 = 0.0;  // barycentrics: the point is b0 p0 + b1 p1 + b2 p2
};

// The per-ray part of the watertight test (the paper's "precalculations"): the dominant axis of
// the direction becomes z and a shear maps the direction onto +z, so each triangle reduces to a 2D
// point-in-triangle test at the origin. Compute it once per ray, reuse it for every triangle.
class WatertightRay {
public:
    explicit WatertightRay(const Ray& ray);

    std::optional<TriangleHit> intersect(const TriangleVertices& tri, double tmin, double tmax) const;

private:
    glm::dvec3 origin_;
    int kx_, ky_, kz_;      // permutation of the axes; kz = dominant axis of the direction
    double sx_, sy_, sz_;   // shear constants
};

// One-off convenience form of WatertightRay(ray).intersect(tri, tmin, tmax).
std::optional<TriangleHit> intersectTriangle(const Ray& ray, const TriangleVertices& tri, double tmin,
                                             double tmax);

// a*b - c*d with the exact sign (zero exactly when a*b == c*d), by Kahan's fma algorithm, whose
// relative error is at most 2 ulps (Jeannerod, Louvet and Muller, Math. Comp. 82, 2013).
double differenceOfProducts(double a, double b, double c, double d);

// Whether the three vertices are collinear (zero area), decided exactly up to the rounding of the
// edge vectors p1 - p0 and p2 - p0 (exact for float vertices within 2^29 of each other's scale).
bool isDegenerate(const TriangleVertices& tri);

}  // namespace vkray::geometry
