// The one loop that tests a run of triangles: brute force runs it over the whole triangle buffer,
// the BVH and the kd-tree over a leaf.
//
// Slots per iteration: brute force tests four per iteration, which divides its iterations by four,
// keeps the loops of a pixel far below lavapipe's budget of 65535 iterations (trace_status.glsl) and
// multiplies the scene size it can handle under it. A leaf tests LEAF_SLOTS per iteration, one:
// llvmpipe runs a loop body at least once wherever the loop is reached, for all SIMD lanes and
// masked, even when no lane has a triangle to test, and a traversal reaches its leaf loop at every
// node step, so four slots would cost four triangle tests per step (docs/performance.md, "What
// lavapipe charges for"). Only the resumable variant tests
// four, for a structure with leaves of more than VKRAY_SINGLE_SLOT_LEAF_LIMIT triangles (a burst
// of overlapping triangles; the host decides: ShaderFeatures::leafSlots()): with one a pass, a
// tile of such leaves that runs out of llvmpipe's budget in the plain kernel is resumed there. In
// the plain kernel the four-slot loop would be dead code for almost every structure, yet lavapipe
// translates the whole SPIR-V before a specialization constant folds it, so it would lengthen
// every render's pipeline creation (docs/performance.md, "What lavapipe charges for").
#ifndef VKRAY_LEAF_TRIANGLES_GLSL
#define VKRAY_LEAF_TRIANGLES_GLSL

#ifdef VKRAY_RESUMABLE_KERNEL
layout(constant_id = VKRAY_SPEC_LEAF_SLOTS) const uint LEAF_SLOTS = 1u;
#else
const uint LEAF_SLOTS = 1u;
#endif
const uint kBruteSlotsPerIteration = 4u;

#include "bindings.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

// The triangle listed in `slot` of a leaf: an index into the triangle buffer. Defined by the
// accelerator include: the slot itself for brute force and the BVH (whose leaves are runs of the
// buffer in leaf order), the slot's entry of the index list for the kd-tree (whose leaves share
// triangles through it).
uint slotTriangle(uint slot);

// Slot `slot` when below `end`: the last iteration's four slots may run past the end.
void testSlot(uint slot, uint end, WatertightRay ray, const bool anyHit, inout Hit best) {
    if (slot < end) {
        if (anyHit) anyTriangle(slotTriangle(slot), ray, best);
        else closestTriangle(slotTriangle(slot), ray, best);
    }
}

// Tests slots [i, end) on (0, best.t) and keeps every hit that beats `best` (beats(),
// triangle.glsl). With anyHit the loop ends at the first hit: best.triangle >= 0, best.t unchanged.
// anyHit and perIteration (kBruteSlotsPerIteration or LEAF_SLOTS, 1 or 4) are constants at every
// call, so the compiler folds every test of them. In the resumable variant, returns false, with
// the pixel flagged, if the loop ended before either (its budget: budgetLeft()); `i` is then the
// first slot not tested (brute force resumes there: render_main.glsl, "Resumable
// pixels"). The triangles counted are those the loop reached.
bool testSlotsFrom(inout uint i, uint end, WatertightRay ray, const bool anyHit, const uint perIteration,
                   inout Hit best) {
    const uint begin = i;
    // The resumable variant tells whether the loop ran to its end by an iteration count, not by
    // testing its condition again: the compiler takes a loop to end only when its condition is
    // false and folds such a test to true (seen on lavapipe: cut-short brute-force loops went
    // unflagged and returned a miss). The plain kernel counts nothing here: a loop llvmpipe's
    // budget ended is caught for the whole pixel by loopBudgetRanOut() (trace_status.glsl).
    const uint needed = i < end ? (end - i + perIteration - 1u) / perIteration : 0u;
    uint iterations = 0u;
    for (; budgetLeft() && i < end && !(anyHit && best.triangle >= 0); i += perIteration) {
        testSlot(i, end, ray, anyHit, best);
        if (perIteration == 4u) {
            testSlot(i + 1u, end, ray, anyHit, best);
            testSlot(i + 2u, end, ray, anyHit, best);
            testSlot(i + 3u, end, ray, anyHit, best);
        }
        if (RESUMABLE) ++iterations;
    }
    countTriangles(min(i, end) - begin);
    const bool complete = !RESUMABLE || iterations >= needed || (anyHit && best.triangle >= 0);
    if (!complete) gLoopCutShort = true;
    return complete;
}

bool testSlots(uint begin, uint end, WatertightRay ray, const bool anyHit, const uint perIteration, inout Hit best) {
    uint i = begin;
    return testSlotsFrom(i, end, ray, anyHit, perIteration, best);
}

#endif
