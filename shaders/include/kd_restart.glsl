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
//
// kd-ropes is this walk going on by ropes (Popov, Guenther, Seidel and Slusallek, "Stackless KD-Tree
// Traversal for High Performance GPU Ray Tracing", Eurographics 2007, section 3;
// render_kd_ropes.comp defines VKRAY_KD_ROPES): each leaf has its box and, per face, the smallest
// node holding that whole face on its far side, and every node's box (KdRopeRecord in the extra
// binding). After a leaf the walk descends from the rope of the exit face, with the rest of the ray
// clipped to that node's box, not from the root (kdRopeOf, kdEnterRope).
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
#ifdef VKRAY_KD_ROPES
const bool kKdRopes = true;
#else
const bool kKdRopes = false;
#endif

// kd-ropes: whether the rope's node holds the ray at the exit of the leaf whose segment is [segMin,
// segMax], in this pass's order of tied planes, with no plane hit (ropeHoldsExit in
// kd_traversal.cpp, which gives the argument).
bool kdRopeHoldsExit(float segMin, uint minAxis, float segMax, uint maxAxis, float passMin) {
    return segMin != segMax || (minAxis == maxAxis && segMin > passMin);
}

// kd-ropes: the rope of the face by which the ray leaves leaf `leaf` along `exitAxis` (< 3: the
// pass's end would have ended the pass). Selects, not r.dir[exitAxis].
uint kdRopeOf(KdRay r, uint leaf, uint exitAxis) {
    const bool up = (exitAxis == 0u ? r.dir.x : (exitAxis == 1u ? r.dir.y : r.dir.z)) > 0.0;
    const int base = int(VKRAY_KD_ROPE_TEXELS * leaf);
    if (exitAxis == 0u) return extraTexel(base + (up ? 1 : 0)).w;
    const uvec4 yz = extraTexel(base + 2);
    return exitAxis == 1u ? (up ? yz.y : yz.x) : (up ? yz.w : yz.z);
}

// kd-ropes: goes on at node `rope` past the leaf whose exit the segment ends at, the segment from
// the exit to the pass's end clipped to that node's box (a descent from there crosses only the
// node's own splits). False, and the segment untouched, when the ray may not be inside that node yet
// (kdRopeHoldsExit: it left the leaf through an edge or corner in no length): the walk then restarts
// as kd-restart does. KdRestartTracer::walkPass is the CPU twin.
bool kdEnterRope(KdRay r, uint rope, float passMin, float passMax, uint passMaxAxis, inout float segMin,
                 inout uint minAxis, inout float segMax, inout uint maxAxis, inout KdPass pass) {
    const int at = int(VKRAY_KD_ROPE_TEXELS * rope);
    if (!kdRopeHoldsExit(segMin, minAxis, segMax, maxAxis, passMin)) return false;
    const vec3 lo = uintBitsToFloat(extraTexel(at).xyz), hi = uintBitsToFloat(extraTexel(at + 1).xyz);
    segMin = segMax;
    minAxis = maxAxis;
    segMax = passMax;
    maxAxis = passMaxAxis;
    kdBoxExit(r, lo, hi, segMax, maxAxis, pass);
    return true;
}

bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best) {
    const float globalMin = segMin, globalMax = segMax;
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
        } else {
            // kd-ropes: on from the rope of the exit face; none: the ray left the tree. Otherwise (or
            // when the rope's node does not hold the ray yet) restart past this leaf, at the root (at
            // the pushed-down node with push-down).
            const uint rope = kKdRopes ? kdRopeOf(r, node, maxAxis) : VKRAY_KD_NO_ROPE;
            passDone = kKdRopes && rope == VKRAY_KD_NO_ROPE;
            if (kKdRopes && !passDone && kdEnterRope(r, rope, globalMin, globalMax, globalMaxAxis, segMin, minAxis, segMax, maxAxis, pass))
                node = rope;
            else if (!passDone)
                node = kdRestart(restart, globalMax, globalMaxAxis, segMin, minAxis, segMax, maxAxis);
        }
    }
    return passDone;
}

#endif
