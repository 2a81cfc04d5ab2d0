// The stackless walk of the 4-wide BVH (bvh-stackless's rays, and every BVH kernel's shadow rays):
// no stack, a parent link per node instead (after Hapala, Davidovic, Wald, Havran and Slusallek,
// "Efficient Stack-less BVH Traversal for Ray Tracing", SCCG 2011, whose three-state automaton walks
// a binary tree; here its 4-wide analogue).
// At a node the walk takes, among the children the ray enters within the best hit so far, the
// first after the child it came back from, in one order of the node's children that is the same on
// every visit: by entry distance, then by slot. With none left it climbs to the parent, whose link
// names the slot it came from, and reads that node again. So a node is read once on the way down
// and once after each of its children, and no per-ray memory but a node index and a slot is kept.
// Leaves test their triangles in the loop of leaf_triangles.glsl. The CPU twin is Hapala et al.'s
// binary automaton in accel/bvh/bvh_tracer.cpp.
#ifndef VKRAY_BVH_STACKLESS_GLSL
#define VKRAY_BVH_STACKLESS_GLSL

#include "bvh_common.glsl"
#include "leaf_triangles.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

// Component i of v, by selects (a dynamic index made llvmpipe keep the vector in memory).
float bvhPick(vec4 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : (i == 2 ? v.z : v.w)); }
uint bvhPick(uvec4 v, int i) { return i == 0 ? v.x : (i == 1 ? v.y : (i == 2 ? v.z : v.w)); }

// The child to take after slot `from` (-1: none yet): the first, in the order (entry distance,
// slot), of the entered children that come after `from` in it; -1 when none is left.
int bvhNextChild(bvec4 hit, vec4 tEnter, int from) {
    const float kFrom = from < 0 ? -kInfinity : bvhPick(tEnter, from);
    const bvec4 later = bvec4(uvec4(greaterThan(tEnter, vec4(kFrom))) |
                              uvec4(equal(tEnter, vec4(kFrom))) * uvec4(greaterThan(ivec4(0, 1, 2, 3), ivec4(from))));
    const bvec4 candidate = bvec4(uvec4(hit) * uvec4(later));
    int next = candidate.x ? 0 : -1;
    float key = candidate.x ? tEnter.x : kInfinity;
    if (candidate.y && (next < 0 || tEnter.y < key)) { next = 1; key = tEnter.y; }
    if (candidate.z && (next < 0 || tEnter.z < key)) { next = 2; key = tEnter.z; }
    if (candidate.w && (next < 0 || tEnter.w < key)) { next = 3; key = tEnter.w; }
    return next;
}

// Resumable variant (render_main.glsl, "Resumable pixels"): the walk's whole state is its position,
// a node and the slot it came back from, so an interrupted walk saves that, packed in one word that
// is never 0 (node << 3 | from + 2, from in -1..3), its best hit and its node steps so far (the
// cap counts over all dispatches), and goes on from there in the next dispatch.
uint bvhResumeWord(uint node, int from) { return node << 3 | uint(from + 2); }

void bvhSaveWalk(uint node, int from, int steps, int firstStep, Hit best) {
    gResumeSlot = bvhResumeWord(node, from);
    gResumeBest = best;
    gResumeSteps = uint(steps);
    if (steps > firstStep) gProgress = true;
}

// Closest hit in (0, tmax), or with anyHit (a constant at every call) the first hit found.
// A loop over leaves around a loop over node steps, as the stack walk (bvh_traversal.glsl).
Hit bvhStacklessTrace(vec3 origin, vec3 dir, float tmax, const bool anyHit) {
    Hit best = noHit(tmax);
    if (params.counts.x == 0u) return best;
    const BoxRay boxRay = makeBoxRay(origin, dir);
    const WatertightRay ray = makeWatertightRay(origin, dir);
    uint node = 0u;  // the root
    int from = -1;   // the slot of `node` the walk came back from
    bool done = false;
    int iteration = 0;
    if (RESUMABLE && gResumeSlot > 0u) {  // where the interrupted walk stopped
        node = gResumeSlot >> 3;
        from = int(gResumeSlot & 7u) - 2;
        iteration = int(gResumeSteps);
        best = gResumeBest;
    }
    const int firstStep = iteration;
    // The position before the step that found the leaf being tested: a leaf loop cut short is
    // taken again from there (its triangles tested twice find the same hits).
    uint stepNode = node;
    int stepFrom = from, stepIteration = iteration;
    while (budgetLeft() && !done && iteration < VKRAY_BVH_MAX_ITERATIONS) {
        // Down, sideways and up until a leaf is next or the walk climbed past the root.
        uint leaf = VKRAY_BVH_NO_CHILD;
        for (; budgetLeft() && !done && leaf == VKRAY_BVH_NO_CHILD && iteration < VKRAY_BVH_MAX_ITERATIONS; ++iteration) {
            if (RESUMABLE) {
                stepNode = node;
                stepFrom = from;
                stepIteration = iteration;
            }
            countNode();
            const BvhNode n = loadBvhNode(node);
            vec4 tEnter;
            const bvec4 hit = hitsChildren(n, boxRay, best.t, tEnter);
            const int next = bvhNextChild(hit, anyHit ? vec4(0.0) : tEnter, from);
            const uint ref = bvhPick(n.child, max(next, 0));
            const uint link = next < 0 ? bvhParentLink(node, n) : 0u;
            leaf = next >= 0 && isLeafRef(ref) ? ref : VKRAY_BVH_NO_CHILD;
            done = next < 0 && link == VKRAY_BVH_NO_PARENT;
            // A leaf: stay, and go on after it; an inner child: down; none: up to the parent.
            from = next >= 0 ? (leaf != VKRAY_BVH_NO_CHILD ? next : -1) : int(link & 3u);
            node = next >= 0 ? (leaf != VKRAY_BVH_NO_CHILD ? node : ref) : link >> 2;
        }
        if (leaf == VKRAY_BVH_NO_CHILD || iteration >= VKRAY_BVH_MAX_ITERATIONS) break;
        ++iteration;
        countNode();
        countLeaf();
        // Cut short by the driver (flagged there; the resumable variant goes on at this leaf), or an
        // occluder found: the walk ends.
        const bool complete = testSlots(leafFirst(leaf), leafFirst(leaf) + leafCount(leaf), ray, anyHit, LEAF_SLOTS, best);
        if (!complete || (anyHit && best.triangle >= 0)) {
            if (RESUMABLE && complete) gResumeSlot = 0u;
            if (RESUMABLE && !complete) bvhSaveWalk(stepNode, stepFrom, stepIteration, firstStep, best);
            return best;
        }
    }
    bvhEndLoop(done, iteration);
    if (RESUMABLE && (done || iteration >= VKRAY_BVH_MAX_ITERATIONS)) gResumeSlot = 0u;
    else if (RESUMABLE) bvhSaveWalk(node, from, iteration, firstStep, best);
    return best;
}

#endif
