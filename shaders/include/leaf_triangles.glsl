// The one loop that tests a run of triangles: brute force runs it over the whole triangle buffer,
// the BVH and the kd-tree over a leaf. Four triangles per iteration divide a ray's iterations by
// four, which keeps the loops of a pixel far below lavapipe's budget of 65535 iterations
// (trace_status.glsl) and multiplies the scene size brute force can handle under it.
#ifndef VKRAY_LEAF_TRIANGLES_GLSL
#define VKRAY_LEAF_TRIANGLES_GLSL

#include "bindings.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

// The triangle listed in `slot` of a leaf: an index into the triangle buffer. Defined by the
// accelerator include: the slot itself for brute force and the BVH (whose leaves are runs of the
// buffer in leaf order), kdIndices[slot] for the kd-tree (whose leaves share triangles through an
// index list).
uint slotTriangle(uint slot);

// Any hit asks only whether: it records the triangle in `best` and keeps best.t, the ray's tmax, so
// it neither loads the triangle's identity nor computes uv as the closest-hit update does. (Any hit
// through closestTriangle, or testSlot written with early returns, made the brute-force kernel,
// nearly all shadow rays, 4-9% slower on lavapipe; docs/benchmarks.md, "One loop per traversal".)
void anyTriangle(uint triangle, WatertightRay ray, inout Hit best) {
    float t;
    vec2 uv;
    if (hitTriangle(ray, triangles[triangle], t, uv) && t < best.t) best.triangle = int(triangle);
}

// Slot `slot` when below `end`: the last iteration's four slots may run past the end.
void testSlot(uint slot, uint end, WatertightRay ray, const bool anyHit, inout Hit best) {
    if (slot < end) {
        if (anyHit) anyTriangle(slotTriangle(slot), ray, best);
        else closestTriangle(slotTriangle(slot), ray, best);
    }
}

// Tests slots [begin, end) on (0, best.t) and keeps every hit that beats `best` (beats(),
// triangle.glsl). With anyHit (a constant at every call, so the compiler folds it) the loop ends at
// the first hit: best.triangle >= 0, best.t unchanged. Returns false, with the pixel flagged, if the
// driver ended the loop before either; the triangles counted are those the loop reached.
bool testSlots(uint begin, uint end, WatertightRay ray, const bool anyHit, inout Hit best) {
    uint i = begin;
    for (; i < end && !(anyHit && best.triangle >= 0); i += 4u) {  // 4 slots per iteration
        testSlot(i, end, ray, anyHit, best);
        testSlot(i + 1u, end, ray, anyHit, best);
        testSlot(i + 2u, end, ray, anyHit, best);
        testSlot(i + 3u, end, ray, anyHit, best);
    }
    countTriangles(min(i, end) - begin);
    const bool complete = i >= end || (anyHit && best.triangle >= 0);
    if (!complete) gLoopCutShort = true;
    return complete;
}

#endif
