// The `brute` accelerator: every ray is tested against every triangle. The reference the other
// traversals are measured against, usable for small scenes and tests.
//
// The loops test kBruteBatch triangles per iteration, which multiplies the scene size brute force
// handles under lavapipe's loop budget (trace_status.glsl), and report a loop cut short.
#ifndef VKRAY_BRUTE_FORCE_GLSL
#define VKRAY_BRUTE_FORCE_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

const uint kBruteBatch = 4;

// Closest hit in (0, tmax). Ties in t go to the lowest triangle index (beats(), triangle.glsl), as
// on the CPU and in every other kernel.
Hit traceClosest(vec3 origin, vec3 dir, float tmax) {
    Hit best = noHit(tmax);
    const uint count = params.counts.x;
    const WatertightRay ray = makeWatertightRay(origin, dir);
    uint i = 0;
    for (; i < count; i += kBruteBatch) {
        closestInSlot(i, count, ray, best);
        closestInSlot(i + 1, count, ray, best);
        closestInSlot(i + 2, count, ray, best);
        closestInSlot(i + 3, count, ray, best);
    }
    if (i < count) gLoopCutShort = true;
    countTriangles(count);
    return best;
}

// Any hit in (0, tmax): shadow rays stop at the first occluder.
bool traceAny(vec3 origin, vec3 dir, float tmax) {
    const uint count = params.counts.x;
    const WatertightRay ray = makeWatertightRay(origin, dir);
    bool occluded = false;
    uint i = 0;
    for (; i < count && !occluded; i += kBruteBatch)
        occluded = occludesInSlot(i, count, ray, tmax) || occludesInSlot(i + 1, count, ray, tmax) ||
                   occludesInSlot(i + 2, count, ray, tmax) || occludesInSlot(i + 3, count, ray, tmax);
    if (!occluded && i < count) gLoopCutShort = true;
    countTriangles(min(i, count));
    return occluded;
}

#endif
