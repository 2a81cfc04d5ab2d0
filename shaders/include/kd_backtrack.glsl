// kd-backtrack (Foley and Sugerman, "KD-Tree Acceleration Structures for a GPU Raytracer", Graphics
// Hardware 2005, section 4.2): stackless, with a parent link and a box per node in a separate array
// (VKRAY_BINDING_EXTRA_TEXELS) that only this kernel reads. After a leaf without an accepted hit,
// tmin becomes the leaf's exit and the search climbs the parent links to the nearest ancestor whose
// box the remaining segment still crosses for a positive length (exit > tmin), then descends from
// there; a climbing step computes only the box's exit (kdClimbStep). Climbing and descending steps
// share one step cap. The passes around this walk are
// kdTrace's (kd_common.glsl).
#ifndef VKRAY_KD_BACKTRACK_GLSL
#define VKRAY_KD_BACKTRACK_GLSL

#include "kd_common.glsl"
#include "shared/kd_layout.h"
#include "trace_status.glsl"
#include "triangle.glsl"

// Node i's parent link and box, through the extra data's texel view: two texels.
KdNodeExtra kdExtraAt(uint i) {
    const uvec4 a = extraTexel(int(2u * i)), b = extraTexel(int(2u * i + 1u));
    return KdNodeExtra(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w);
}

// Node i's parent link alone: the first of its two texels.
uint kdParentOf(uint i) { return extraTexel(int(2u * i)).w; }

// One climbing step from `node`, an ancestor of the leaf just left: whether its box still holds part
// of the segment past segMin (then the segment becomes that part and the walk descends from there);
// else `node` moves to its parent. Only the box's exit is computed: the ancestor holds the leaf, so
// the ray entered it no later than segMin (exitFromBox in kd_traversal.cpp).
bool kdClimbStep(KdRay r, inout uint node, float segMin, uint minAxis, inout float segMax, inout uint maxAxis,
                 float globalMax, uint globalMaxAxis, inout KdPass pass) {
    const KdNodeExtra extra = kdExtraAt(node);
    float t1 = globalMax;
    uint a1 = globalMaxAxis;
    kdBoxExit(r, extra.lo, extra.hi, t1, a1, pass);
    if (kdCompare(pass, t1, a1, segMin, minAxis) > 0) {
        segMax = t1;
        maxAxis = a1;
        return true;
    }
    node = extra.parent;
    return false;
}

bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best) {
    const float globalMax = segMax;
    const uint globalMaxAxis = maxAxis;
    uint node = 0u;
    bool climbing = false;
    bool passDone = false;
    while (budgetLeft() && !passDone && steps < VKRAY_KD_MAX_STEPS) {
        // Up to an ancestor the segment still crosses (after a leaf), then down to the next leaf:
        // two loops, so that a descending step does not pay for the box clip of a climbing step
        // (kd_common.glsl, "Loops"). Both count against the one step cap.
        for (; budgetLeft() && climbing && node != VKRAY_KD_NO_PARENT && steps < VKRAY_KD_MAX_STEPS; ++steps) {
            countNode();
            climbing = !kdClimbStep(r, node, segMin, minAxis, segMax, maxAxis, globalMax, globalMaxAxis, pass);
        }
        if (climbing && node == VKRAY_KD_NO_PARENT && steps < VKRAY_KD_MAX_STEPS) {
            countNode();  // the step that found the root's parent: the segment left the tree
            ++steps;
            passDone = true;
            break;
        }
        uvec2 n = kdNode(node);
        for (; budgetLeft() && !climbing && !kdIsLeaf(n) && steps < VKRAY_KD_MAX_STEPS; ++steps) {
            countNode();
            uint first, second;
            float thit;
            const int visit = kdStepInner(r, n, node, segMin, minAxis, segMax, maxAxis, pass, first, second, thit);
            node = kdDescend(visit, n, first, second, thit, segMin, minAxis, segMax, maxAxis);
            n = kdNode(node);
        }
        if (!kdLeafStep(n, steps)) break;  // the cap, or the driver
        kdVisitLeaf(n, w, anyHit, best);
        if (kdFinished(best, anyHit, segMax) || kdCompare(pass, segMax, maxAxis, globalMax, globalMaxAxis) >= 0) {
            passDone = true;
        } else {  // climb from this leaf's parent
            segMin = segMax;
            minAxis = maxAxis;
            node = kdParentOf(node);
            climbing = true;
            countRestart();
        }
    }
    return passDone;
}

#endif
