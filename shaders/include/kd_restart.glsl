// kd-restart (Foley and Sugerman, "KD-Tree Acceleration Structures for a GPU Raytracer", Graphics
// Hardware 2005, section 4.1): stackless. The descent drops the stack traversal's push and only
// shortens tmax; after a leaf without an accepted hit, tmin becomes the leaf's exit and the search
// restarts at the root, until the exit reaches the global tmax. Strict advance: a child is entered
// first only if its plane lies strictly beyond tmin (kdStepInner: thit <= tmin goes second), so
// the leaf just left is never entered again.
#ifndef VKRAY_KD_RESTART_GLSL
#define VKRAY_KD_RESTART_GLSL

#include "kd_common.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

// Passes (KdPass) are an outer loop: llvmpipe runs every statement of a loop body for all lanes,
// masked, so pass switching inside the node loop slowed every step (measured 1.5x).
Hit kdRestartTrace(vec3 origin, vec3 dir, float tmax, const bool anyHit) {
    Hit best = noHit(tmax);
    const KdRay r = makeKdRay(origin, dir);
    const WatertightRay w = makeWatertightRay(origin, dir);
    KdPass pass = kdFirstPass();
    uvec2 walked = uvec2(0u);
    int steps = 0;
    bool passDone = true;
    for (uint passes = 0u; passes < 8u; ++passes) {
        float segMin = 0.0, segMax = tmax;
        uint minAxis = kKdHardBound, maxAxis = kKdHardBound;
        passDone = !kdClipBox(r, kdTree.lo, kdTree.hi, segMin, minAxis, segMax, maxAxis, pass);
        const float globalMax = segMax;
        const uint globalMaxAxis = maxAxis;
        uint node = 0u;
        for (; !passDone && steps < VKRAY_KD_MAX_STEPS; ++steps) {
            countNode();
            const uvec2 n = kdNodes[node];
            if (!kdIsLeaf(n)) {
                uint first, second;
                float thit;
                const int visit = kdStepInner(r, n, node, segMin, minAxis, segMax, maxAxis, pass, first, second, thit);
                node = kdDescend(visit, n, first, second, thit, segMax, maxAxis);
                continue;
            }
            kdVisitLeaf(n, w, anyHit, best);
            if (kdFinished(best, anyHit, segMax) || kdCompare(pass, segMax, maxAxis, globalMax, globalMaxAxis) >= 0) {
                passDone = true;
            } else {  // restart at the root past this leaf
                segMin = segMax;
                minAxis = maxAxis;
                segMax = globalMax;
                maxAxis = globalMaxAxis;
                node = 0u;
                countRestart();
            }
        }
        // Another pass for an in-plane node or a tie met, or the end.
        if (!kdAnotherPass(passDone, anyHit, best, pass, walked)) break;
    }
    kdEndLoop(passDone, steps);
    return best;
}

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return kdRestartTrace(origin, dir, tmax, false); }
bool traceAny(vec3 origin, vec3 dir, float tmax) { return kdRestartTrace(origin, dir, tmax, true).triangle >= 0; }

#endif
