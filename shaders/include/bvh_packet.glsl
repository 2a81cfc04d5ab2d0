// The packet walk of the 4-wide BVH (`bvh-packet`): the rays of a subgroup's lanes that call a
// trace together walk `bvh`'s tree as one packet (Wald, Slusallek, Benthin and Wagner, "Interactive
// Rendering with Coherent Ray Tracing", Eurographics 2001; on the GPU's BVH, Günther, Popov, Seidel
// and Slusallek, "Realtime Ray Tracing on GPU with BVH-based Packet Traversal", IRT 2007). The node
// to visit and the stack's nodes are the packet's, the same in every lane; each lane tests its own
// ray against the node's four children, and the packet descends into every child that some lane's
// ray enters (subgroupOr of the lanes' child masks), nearest first by the entry distances of the
// packet's first lane (subgroupBroadcastFirst: one lane's distances stand for the packet's, where
// the packet's nearest entry, a subgroupMin of four distances, costs four reductions a step, each a
// loop over the lanes on llvmpipe: docs/performance.md, "Packet traversal"). A lane whose ray does
// not enter the node sits the step out (its box test is masked), and beside each node on the stack
// every lane keeps its own entry distance, so a popped node that no lane's ray enters within its
// best hit so far is dropped without a read. Leaves test their triangles in the loop of
// leaf_triangles.glsl, each lane on its own ray and only where its ray enters the leaf.
//
// Every loop condition and branch of the walk is the same in every lane of the packet (the node,
// the stack's depth, the children's count), so the subgroup operations in it are reached by all
// of the packet's lanes together, whichever lanes called it: only those active at the call form
// the packet, for any subgroup size. Hits are the single-ray walk's: a lane tests every leaf its
// ray enters within its best hit, and keeps every hit that beats its best (beats(), triangle.glsl).
// The kernel needs subgroup ballot operations besides those of every kernel (vote, arithmetic);
// a device without them runs `bvh`'s kernel instead (gpu::kernelTraversal).
#ifndef VKRAY_BVH_PACKET_GLSL
#define VKRAY_BVH_PACKET_GLSL

#include "bvh_common.glsl"
#include "leaf_triangles.glsl"
#include "trace_status.glsl"
#include "triangle.glsl"

// The children of a node that some lane's ray enters (`lane`: this lane's entry distances, +inf
// where its ray misses the child or does not enter the node), first in `kids` and `lane`, in the
// order of the first lane's entry distances (`tEnter`), the same in every lane; returns how many.
int packetChildren(vec4 tEnter, inout vec4 lane, inout uvec4 kids) {
    const uvec4 bits = uvec4(lessThan(lane, vec4(kInfinity))) << uvec4(0u, 1u, 2u, 3u);
    const uint entered = subgroupOr(bits.x | bits.y | bits.z | bits.w);
    const bvec4 packetEnters = notEqual(uvec4(entered) & uvec4(1u, 2u, 4u, 8u), uvec4(0u));
    vec4 key = mix(vec4(kInfinity), subgroupBroadcastFirst(tEnter), packetEnters);
    uvec4 laneBits = floatBitsToUint(lane);
    sortByKey(key, kids, laneBits);
    lane = uintBitsToFloat(laneBits);
    return bitCount(entered);
}

// Closest hit in (0, tmax), walked as a packet with the lanes active at the call. The loop over
// leaves around a loop over node steps of the stack walk (bvh_traversal.glsl, Aila and Laine 2009),
// with the packet's node and stack in place of the ray's.
Hit bvhPacketTrace(vec3 origin, vec3 dir, float tmax) {
    Hit best = noHit(tmax);
    if (params.counts.x == 0u) return best;
    const BoxRay boxRay = makeBoxRay(origin, dir);
    const WatertightRay ray = makeWatertightRay(origin, dir);

    uint stackRef[VKRAY_BVH_STACK_SIZE];     // the packet's: the same in every lane
    float stackEnter[VKRAY_BVH_STACK_SIZE];  // the lane's own entry distance, +inf: its ray misses
    int top = 0;
    uint ref = 0u;  // the root: inner node 0
    bool haveRef = true;
    bool enters = true;  // whether this lane's ray enters `ref`
    int iteration = 0;
    // The next entry of the stack into `ref`: the lanes whose rays enter it before their best hit
    // (widened as in bvh_traversal.glsl's pop: a triangle in its box's face may hit one ulp before
    // the box's computed entry) take part; with none, the entry is dropped (haveRef false).
#define VKRAY_PACKET_POP()                                                                        \
    {                                                                                             \
        --top;                                                                                    \
        ref = stackRef[top];                                                                      \
        const float enter = stackEnter[top];                                                      \
        enters = enter < kInfinity && !(enter > best.t * kRoundingSlack);                       \
        haveRef = subgroupAny(enters);                                                            \
    }
    while (iteration < VKRAY_BVH_MAX_ITERATIONS && (haveRef || top > 0)) {
        for (; iteration < VKRAY_BVH_MAX_ITERATIONS && (haveRef || top > 0) && !(haveRef && isLeafRef(ref)); ++iteration) {
            if (haveRef) {
                if (enters) countNode();
                else countIdleStep();
                const BvhNode n = loadBvhNode(ref);
                vec4 tEnter;
                const bvec4 hit = hitsChildren(n, boxRay, best.t, tEnter);
                vec4 lane = mix(vec4(kInfinity), tEnter, bvec4(uvec4(hit) * uint(enters)));
                uvec4 kids = n.child;
                const int hits = packetChildren(tEnter, lane, kids);
                if (top + hits > VKRAY_BVH_STACK_SIZE) {  // deeper than the stack: flag, never guess
                    gLoopCutShort = true;
                    return best;
                }
                VKRAY_BVH_PUSH_REST(kids, lane, hits)
                ref = kids.x;
                enters = lane.x < kInfinity;
                haveRef = hits > 0;
            }
            if (!haveRef && top > 0) VKRAY_PACKET_POP()
        }
        // The stack ran empty, or the loop was cut short (cap or driver).
        if (!haveRef || !isLeafRef(ref) || iteration >= VKRAY_BVH_MAX_ITERATIONS) break;
        // The leaf: the lanes whose rays enter it test its triangles, then the next entry.
        ++iteration;
        if (enters) {
            countNode();
            countLeaf();
            testSlots(leafFirst(ref), leafFirst(ref) + leafCount(ref), ray, false, LEAF_SLOTS, best);
        } else {
            countIdleStep();
        }
        haveRef = false;
        if (top > 0) VKRAY_PACKET_POP()
    }
#undef VKRAY_PACKET_POP
    bvhEndLoop(!haveRef && top == 0, iteration);  // something left: the walk did not end by itself
    return best;
}

#endif
