// The standard kd-tree traversal with a per-ray stack (Foley and Sugerman, "KD-Tree Acceleration
// Structures for a GPU Raytracer", Graphics Hardware 2005, section 3): the baseline kd-restart and
// kd-backtrack are measured against. The far child is pushed with its segment; after a leaf without
// an accepted hit, the nearest pending one is popped. The passes around this walk are kdTrace's
// (kd_common.glsl).
//
// kd-shortstack is this walk with a short stack (Horn, Sugerman, Houston and Hanrahan, "Interactive
// k-D Tree GPU Raytracing", I3D 2007, section 4.2; render_kd_shortstack.comp defines
// VKRAY_KD_SHORT_STACK): a ring of VKRAY_SPEC_KD_SHORT_STACK entries (a specialization constant,
// VKRAY_KD_SHORT_STACK_SIZE unless kd-short-stack=N says otherwise); a push onto a full ring drops
// the oldest entry, and when the ring runs dry with part of the ray left (something was dropped) the
// walk restarts past the leaf, at the node push-down keeps (kd_restart.glsl).
#ifndef VKRAY_KD_STACK_GLSL
#define VKRAY_KD_STACK_GLSL

#include "kd_common.glsl"
#include "shared/kd_layout.h"
#include "trace_status.glsl"
#include "triangle.glsl"

// A stack entry's node and the axis its segment starts on, in one word: every word of an entry
// is a store at a per-lane index, a loop over the SIMD lanes on llvmpipe (docs/performance.md,
// "What lavapipe charges for"). Node indices stay below 2^28: a kd-tree's nodes are read through one texel view of
// at most maxTexelBufferElements (2^27 on lavapipe) texels, and the host refuses more
// (VKRAY_KD_MAX_NODES).
uint kdStackEntry(uint node, uint minAxis, bool emptyLeaf) {
    return node | (minAxis << VKRAY_KD_STACK_AXIS_SHIFT) | (emptyLeaf ? VKRAY_KD_STACK_EMPTY_LEAF : 0u);
}
uint kdStackNode(uint entry) { return entry & VKRAY_KD_STACK_NODE_MASK; }
uint kdStackAxis(uint entry) { return (entry >> VKRAY_KD_STACK_AXIS_SHIFT) & 3u; }
bool kdStackEmptyLeaf(uint entry) { return (entry & VKRAY_KD_STACK_EMPTY_LEAF) != 0u; }

#ifdef VKRAY_KD_SHORT_STACK
const bool kKdShortStack = true;
layout(constant_id = VKRAY_SPEC_KD_SHORT_STACK) const int kKdStackSlots = VKRAY_KD_SHORT_STACK_SIZE;
#else
const bool kKdShortStack = false;
const int kKdStackSlots = VKRAY_KD_STACK_SIZE;
#endif

// The ring slot of logical stack position i (the short stack only; the full stack never wraps).
int kdStackSlot(int i) { return kKdShortStack ? i % kKdStackSlots : i; }

// A stack entry with its whole segment, in registers. The walk holds the top entry so (`held`) from
// the push that made it or the pop that uncovered it until it is popped, and passes leaves without
// triangles without stepping onto them: a descent step whose segment reaches one child alone, such a
// leaf (kdOnlyChildEmpty), pops the held entry at once; and a pop that uncovers such a leaf (a far
// child pushed with VKRAY_KD_STACK_EMPTY_LEAF) goes on with the entry below it, which that pop has
// read anyway to hold it. On llvmpipe every leaf stepped onto costs a pass of the outer loop, with a
// masked pass of the triangle loop (kd_common.glsl, "Loops"), and the SAH's empty-space bonus makes
// most of the leaves a camera ray reaches on a scanned mesh empty (docs/kdtree.md, "Empty near
// children"). Reading the top entry from the stack arrays in the step instead would cost every
// step their per-lane loads. The hits are those of the CPU twin (KdStackTracer::walkPass), which
// steps onto those leaves: only the leaf and node counts differ.
struct KdHeldEntry {
    uint node;
    float segMin;
    uint minAxis;
    float segMax;
    uint maxAxis;
    bool valid;
};

// Stack word `entry` starting at `start`; it ends where the entry below starts (`belowEntry`, `belowStart`)
// if there is one, else at `end` (the last dropped entry's start, or the pass's end).
KdHeldEntry kdHeldEntry(uint entry, float start, bool hasBelow, uint belowEntry, float belowStart, float end,
                        uint endAxis) {
    return KdHeldEntry(kdStackNode(entry), start, kdStackAxis(entry), hasBelow ? belowStart : end,
                       hasBelow ? kdStackAxis(belowEntry) : endAxis, true);
}

// The walk resumes at entry e.
uint kdResume(KdHeldEntry e, out float segMin, out uint minAxis, out float segMax, out uint maxAxis) {
    segMin = e.segMin;
    minAxis = e.minAxis;
    segMax = e.segMax;
    maxAxis = e.maxAxis;
    return e.node;
}

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
    KdHeldEntry held = KdHeldEntry(0u, 0.0, 0u, 0.0, 0u, false);
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
                stackNode[slot] = kdStackEntry(second, kdAxis(n), kdChildEmpty(n, second == node + 1u));
                stackMin[slot] = thit;
                ++top;
                held = KdHeldEntry(second, thit, kdAxis(n), segMax, maxAxis, true);
            }
            const uint parent = node;
            node = kdDescend(visit, n, first, second, thit, segMin, minAxis, segMax, maxAxis);
            kdEntered(restart, kKdShortStack, visit, node);
            if (held.valid && kdOnlyChildEmpty(n, parent, visit, node) && !kdFinished(best, anyHit, segMax)) {
                --top;  // pop the held entry (the leaf's visit would have found nothing)
                node = kdResume(held, segMin, minAxis, segMax, maxAxis);
                held.valid = false;
            }
            n = kdNode(node);
        }
        if (!kdLeafStep(n, steps)) break;  // the cap, or the driver
        kdVisitLeaf(n, w, anyHit, best);
        if (kdFinished(best, anyHit, segMax)) {
            passDone = true;
        } else if (top > bottom) {  // pop the nearest pending node; the one below it is held
            --top;
            const int i0 = kdStackSlot(top), i1 = kdStackSlot(max(top - 1, 0)), i2 = kdStackSlot(max(top - 2, 0));
            const uint e1 = stackNode[i1];
            const float m1 = stackMin[i1];
            const uint e0 = stackNode[i0];
            const KdHeldEntry popped = kdHeldEntry(e0, stackMin[i0], top > bottom, e1, m1, dropEnd, dropEndAxis);
            held = kdHeldEntry(e1, m1, top - 1 > bottom, stackNode[i2], stackMin[i2], dropEnd, dropEndAxis);
            // A leaf without triangles is passed: the entry below it is popped too.
            const bool passLeaf = kdStackEmptyLeaf(e0) && top > bottom && !kdFinished(best, anyHit, popped.segMax);
            node = kdResume(passLeaf ? held : popped, segMin, minAxis, segMax, maxAxis);
            top -= passLeaf ? 1 : 0;
            held.valid = !passLeaf && top > bottom;
        } else if (!kKdShortStack || kdCompare(pass, segMax, maxAxis, passMax, passMaxAxis) >= 0) {
            passDone = true;  // nothing pending, and nothing dropped beyond this leaf
        } else {  // the short stack ran dry: restart past this leaf at the pushed-down node
            top = bottom = 0;
            held.valid = false;
            dropEnd = passMax;
            dropEndAxis = passMaxAxis;
            node = kdRestart(restart, passMax, passMaxAxis, segMin, minAxis, segMax, maxAxis);
        }
    }
    return passDone;
}

#endif
