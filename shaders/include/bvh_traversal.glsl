// The `bvh` accelerator (accel/bvh: AAC after Gu et al. 2013, or the binned-SAH reference), in the
// 4-wide layout of shared/bvh_layout.h: a node holds its children's boxes, coordinates grouped by
// axis, so one read and one set of vector operations test all four; leaves are runs of the triangle
// buffer in leaf order, named by the reference itself, and take no node.
//
// The stack walk, for closest hits (bvhTrace): the children a ray enters are sorted by entry
// distance; the nearest is visited next and the others are pushed, farthest first, with their
// entry distances on a stack in local memory; a popped entry entered beyond the best hit so far is
// skipped. Leaves test their triangles in the loop of leaf_triangles.glsl. Shadow rays (any hit)
// take the stackless walk of bvh_stackless.glsl in every BVH kernel: on llvmpipe a walk that stores
// nothing per ray is the faster one for them, though it takes more node steps: the stack walk's
// pushes are per-lane stores, lane by lane there (docs/performance.md, "Stackless BVH").
#ifndef VKRAY_BVH_TRAVERSAL_GLSL
#define VKRAY_BVH_TRAVERSAL_GLSL

#include "bvh_common.glsl"
#include "bvh_stackless.glsl"
#include "leaf_triangles.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

// The entered children first, nearest first (sortByKey, bvh_common.glsl), +inf for a miss.
void sortEntered(bvec4 hit, vec4 tEnter, uvec4 child, out vec4 key, out uvec4 kids) {
    key = mix(vec4(kInfinity), tEnter, hit);
    kids = child;
    sortByKey(key, kids);
}

// Closest hit in (0, tmax).
//
// A loop over leaves around a loop over the node steps down to the next leaf ("while-while", Aila
// and Laine, "Understanding the Efficiency of Ray Traversal on GPUs", HPG 2009): llvmpipe runs
// every statement of a loop body for all SIMD lanes, masked, so with the leaf's triangle loop
// inside the node loop every node step of every lane would pay for a triangle test, and a ray takes
// several times more node steps than triangle tests (docs/performance.md, "What lavapipe charges
// for").
Hit bvhTrace(vec3 origin, vec3 dir, float tmax) {
    Hit best = noHit(tmax);
    if (params.counts.x == 0u) return best;
    const BoxRay boxRay = makeBoxRay(origin, dir);
    const WatertightRay ray = makeWatertightRay(origin, dir);

    uint stackRef[VKRAY_BVH_STACK_SIZE];
    float stackEnter[VKRAY_BVH_STACK_SIZE];
    int top = 0;
    uint ref = 0u;  // the root: inner node 0
    bool haveRef = true;
    int iteration = 0;
    // The next entry of the stack into `ref`. A popped entry entered beyond the best hit found
    // since it was pushed is dropped (haveRef false): that costs an iteration but reads nothing.
    // "Beyond" with the slab test's own widening: the triangle test and the slab test round
    // differently, and a triangle lying in a face of its box (axis-aligned geometry) was measured
    // to hit one ulp before the box's computed entry; compared unwidened, that node was dropped and
    // a closer hit, or an equal-t one of lower index (beats(), triangle.glsl), lost
    // (scenes/stress/split-planes.scene, 3 of 3969 camera rays). (A macro, not a function: GLSL
    // passes arrays by copy.)
#define VKRAY_BVH_POP()                                                            \
    {                                                                              \
        --top;                                                                     \
        ref = stackRef[top];                                                       \
        haveRef = !(stackEnter[top] > best.t * kRoundingSlack);                    \
    }
    while (budgetLeft() && iteration < VKRAY_BVH_MAX_ITERATIONS) {
        // Node steps while `ref` is an inner node or a dropped entry, and something is left. The
        // loop's exits are all in its condition: a `break` in its body made llvmpipe's masked
        // loop measurably slower.
        for (; budgetLeft() && iteration < VKRAY_BVH_MAX_ITERATIONS && (haveRef || top > 0) && !(haveRef && isLeafRef(ref));
             ++iteration) {
            if (haveRef) {
                countNode();
                const BvhNode n = loadBvhNode(ref);
                vec4 tEnter;
                const bvec4 hit = hitsChildren(n, boxRay, best.t, tEnter);
                vec4 key;
                uvec4 kids;
                sortEntered(hit, tEnter, n.child, key, kids);
                const int hits = int(hit.x) + int(hit.y) + int(hit.z) + int(hit.w);
                if (top + hits > VKRAY_BVH_STACK_SIZE) {  // deeper than the stack: flag, never guess
                    gLoopCutShort = true;
                    return best;
                }
                VKRAY_BVH_PUSH_REST(kids, key, hits)
                ref = kids.x;
                haveRef = hits > 0;
            }
            if (!haveRef && top > 0) VKRAY_BVH_POP()
        }
        // The stack ran empty, or the loop was cut short (cap or driver).
        if (!haveRef || !isLeafRef(ref) || iteration >= VKRAY_BVH_MAX_ITERATIONS) break;
        // The leaf: its triangles, in the loop of leaf_triangles.glsl, then the next entry.
        ++iteration;
        countNode();
        countLeaf();
        const uint first = leafFirst(ref);
        const uint count = leafCount(ref);
        if (!testSlots(first, first + count, ray, false, LEAF_SLOTS, best)) return best;  // cut short by the driver
        haveRef = false;
        if (top > 0) VKRAY_BVH_POP()
    }
#undef VKRAY_BVH_POP
    bvhEndLoop(!haveRef && top == 0, iteration);  // something left: the walk did not end by itself
    return best;
}

// The stack kernels' two queries (bvh and its presets, bvh-sphere): closest hits by the stack walk,
// shadow rays by the stackless one. The resumable variant walks closest hits stackless too: an
// interrupted stackless walk is resumed from a node and a slot (bvh_stackless.glsl), where the
// stack walk would have to save its whole stack, up to VKRAY_BVH_STACK_SIZE entries, per pixel.
// Both walks find the same closest hit (every hit that beats the best is kept, ties by beats(),
// triangle.glsl), so a resumed tile's image is the plain kernel's; only its node steps differ.
Hit traceClosest(vec3 origin, vec3 dir, float tmax) {
    if (RESUMABLE) return bvhStacklessTrace(origin, dir, tmax, false);
    return bvhTrace(origin, dir, tmax);
}
bool traceAny(vec3 origin, vec3 dir, float tmax) { return bvhStacklessTrace(origin, dir, tmax, true).triangle >= 0; }

#endif
