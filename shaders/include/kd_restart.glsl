// kd-restart (Foley and Sugerman, "KD-Tree Acceleration Structures for a GPU Raytracer", Graphics
// Hardware 2005, section 4.1): stackless. The descent drops the stack traversal's push and only
// shortens tmax; after a leaf without an accepted hit, tmin becomes the leaf's exit and the search
// restarts at the root, until the exit reaches the global tmax. Strict advance: a child is entered
// first only if its plane lies strictly beyond tmin (kdStepInner: thit <= tmin goes second), so
// the leaf just left is never entered again. The passes around this walk are kdTrace's
// (kd_common.glsl).
//
// kd-pushdown is this walk with push-down (Horn, Sugerman, Houston and Hanrahan, "Interactive k-D
// Tree GPU Raytracing", I3D 2007, section 4.1; render_kd_pushdown.comp defines
// VKRAY_KD_PUSH_DOWN): a restart begins at the deepest node whose region holds the whole rest of
// the ray, the last node a descent entered before it first reached both children of a node
// (KdRestartTracer::walkPass explains why the steps below it are those of a restart from the root).
#ifndef VKRAY_KD_RESTART_GLSL
#define VKRAY_KD_RESTART_GLSL

#include "kd_common.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

#ifdef VKRAY_KD_PUSH_DOWN
const bool kKdPushDown = true;
#else
const bool kKdPushDown = false;
#endif

bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best) {
    const float globalMax = segMax;
    const uint globalMaxAxis = maxAxis;
    uint node = 0u;
    KdRestartPoint restart = kdRootRestart();
    bool passDone = false;
    while (budgetLeft() && !passDone && steps < VKRAY_KD_MAX_STEPS) {
        // Down to the next leaf (kd_common.glsl, "Loops").
        uvec2 n = kdNode(node);
        for (; budgetLeft() && !kdIsLeaf(n) && steps < VKRAY_KD_MAX_STEPS; ++steps) {
            countNode();
            uint first, second;
            float thit;
            const int visit = kdStepInner(r, n, node, segMin, minAxis, segMax, maxAxis, pass, first, second, thit);
            node = kdDescend(visit, n, first, second, thit, segMin, minAxis, segMax, maxAxis);
            kdEntered(restart, kKdPushDown, visit, node);
            n = kdNode(node);
        }
        if (!kdLeafStep(n, steps)) break;  // the cap, or the driver
        kdVisitLeaf(n, w, anyHit, best);
        if (kdFinished(best, anyHit, segMax) || kdCompare(pass, segMax, maxAxis, globalMax, globalMaxAxis) >= 0) {
            passDone = true;
        } else {  // restart past this leaf, at the root (at the pushed-down node with push-down)
            node = kdRestart(restart, globalMax, globalMaxAxis, segMin, minAxis, segMax, maxAxis);
        }
    }
    return passDone;
}

#endif
