// The `brute` accelerator: every ray is tested against every triangle. The reference the other
// traversals are measured against, usable for small scenes and tests. Its one loop is the leaf loop
// of the other accelerators (leaf_triangles.glsl) run over the whole triangle buffer.
#ifndef VKRAY_BRUTE_FORCE_GLSL
#define VKRAY_BRUTE_FORCE_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "leaf_triangles.glsl"
#include "triangle.glsl"

uint slotTriangle(uint slot) { return slot; }

// Closest hit, or with anyHit the first hit found, in (0, tmax). Ties in t go to the lowest
// triangle identity (beats(), triangle.glsl), as on the CPU and in every other kernel.
// The resumable variant goes on from where the saved traversal stopped, and saves where this one
// stops: brute force alone can need more iterations for one ray than the driver's whole budget.
Hit bruteTrace(vec3 origin, vec3 dir, float tmax, const bool anyHit) {
    Hit best = noHit(tmax);
    uint slot = 0u;
    if (RESUMABLE && gResumeSlot > 0u) {
        slot = gResumeSlot;
        best = gResumeBest;
    }
    const uint begin = slot;
    const bool complete =
        testSlotsFrom(slot, params.counts.x, makeWatertightRay(origin, dir), anyHit, kBruteSlotsPerIteration, best);
    if (RESUMABLE) {
        gResumeSlot = complete ? 0u : slot;
        gResumeBest = best;
        if (slot > begin) gProgress = true;
    }
    return best;
}

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return bruteTrace(origin, dir, tmax, false); }
bool traceAny(vec3 origin, vec3 dir, float tmax) { return bruteTrace(origin, dir, tmax, true).triangle >= 0; }

#endif
