// What the walks of the 4-wide BVH share (bvh_traversal.glsl, the stack walk of closest hits;
// bvh_stackless.glsl, the stackless walk; bvh_packet.glsl, the packet walk): the node fetch through
// the texel view, the test of a node's four children, their sort, and leaf references. Layout: shared/bvh_layout.h. A kernel that defines
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
    const uvec4 grid = nodeTexel(k);
    return GpuBvhNode(uintBitsToFloat(grid.xyz), grid.w, nodeTexel(k + 1), nodeTexel(k + 2), nodeTexel(k + 3));
}
#endif

// Below this magnitude a direction component counts as zero: its inverse would overflow.
const float kFlatDirection = 1.0e-30;

// Per-ray constants of the node tests. Box test: a direction component under kFlatDirection gets
// the inverse 1e30 instead of 1 / d (inf, or 1e30 and more): a slab it lies inside then spans
// [-huge, +huge] and one it lies outside starts or ends beyond any hit, and where the two meet (a
// ray in a box face's plane) the margin of the box test, which grows with the distances, keeps
// the box (see gridSlab4) whenever the node is wider on that axis than 1e-24 of the hit distance.
// Narrower is a node of children all flat in the ray's own plane, whose triangles the ray cannot
// hit (a ray in a triangle's plane misses it, triangle.glsl), or of coordinates below 1e-17 of the
// hit distance, where a float extent can be that small. Each kernel keeps only what its test reads.
struct BoxRay {
    vec3 origin;
    vec3 inv;
    bvec3 down;  // inv < 0: the upper planes are the near ones
    vec3 dir;    // sphere test
    float invDirLength2;
};

BoxRay makeBoxRay(vec3 origin, vec3 dir) {
    BoxRay r;
    r.origin = origin;
    r.dir = dir;
    r.invDirLength2 = 1.0 / dot(dir, dir);
    r.inv = mix(1.0 / dir, vec3(1.0e30), lessThan(abs(dir), vec3(kFlatDirection)));
    r.down = lessThan(r.inv, vec3(0.0));
    return r;
}

// Relative margin of a box test's distances: the float errors below are a few ulps (2^-24 each) of
// the terms' magnitudes, and a GPU's 1 / d may be 2.5 ulp off; 1e-6 is 16 ulps.
const float kBoxSlack = 1.0e-6;

// One axis of the box test for the four children, in the node's grid (Ylitie, Karras and Laine
// 2017, section 4): plane c + q 2^e is met at t = q a + b with a = 2^e inv and b = (c - o) inv,
// one multiply-add a plane instead of decoding it and then (plane - o) inv. The near and far
// planes of each slab are picked by the ray's sign (their bytes). The errors: a is exact (a power
// of two times inv); b is two roundings off; the multiply-add (one rounding, or two where the
// device does not fuse it) adds one more, of a result no larger than q |a| + |b|: in all a few
// ulps of q |a| + |b|, with inv's own error. Each distance is moved out by kBoxSlack of
// q |a| + |b| (plus 1e-30 for what underflows), folded into a and b since q >= 0, so the interval
// [tNear, tFar] holds the exact one and no box is rejected that the ray meets. A distance that
// overflows is an infinity of the right sign; an inf - inf (NaN) drops out of the chains of minOf /
// maxOf that combine the axes (each returns its second operand for a NaN first one, and the chains
// end in 0 and tLimit), which only drops that axis' bound: the box is kept.
// `exponent`: the axis' exponent byte in bits 0-7 (higher bits ignored).
void gridSlab4(uint lowerBytes, uint upperBytes, float corner, uint exponent, float origin, float inv, bool down,
               out vec4 tNear, out vec4 tFar) {
    const float a = uintBitsToFloat((exponent & 255u) << 23) * inv;
    const float b = (corner - origin) * inv;
    const float slackA = kBoxSlack * abs(a), slackB = kBoxSlack * abs(b) + 1.0e-30;
    const uvec4 shifts = uvec4(0u, 8u, 16u, 24u);
    const vec4 qNear = vec4((uvec4(down ? upperBytes : lowerBytes) >> shifts) & 255u);
    const vec4 qFar = vec4((uvec4(down ? lowerBytes : upperBytes) >> shifts) & 255u);
    tNear = qNear * (a - slackA) + (b - slackB);
    tFar = qFar * (a + slackA) + (b + slackB);
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
// Which of the node's children the ray meets for t in [0, tLimit]; tEnter = where it enters each
// (at most: each distance is a bound, gridSlab4).
bvec4 hitsChildren(GpuBvhNode n, BoxRay r, float tLimit, out vec4 tEnter) {
    vec4 nearX, farX, nearY, farY, nearZ, farZ;
    gridSlab4(n.planesXY.x, n.planesXY.y, n.corner.x, n.exponents, r.origin.x, r.inv.x, r.down.x, nearX, farX);
    gridSlab4(n.planesXY.z, n.planesXY.w, n.corner.y, n.exponents >> 8u, r.origin.y, r.inv.y, r.down.y, nearY, farY);
    gridSlab4(n.planesZ.x, n.planesZ.y, n.corner.z, n.exponents >> 16u, r.origin.z, r.inv.z, r.down.z, nearZ, farZ);
    tEnter = maxOf(maxOf(nearX, nearY), maxOf(nearZ, vec4(0.0)));
    const vec4 tExit = minOf(minOf(farX, farY), minOf(farZ, vec4(tLimit)));
    return bvec4(uvec4(lessThanEqual(tEnter, tExit)) * uvec4(notEqual(n.child, uvec4(VKRAY_BVH_NO_CHILD))));
}
#endif

// Orders entries a and b of (key, ref, also) by key.
void sortPair(inout vec4 key, inout uvec4 ref, inout uvec4 also, int a, int b) {
    if (key[b] < key[a]) {
        const float k = key[a];
        key[a] = key[b];
        key[b] = k;
        const uint r = ref[a];
        ref[a] = ref[b];
        ref[b] = r;
        const uint o = also[a];
        also[a] = also[b];
        also[b] = o;
    }
}

// (key, ref, also) in the order of key: a sorting network of five compare-swaps, one network for
// two payloads (the packet walk's children and its lane's entry distances).
void sortByKey(inout vec4 key, inout uvec4 ref, inout uvec4 also) {
    sortPair(key, ref, also, 0, 1);
    sortPair(key, ref, also, 2, 3);
    sortPair(key, ref, also, 0, 2);
    sortPair(key, ref, also, 1, 3);
    sortPair(key, ref, also, 1, 2);
}

// (key, ref) in the order of key: the network above with an unused second payload, whose swaps the
// compiler drops as dead code.
void sortByKey(inout vec4 key, inout uvec4 ref) {
    uvec4 unused = uvec4(0u);
    sortByKey(key, ref, unused);
}

// The stack walks' push (bvh_traversal.glsl, bvh_packet.glsl): entries 1 .. HITS - 1 of the sorted
// children (KIDS, ENTER), farthest first, so the nearest pops next, onto `stackRef`/`stackEnter` at
// `top`; `iteration` counts the passes. A loop of hits - 1 passes, not three pushes under `if`s:
// llvmpipe runs an `if` body for all lanes, and its masked store into a local array reads and
// writes back every lane's entry whether or not the lane pushes; a loop stops when no lane has an
// entry left (docs/performance.md, "What lavapipe charges for"). A macro, not a function: GLSL
// passes arrays by copy.
#define VKRAY_BVH_PUSH_REST(KIDS, ENTER, HITS)                                     \
    {                                                                              \
        uvec4 pushRef = (KIDS).yzwx;                                               \
        vec4 pushEnter = (ENTER).yzwx;                                             \
        int slot = top + (HITS) - 2;                                               \
        for (int i = 1; countPass() && i < (HITS); ++i) {                          \
            stackRef[slot] = pushRef.x;                                            \
            stackEnter[slot] = pushEnter.x;                                        \
            --slot;                                                                \
            pushRef = pushRef.yzwx;                                                \
            pushEnter = pushEnter.yzwx;                                            \
        }                                                                          \
        const int pushes = max((HITS) - 1, 0);                                     \
        top += pushes;                                                             \
        iteration += pushes; /* the pushes' passes count against the cap too */    \
    }

// Node `index`'s parent link, parent << 2 | its slot there (shared/bvh_layout.h): in the node itself
// for boxes, in the index view for spheres.
#ifdef VKRAY_BVH_SPHERES
uint bvhParentLink(uint index, GpuBvhSphereNode n) { return indexTexel(int(index)).x; }
#else
uint bvhParentLink(uint index, GpuBvhNode n) { return n.planesZ.z; }
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
