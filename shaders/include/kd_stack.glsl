// The standard kd-tree traversal with a per-ray stack (Foley and Sugerman, "KD-Tree Acceleration
// Structures for a GPU Raytracer", Graphics Hardware 2005, section 3): the baseline kd-restart and
// kd-backtrack are measured against. The far child is pushed with its segment; after a leaf without
// an accepted hit, the nearest pending one is popped. The passes around this walk are kdTrace's
// (kd_common.glsl).
//
// kd-shortstack is this walk with a short stack (Horn, Sugerman, Houston and Hanrahan, "Interactive
// k-D Tree GPU Raytracing", I3D 2007, section 4.2; render_kd_shortstack.comp defines
// VKRAY_KD_SHORT_STACK): a ring of VKRAY_SPEC_KD_SHORT_STACK entries (a specialization constant,
// VKRAY_KD_SHORT_STACK_SIZE unless --kd-short-stack says otherwise); a push onto a full ring drops
// the oldest entry, and when the ring runs dry with part of the ray left (something was dropped) the
// walk restarts past the leaf, at the node push-down keeps (kd_restart.glsl).
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

#ifdef VKRAY_KD_SHORT_STACK
const bool kKdShortStack = true;
layout(constant_id = VKRAY_SPEC_KD_SHORT_STACK) const int kKdStackSlots = VKRAY_KD_SHORT_STACK_SIZE;
#else
const bool kKdShortStack = false;
const int kKdStackSlots = VKRAY_KD_STACK_SIZE;
#endif

// The ring slot of logical stack position i (the short stack only; the full stack never wraps).
int kdStackSlot(int i) { return kKdShortStack ? i % kKdStackSlots : i; }

bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best) {
    // At most one push per level: VKRAY_KD_STACK_SIZE >= the builder's depth limit. An entry is a
    // pending node with the start of its segment: stackNode holds the node in bits 0-27 and the axis
    // of its segment's start above (kdStackEntry), stackMin the start. Its end is not stored: the
    // walk's current segment always ends where the top entry's starts (a push cuts the segment at the
    // plane where the pushed one starts, and a pop resumes a segment that ended there too), so an
    // entry's end is the start of the entry below it, or the pass's end for the bottom one.
    // The short stack keeps logical positions [bottom, top) in its ring; the entries below `bottom`
    // were dropped, and the bottom entry's end is then the start of the last one dropped (dropEnd).
    uint stackNode[kKdStackSlots];
    float stackMin[kKdStackSlots];
    const float passMax = segMax;
    const uint passMaxAxis = maxAxis;
    int top = 0, bottom = 0;
    float dropEnd = passMax;
    uint dropEndAxis = passMaxAxis;
    uint node = 0u;
    KdRestartPoint restart = kdRootRestart();  // the short stack's, when it runs dry
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
                if (kKdShortStack && top - bottom == kKdStackSlots) {  // full: drop the oldest
                    const int oldest = kdStackSlot(bottom);
                    dropEnd = stackMin[oldest];
                    dropEndAxis = kdStackAxis(stackNode[oldest]);
                    ++bottom;
                } else if (!kKdShortStack && top == kKdStackSlots) {  // deeper than the builder goes: malformed
                    steps = VKRAY_KD_MAX_STEPS;
                    break;
                }
                const int slot = kdStackSlot(top);
                stackNode[slot] = kdStackEntry(second, kdAxis(n));
                stackMin[slot] = thit;
                ++top;
            }
            node = kdDescend(visit, n, first, second, thit, segMin, minAxis, segMax, maxAxis);
            kdEntered(restart, kKdShortStack, visit, node);
            n = kdNode(node);
        }
        if (!kdLeafStep(n, steps)) break;  // the cap, or the driver
        kdVisitLeaf(n, w, anyHit, best);
        if (kdFinished(best, anyHit, segMax)) {
            passDone = true;
        } else if (top > bottom) {  // pop the nearest pending node
            --top;
            const uint entry = stackNode[kdStackSlot(top)];
            node = kdStackNode(entry);
            minAxis = kdStackAxis(entry);
            segMin = stackMin[kdStackSlot(top)];
            segMax = top > bottom ? stackMin[kdStackSlot(top - 1)] : dropEnd;
            maxAxis = top > bottom ? kdStackAxis(stackNode[kdStackSlot(top - 1)]) : dropEndAxis;
        } else if (!kKdShortStack || kdCompare(pass, segMax, maxAxis, passMax, passMaxAxis) >= 0) {
            passDone = true;  // nothing pending, and nothing dropped beyond this leaf
        } else {  // the short stack ran dry: restart past this leaf at the pushed-down node
            top = bottom = 0;
            dropEnd = passMax;
            dropEndAxis = passMaxAxis;
            node = kdRestart(restart, passMax, passMaxAxis, segMin, minAxis, segMax, maxAxis);
        }
    }
    return passDone;
}

#endif
