// What the two walks of the 4-wide BVH share (bvh_traversal.glsl, the stack walk of `bvh`;
// bvh_stackless.glsl, `bvh-stackless`): the node fetch through the texel view, the slab test of a
// node's four children, and leaf references. Layout: shared/bvh_layout.h.
#ifndef VKRAY_BVH_COMMON_GLSL
#define VKRAY_BVH_COMMON_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "constants.glsl"
#include "shared/bvh_layout.h"
#include "trace_status.glsl"

// Node `index`, through the nodes' texel view.
GpuBvhNode loadBvhNode(uint index) {
    const int k = int(uint(VKRAY_BVH_NODE_TEXELS) * index);
    GpuBvhNode n;
    n.loX = uintBitsToFloat(texelFetch(nodeTexels, k));
    n.hiX = uintBitsToFloat(texelFetch(nodeTexels, k + 1));
    n.loY = uintBitsToFloat(texelFetch(nodeTexels, k + 2));
    n.hiY = uintBitsToFloat(texelFetch(nodeTexels, k + 3));
    n.loZ = uintBitsToFloat(texelFetch(nodeTexels, k + 4));
    n.hiZ = uintBitsToFloat(texelFetch(nodeTexels, k + 5));
    n.child = texelFetch(nodeTexels, k + 6);
    return n;
}

// Below this magnitude a direction component counts as zero: its inverse would overflow.
const float kFlatDirection = 1.0e-30;

// Per-ray constants of the slab test. A direction component of +-0 gets inverse 0 (never inf, so
// no 0 * inf = NaN can reach min/max) and a flag: the ray then stays in the plane x_a = origin_a,
// which is inside the slab for every t or for none.
struct BoxRay {
    vec3 origin;
    vec3 inv;
    bvec3 flat_;
    vec3 flatExit;  // +inf on a flat axis, 0 otherwise: added to that axis' exit distances
};

BoxRay makeBoxRay(vec3 origin, vec3 dir) {
    BoxRay r;
    r.origin = origin;
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
    tNear = min(t0, t1);
    tFar = max(t0, t1) + flatExit;  // a flat axis bounds no exit (inside) or none matters (outside)
    outside = flatAxis ? dl * dh : vec4(0.0);
}

// Which of the node's children the ray meets for t in [0, tLimit]; tEnter = where it enters each.
bvec4 hitsChildren(GpuBvhNode n, BoxRay r, float tLimit, out vec4 tEnter) {
    vec4 nearX, farX, nearY, farY, nearZ, farZ, outX, outY, outZ;
    slab4(n.loX, n.hiX, r.origin.x, r.inv.x, r.flat_.x, r.flatExit.x, nearX, farX, outX);
    slab4(n.loY, n.hiY, r.origin.y, r.inv.y, r.flat_.y, r.flatExit.y, nearY, farY, outY);
    slab4(n.loZ, n.hiZ, r.origin.z, r.inv.z, r.flat_.z, r.flatExit.z, nearZ, farZ, outZ);
    tEnter = max(max(nearX, nearY), max(nearZ, vec4(0.0)));
    // The far distance widened for float rounding, so a box never rejects a ray that touches it.
    const vec4 tExit = min(min(farX, farY), min(farZ, vec4(tLimit))) * kRoundingSlack;
    const vec4 outside = max(max(outX, outY), outZ);
    return bvec4(uvec4(lessThanEqual(tEnter, tExit)) * uvec4(lessThanEqual(outside, vec4(0.0))) *
                 uvec4(notEqual(n.child, uvec4(VKRAY_BVH_NO_CHILD))));
}

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
