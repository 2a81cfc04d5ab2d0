// What every traversal reports besides its hit: whether a loop was cut short by the driver, rays
// ended by an iteration cap, and (in the statistics variant only) the work done.
//
// llvmpipe (lavapipe) of Mesa 22.3 ends every loop of an invocation once its loops together ran
// 65535 iterations (Mesa gallivm LP_MAX_TGSI_LOOP_ITERATIONS; Mesa 25's runs them to the end: the
// host measures which, VulkanContext::loopBudget()). A traversal loop that ends before its own
// exit condition and before its cap sets gLoopCutShort, so such a pixel is flagged, never silently
// wrong. A loop that reaches its own iteration cap (a runaway ray: lavapipe has no watchdog)
// counts the ray in gCappedRays instead.
#ifndef VKRAY_TRACE_STATUS_GLSL
#define VKRAY_TRACE_STATUS_GLSL

#include "bindings.glsl"
#include "triangle.glsl"

layout(constant_id = VKRAY_SPEC_COUNT_TRAVERSAL) const bool COUNT_TRAVERSAL = false;
// The resumable variant (render_main.glsl, "Resumable pixels"): a traversal cut short is taken up
// again in the next dispatch instead of flagging the pixel. Compiled apart (the build defines
// VKRAY_RESUMABLE_KERNEL for its second SPIR-V of every kernel), not specialised: lavapipe works
// through the whole SPIR-V before it folds a specialization constant.
#ifdef VKRAY_RESUMABLE_KERNEL
const bool RESUMABLE = true;
#else
const bool RESUMABLE = false;
#endif

bool gLoopCutShort = false;
// Resumable variant: the interrupted traversal of brute force or the BVH (where it goes on, 0 =
// none; the best hit so far; the BVH walk's node steps so far), saved with the pixel and handed to
// the first traversal of the next dispatch, the one that was interrupted (a pixel stops at its
// first interrupted traversal).
uint gResumeSlot = 0u;
Hit gResumeBest;
uint gResumeSteps = 0u;
// Resumable variant: some work of this dispatch is kept (a traversal ended, or brute force got on).
bool gProgress = false;

// The resumable variant's own loop budget. llvmpipe counts the iterations of all loops of a
// subgroup (its SIMD width of lanes run in lockstep) and ends every loop once they reach 65535 —
// without the exits the compiler knows of, so values leaving such a loop can be stale (its phi
// copies sit on the exits it knows; seen: a pixel kept the pending ray but lost the radiance added
// in the same iteration). So the resumable variant counts the same iterations itself, once per
// subgroup in workgroup memory, and every loop of the kernel ends through its own condition once
// VKRAY_RESUMABLE_LOOP_BUDGET is spent: all values stay exact, and the pixel saves where it is.
shared uint sLoopIterations[VKRAY_WORKGROUP_X * VKRAY_WORKGROUP_Y];  // per subgroup
// Whether any pixel of the subgroup got work done in this dispatch (subgroupProgress()).
shared uint sSubgroupProgress[VKRAY_WORKGROUP_X * VKRAY_WORKGROUP_Y];

// Whether llvmpipe's loop budget ran out anywhere in this invocation: from then on every loop ends
// after one pass, so a loop that needs two is cut. Checked at the end of every pixel, so a loop ended
// by the driver flags the pixel even where the values leaving that loop were stale and looked
// complete. The trip count comes from the push constants (always 2) so the compiler cannot unroll it.
bool loopBudgetRanOut() {
    const uint needed = 2u + (params.counts.x >> 31);
    uint passes = 0u;
    for (uint k = 0u; k < needed; ++k) ++passes;
    return passes < needed;
}

void startLoopBudget() {
    if (RESUMABLE && subgroupElect()) {
        sLoopIterations[gl_SubgroupID] = 0u;
        sSubgroupProgress[gl_SubgroupID] = 0u;
    }
    if (RESUMABLE) subgroupMemoryBarrierShared();
}

// Resumable variant, at the end of a pixel: whether its subgroup got anything done in this dispatch.
// The subgroup shares one budget, so one pixel's long traversal can spend it all while another
// pixel waits its turn with nothing done; that pixel is not stuck. Only a subgroup none of whose
// pixels got on is (then every unfinished one is flagged): otherwise some pixel's remaining work
// shrank, and once it is done the others have the budget to themselves.
bool subgroupProgress() {
    if (gProgress) sSubgroupProgress[gl_SubgroupID] = 1u;
    subgroupMemoryBarrierShared();
    return sSubgroupProgress[gl_SubgroupID] != 0u;
}

// Counts a pass of the subgroup through a loop's header in the resumable variant; always true, so
// it can stand in a loop's condition. Alone it serves a loop that may not be refused a pass, one
// that finishes a step already begun (the BVH walk's pushes, at most VKRAY_BVH_WIDTH passes): the
// few passes it takes after the budget is spent fit in the margin between the budget and
// llvmpipe's own count.
bool countPass() {
    if (RESUMABLE) {
        if (subgroupElect()) sLoopIterations[gl_SubgroupID] += 1u;
        subgroupMemoryBarrierShared();
    }
    return true;
}

// Called first in the condition of every other loop: counts the pass and says whether the budget
// allows it. Always true in the plain kernel.
bool budgetLeft() { return countPass() && (!RESUMABLE || sLoopIterations[gl_SubgroupID] <= VKRAY_RESUMABLE_LOOP_BUDGET); }

uint gCappedRays = 0;
uint gShadowRays = 0;
uint gNodesVisited = 0;
uint gLeavesVisited = 0;
uint gTrianglesTested = 0;
uint gWalkEvents = 0;  // GpuPixel.walkEvents

// A new pixel of the same invocation (render_main.glsl, "Pixels per invocation") counts from zero.
void resetPixelCounters() {
    gCappedRays = gShadowRays = gNodesVisited = gLeavesVisited = gTrianglesTested = gWalkEvents = 0u;
}

// The counters compile to nothing unless the host specialises COUNT_TRAVERSAL to true.
void countNode() { if (COUNT_TRAVERSAL) ++gNodesVisited; }
void countLeaf() { if (COUNT_TRAVERSAL) ++gLeavesVisited; }
void countTriangles(uint n) { if (COUNT_TRAVERSAL) gTrianglesTested += n; }
void countRestart() { if (COUNT_TRAVERSAL) ++gWalkEvents; }
// A packet walk's step that the lane's ray sits out (bvh_packet.glsl, kd_packet.glsl): with the
// nodes it visits, the steps its packet took, whose share it used is the lanes' use of the packet.
void countIdleStep() { if (COUNT_TRAVERSAL) ++gWalkEvents; }

#endif
