// The standard kd-tree traversal with a per-ray stack (Foley and Sugerman, "KD-Tree Acceleration
// Structures for a GPU Raytracer", Graphics Hardware 2005, section 3): the baseline kd-restart and
// kd-backtrack are measured against. The far child is pushed with its segment; after a leaf without
// an accepted hit, the nearest pending one is popped. The passes around this walk are kdTrace's
// (kd_common.glsl).
#ifndef VKRAY_KD_STACK_GLSL
#define VKRAY_KD_STACK_GLSL

#include "kd_common.glsl"
#include "shared/kd_layout.h"
#include "trace_status.glsl"
#include "triangle.glsl"

bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best) {
    // At most one push per level: VKRAY_KD_STACK_SIZE >= the builder's depth limit. stackAxes holds
    // the axes of the entry's segment ends (minAxis << 2 | maxAxis).
    uint stackNode[VKRAY_KD_STACK_SIZE], stackAxes[VKRAY_KD_STACK_SIZE];
    float stackMin[VKRAY_KD_STACK_SIZE], stackMax[VKRAY_KD_STACK_SIZE];
    int top = 0;
    uint node = 0u;
    bool passDone = false;
    while (budgetLeft() && !passDone && steps < VKRAY_KD_MAX_STEPS) {
        // Down to the next leaf (kd_common.glsl, "Loops").
        uvec2 n = kdNode(node);
        for (; budgetLeft() && !kdIsLeaf(n) && steps < VKRAY_KD_MAX_STEPS; ++steps) {
            countNode();
            uint first, second;
            float thit;
            const int visit = kdStepInner(r, n, node, segMin, minAxis, segMax, maxAxis, pass, first, second, thit);
            if (visit == kKdBoth) {
                if (top == VKRAY_KD_STACK_SIZE) {  // deeper than the builder goes: a malformed tree
                    steps = VKRAY_KD_MAX_STEPS;
                    break;
                }
                stackNode[top] = second;
                stackAxes[top] = kdAxis(n) << 2 | maxAxis;
                stackMin[top] = thit;
                stackMax[top] = segMax;
                ++top;
            }
            node = kdDescend(visit, n, first, second, thit, segMax, maxAxis);
            n = kdNode(node);
        }
        if (!kdLeafStep(n, steps)) break;  // the cap, or the driver
        kdVisitLeaf(n, w, anyHit, best);
        if (kdFinished(best, anyHit, segMax) || top == 0) {
            passDone = true;
        } else {  // pop the nearest pending node
            --top;
            node = stackNode[top];
            minAxis = stackAxes[top] >> 2;
            maxAxis = stackAxes[top] & 3u;
            segMin = stackMin[top];
            segMax = stackMax[top];
        }
    }
    return passDone;
}

#endif
