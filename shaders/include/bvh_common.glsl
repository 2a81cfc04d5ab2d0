// What the two walks of the 4-wide BVH share (bvh_traversal.glsl, the stack walk of `bvh`;
// bvh_stackless.glsl, `bvh-stackless`): the node fetch through the texel view, the test of a node's
// four children, and leaf references. Layout: shared/bvh_layout.h. A kernel that defines
// VKRAY_BVH_SPHERES before including this (render_bvh_sphere.comp) walks sphere containers
// (GpuBvhSphereNode) instead of boxes: only the node type, its fetch and its test change.
#ifndef VKRAY_BVH_COMMON_GLSL
#define VKRAY_BVH_COMMON_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "constants.glsl"
#include "min_max.glsl"
#include "shared/bvh_layout.h"
#include "trace_status.glsl"

#ifdef VKRAY_BVH_SPHERES
#define BvhNode GpuBvhSphereNode
#else
#define BvhNode GpuBvhNode
#endif

#ifdef VKRAY_BVH_SPHERES
// Node `index`, through the nodes' texel view.
GpuBvhSphereNode loadBvhNode(uint index) {
    const int k = int(uint(VKRAY_BVH_SPHERE_NODE_TEXELS) * index);
    return GpuBvhSphereNode(nodeFloatTexel(k), nodeFloatTexel(k + 1), nodeFloatTexel(k + 2), nodeFloatTexel(k + 3),
                            nodeTexel(k + 4));
}
#else
// Node `index`, through the nodes' texel view.
GpuBvhNode loadBvhNode(uint index) {
    const int k = int(uint(VKRAY_BVH_NODE_TEXELS) * index);
    return GpuBvhNode(nodeFloatTexel(k), nodeFloatTexel(k + 1), nodeFloatTexel(k + 2), nodeFloatTexel(k + 3),
                      nodeFloatTexel(k + 4), nodeFloatTexel(k + 5), nodeTexel(k + 6));
}
#endif

// Below this magnitude a direction component counts as zero: its inverse would overflow.
const float kFlatDirection = 1.0e-30;

// Per-ray constants of the node tests. Slab test: a direction component of +-0 gets inverse 0
// (never inf, so no 0 * inf = NaN can reach min/max) and a flag: the ray then stays in the plane
// x_a = origin_a, which is inside the slab for every t or for none. Each kernel keeps only what its
// test reads.
struct BoxRay {
    vec3 origin;
    vec3 inv;
    bvec3 flat_;
    vec3 flatExit;  // +inf on a flat axis, 0 otherwise: added to that axis' exit distances
    vec3 dir;       // sphere test
    float invDirLength2;
};

BoxRay makeBoxRay(vec3 origin, vec3 dir) {
    BoxRay r;
    r.origin = origin;
    r.dir = dir;
    r.invDirLength2 = 1.0 / dot(dir, dir);
    r.flat_ = lessThan(abs(dir), vec3(kFlatDirection));
    r.inv = mix(1.0 / dir, vec3(0.0), r.flat_);
    r.flatExit = mix(vec3(0.0), vec3(kInfinity), r.flat_);
    return r;
}

// One axis of the slab test for the four children: the parameter interval of each slab, and for a
// flat axis (inverse 0, so the interval is +-0 at both ends) the product (lo - o)(hi - o), which
// is positive exactly when the origin lies outside the slab (the signs of a float difference and
// product are exact; one that underflows to 0 counts as inside, which only costs a visit), 0 on
// the other axes. The flat case is selects on values the slab test computes anyway: llvmpipe runs
// every `if` body for all lanes, and an `if` here that compared the origin with both planes again
// cost 7% of a camera-ray render (docs/benchmarks.md, "A third round").
void slab4(vec4 lo, vec4 hi, float origin, float inv, bool flatAxis, float flatExit, out vec4 tNear, out vec4 tFar,
           out vec4 outside) {
    const vec4 dl = lo - origin, dh = hi - origin;
    const vec4 t0 = dl * inv, t1 = dh * inv;
    tNear = minOf(t0, t1);
    tFar = maxOf(t0, t1) + flatExit;  // a flat axis bounds no exit (inside) or none matters (outside)
    outside = flatAxis ? dl * dh : vec4(0.0);
}

#ifdef VKRAY_BVH_SPHERES
// Which of the node's children's spheres the ray meets for t in [0, tLimit]; tEnter = where it
// enters each. From the squared distance of the centre to the ray's line, not the quadratic's
// discriminant, which cancels catastrophically for spheres small against their distance (Haines,
// Günther and Akenine-Möller, "Precision Improvements for Ray/Sphere Intersection", Ray Tracing
// Gems, 2019). The radius is widened by the few ulps of |centre - origin| that the line's closest
// point can be off by, so a sphere never rejects a ray that meets it.
bvec4 hitsChildren(GpuBvhSphereNode n, BoxRay r, float tLimit, out vec4 tEnter) {
    const vec4 ox = n.centreX - r.origin.x, oy = n.centreY - r.origin.y, oz = n.centreZ - r.origin.z;
    const vec4 tc = (ox * r.dir.x + oy * r.dir.y + oz * r.dir.z) * r.invDirLength2;  // closest approach
    const vec4 lx = ox - tc * r.dir.x, ly = oy - tc * r.dir.y, lz = oz - tc * r.dir.z;
    const vec4 dist2 = lx * lx + ly * ly + lz * lz;
    const vec4 radius = n.radius * kRoundingSlack + 1.0e-6 * (abs(ox) + abs(oy) + abs(oz));
    const vec4 h2 = radius * radius - dist2;
    const vec4 half_ = sqrt(maxOf(h2, vec4(0.0)) * r.invDirLength2);
    tEnter = maxOf(tc - half_, vec4(0.0));
    const vec4 tExit = minOf(tc + half_, vec4(tLimit)) * kRoundingSlack;
    return bvec4(uvec4(lessThanEqual(tEnter, tExit)) * uvec4(greaterThanEqual(h2, vec4(0.0))) *
                 uvec4(notEqual(n.child, uvec4(VKRAY_BVH_NO_CHILD))));
}
#else
// Which of the node's children the ray meets for t in [0, tLimit]; tEnter = where it enters each.
bvec4 hitsChildren(GpuBvhNode n, BoxRay r, float tLimit, out vec4 tEnter) {
    vec4 nearX, farX, nearY, farY, nearZ, farZ, outX, outY, outZ;
    slab4(n.loX, n.hiX, r.origin.x, r.inv.x, r.flat_.x, r.flatExit.x, nearX, farX, outX);
    slab4(n.loY, n.hiY, r.origin.y, r.inv.y, r.flat_.y, r.flatExit.y, nearY, farY, outY);
    slab4(n.loZ, n.hiZ, r.origin.z, r.inv.z, r.flat_.z, r.flatExit.z, nearZ, farZ, outZ);
    tEnter = maxOf(maxOf(nearX, nearY), maxOf(nearZ, vec4(0.0)));
    // The far distance widened for float rounding, so a box never rejects a ray that touches it.
    const vec4 tExit = minOf(minOf(farX, farY), minOf(farZ, vec4(tLimit))) * kRoundingSlack;
    const vec4 outside = maxOf(maxOf(outX, outY), outZ);
    return bvec4(uvec4(lessThanEqual(tEnter, tExit)) * uvec4(lessThanEqual(outside, vec4(0.0))) *
                 uvec4(notEqual(n.child, uvec4(VKRAY_BVH_NO_CHILD))));
}
#endif

// Leaves are runs of the triangle buffer in leaf order: Hit.triangle is a slot of it.
uint slotTriangle(uint slot) { return slot; }

bool isLeafRef(uint ref) { return (ref & VKRAY_BVH_LEAF_BIT) != 0u; }

// The leaf reference's triangle slots [first, first + count).
uint leafFirst(uint ref) { return ref & VKRAY_BVH_FIRST_MASK; }
uint leafCount(uint ref) { return ((ref >> VKRAY_BVH_COUNT_SHIFT) & VKRAY_BVH_COUNT_MASK) + 1u; }

// A walk ended: if not by its own exit, either the cap (a runaway ray, counted) or the driver
// (llvmpipe's loop budget: the pixel is flagged).
void bvhEndLoop(bool done, int iteration) {
    if (done) return;
    if (iteration >= VKRAY_BVH_MAX_ITERATIONS) ++gCappedRays;
    else gLoopCutShort = true;
}

#endif
