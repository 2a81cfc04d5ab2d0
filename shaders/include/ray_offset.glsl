// Secondary-ray origins pushed off the surface: far enough that the new ray cannot hit the surface
// it starts on (shadow acne), and no farther, so that it still meets occluders nearly touching it
// (thin contacts). The idea is Waechter and Binder's, "A Fast and Robust Method for Avoiding
// Self-Intersection", Ray Tracing Gems (2019), chapter 6: push the hit point along the normal by
// its own floating-point error. Their constants (256 ulps of P per unit of normal, 1/65536
// absolutely where a coordinate is below 1/32) are tuned to scenes of about unit size; measured on
// scenes/stress/far-1e6.scene they pushed shadow rays 16 units off a floor at 1e6 (568 of 3072
// pixels lost a shadow), and on tiny-1e-4.scene by 1.5e-5, more than the 2e-6 plate lying on the
// floor (114 pixels wrong). Here the push follows an error bound instead, after Pharr, Jakob and
// Humphreys, "Physically Based Rendering", 3rd ed., 3.9:
//  - surfaceAt (shading.glsl) computes P = p0 + b1 (p1 - p0) + b2 (p2 - p0). Rounding b1 and b2
//    moves this P within the triangle's plane only; off the plane it carries the rounding of the
//    edge vectors and products, a few u times the triangle's extent, and of the final sum, at most
//    u |P_i| per coordinate (u = 2^-24, the unit roundoff of float);
//  - the new ray's test against the same triangle rounds by a few u times the triangle's extent
//    (its vertices relative to the new origin, Woop et al.'s shear), and so does adding the push.
// So the push is 4 u max|P_i| + 16 u max|edge_i|: at 1e6 a quarter of a unit (4 ulps), 1.2e-6 on a
// unit triangle at unit distance, 1.2e-10 at scale 1e-4; docs/stability.md has what it measured.
#ifndef VKRAY_RAY_OFFSET_GLSL
#define VKRAY_RAY_OFFSET_GLSL

#include "min_max.glsl"

const float kOffsetPerPosition = 1.0 / 4194304.0;  // 4 u = 2^-22
const float kOffsetPerExtent = 1.0 / 1048576.0;    // 16 u = 2^-20

// How far to push a ray starting at P on a triangle with edge vectors e1, e2 (see above). Zero only
// for a triangle collapsed to the point 0, which is never hit.
float offsetDistance(vec3 p, vec3 e1, vec3 e2) {
    const vec3 a = abs(p), e = maxOf(abs(e1), abs(e2));
    return kOffsetPerPosition * maxOf(a.x, maxOf(a.y, a.z)) + kOffsetPerExtent * maxOf(e.x, maxOf(e.y, e.z));
}

// P pushed along the unit vector n (Nf for reflection and shadow rays, -Nf for refraction).
vec3 offsetRayOrigin(vec3 p, vec3 n, float distance) { return p + n * distance; }

#endif
