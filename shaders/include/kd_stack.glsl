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

// A stack entry's node and the axis its segment starts on, in one word: every word of an entry
// is a store at a per-lane index, a loop over the SIMD lanes on llvmpipe (docs/benchmarks.md, "A
// third round"). Node indices stay below 2^28: a kd-tree's nodes are read through one texel view of
// at most maxTexelBufferElements (2^27 on lavapipe) texels, and the host refuses more
// (VKRAY_KD_MAX_NODES).
uint kdStackEntry(uint node, uint minAxis) { return node | (minAxis << VKRAY_KD_STACK_AXIS_SHIFT); }
uint kdStackNode(uint entry) { return entry & VKRAY_KD_STACK_NODE_MASK; }
uint kdStackAxis(uint entry) { return entry >> VKRAY_KD_STACK_AXIS_SHIFT; }

bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best) {
    // At most one push per level: VKRAY_KD_STACK_SIZE >= the builder's depth limit. An entry is a
    // pending node with the start of its segment: stackNode holds the node in bits 0-27 and the axis
    // of its segment's start above (kdStackEntry), stackMin the start. Its end is not stored: the
    // walk's current segment always ends where the top entry's starts (a push cuts the segment at the
    // plane where the pushed one starts, and a pop resumes a segment that ended there too), so an
    // entry's end is the start of the entry below it, or the pass's end for the bottom one.
    uint stackNode[VKRAY_KD_STACK_SIZE];
    float stackMin[VKRAY_KD_STACK_SIZE];
    const float passMax = segMax;
    const uint passMaxAxis = maxAxis;
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
                stackNode[top] = kdStackEntry(second, kdAxis(n));
                stackMin[top] = thit;
                ++top;
            }
            node = kdDescend(visit, n, first, second, thit, segMin, minAxis, segMax, maxAxis);
            n = kdNode(node);
        }
        if (!kdLeafStep(n, steps)) break;  // the cap, or the driver
        kdVisitLeaf(n, w, anyHit, best);
        if (kdFinished(best, anyHit, segMax) || top == 0) {
            passDone = true;
        } else {  // pop the nearest pending node
            --top;
            const uint entry = stackNode[top];
            node = kdStackNode(entry);
            minAxis = kdStackAxis(entry);
            segMin = stackMin[top];
            segMax = top > 0 ? stackMin[top - 1] : passMax;
            maxAxis = top > 0 ? kdStackAxis(stackNode[top - 1]) : passMaxAxis;
        }
    }
    return passDone;
}

#endif
