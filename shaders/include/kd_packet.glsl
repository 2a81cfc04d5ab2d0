// The packet walk of the SAH kd-tree (`kd-packet`): the rays of a subgroup's lanes that call a
// trace together walk kd-stack's tree as packets (Wald, Slusallek, Benthin and Wagner, "Interactive
// Rendering with Coherent Ray Tracing", Eurographics 2001; on the GPU, Horn, Sugerman,
// Houston and Hanrahan, "Interactive k-D Tree GPU Raytracing", I3D 2007). The node to
// visit and the stack's nodes are the packet's, the same in every lane; each lane keeps its own
// segment [segMin, segMax] of its ray, takes kd-stack's step at the node (kdStepInner) on it, and
// sits out the children its segment does not reach. The packet descends into the near child when
// some lane reaches it and pushes the far one when some lane reaches that too, each lane's part of
// it (its segment, or that it sits it out) beside the node on the stack.
//
// A packet is a set of rays with the same direction signs (the octant of dir > 0), as in Wald et
// al.: near and far are then the same child for every ray of the packet at every node, so every
// lane meets its leaves front to back, in the order of kd-stack's walk, and ends its search by
// kd-stack's rule (kdFinished) after a leaf. The lanes of a call whose signs differ form a packet
// of their own: the subgroup walks one packet per octant its rays point into (one for almost every
// subgroup of camera rays; more where a subgroup's pixels straddle an axis of the view). A ray with
// a direction component of +-0 reaches one child alone at a node of that axis (kdStepInner), so it
// walks in whichever packet its signs put it. The passes of a ray (in-plane nodes and ties,
// kd_common.glsl) are walked as packets too: the lanes that need another pass form the next.
//
// Hits are kd-stack's: a lane steps through the inner nodes its segment reaches and tests the leaves
// it reaches, in kd-stack's order, until kdFinished, leaving out only the leaves without triangles
// (as kd-stack's kernel does). Every loop condition and branch of the walk of one packet is the same
// in its lanes (the node, the stack's depth, the step count), so the subgroup operations in it are
// reached by all of the packet's lanes together. The kernel needs subgroup ballot operations
// (subgroupBroadcastFirst); a device without them runs kd-stack's kernel (gpu::kernelTraversal).
#ifndef VKRAY_KD_PACKET_GLSL
#define VKRAY_KD_PACKET_GLSL

#include "kd_common.glsl"
#include "shared/kd_layout.h"
#include "trace_status.glsl"
#include "triangle.glsl"

// The part of a lane in a child of a step: whether its segment reaches the child (and the child has
// triangles), and the segment there with its ends' axes.
struct KdPacketPart {
    bool takes;
    float segMin;
    uint minAxis;
    float segMax;
    uint maxAxis;
};

// A stack word of a lane's part: the axes of its ends, and whether it takes part.
uint kdPartWord(KdPacketPart p) { return p.minAxis | (p.maxAxis << 2) | (p.takes ? 16u : 0u); }

// The lane's part in `child` of inner node `index` (n) after kd-stack's step `visit` over the segment
// [segMin, segMax] (kdStepInner: the first child's part ends at the plane when both are reached,
// the second's starts there when both are reached or the first is passed).
KdPacketPart kdPacketPart(uvec2 n, uint index, uint child, int visit, uint first, float thit, float segMin,
                          uint minAxis, float segMax, uint maxAxis) {
    const bool isFirst = child == first, both = visit == kKdBoth;
    const bool reaches = isFirst ? visit == kKdFirst || both : visit != kKdFirst;
    const bool cutMin = !isFirst && (both || visit == kKdPastFirst), cutMax = isFirst && both;
    return KdPacketPart(reaches && !kdChildEmpty(n, child == index + 1u), cutMin ? thit : segMin,
                        cutMin ? kdAxis(n) : minAxis, cutMax ? thit : segMax, cutMax ? kdAxis(n) : maxAxis);
}

// kd-stack's step at inner node `node` (n) for a `live` lane: its parts in the near and the far
// child, near and far by the packet's signs (`octant`); a lane not live takes part in neither.
void kdPacketStep(KdRay r, uvec2 n, uint node, uint octant, bool live, float segMin, uint minAxis, float segMax,
                  uint maxAxis, inout KdPass pass, out uint near, out uint far, out KdPacketPart nearPart,
                  out KdPacketPart farPart) {
    const bool up = ((octant >> kdAxis(n)) & 1u) != 0u;
    near = up ? node + 1u : kdAboveChild(n);
    far = up ? kdAboveChild(n) : node + 1u;
    nearPart = KdPacketPart(false, 0.0, 0u, 0.0, 0u);
    farPart = nearPart;
    if (!live) {
        countIdleStep();
        return;
    }
    countNode();
    uint first, second;
    float thit;
    const int visit = kdStepInner(r, n, node, segMin, minAxis, segMax, maxAxis, pass, first, second, thit);
    nearPart = kdPacketPart(n, node, near, visit, first, thit, segMin, minAxis, segMax, maxAxis);
    farPart = kdPacketPart(n, node, far, visit, first, thit, segMin, minAxis, segMax, maxAxis);
}

// One pass of the packet of the lanes active at the call, all pointing into `octant`, each over its
// own segment of its ray clipped to the root box. Returns whether the lane's pass ended by its own
// rule (false: the packet's step count reached the cap, or the driver cut the loop short). `steps`
// counts the packet's steps: the cap guards against a runaway walk, and the packet's is the walk.
bool kdPacketPass(KdRay r, WatertightRay w, uint octant, float segMin, uint minAxis, float segMax, uint maxAxis,
                  inout KdPass pass, inout int steps, inout Hit best) {
    uint stackNode[VKRAY_KD_STACK_SIZE];   // the packet's: the same in every lane
    float stackMin[VKRAY_KD_STACK_SIZE];   // the lane's own segment in it
    float stackMax[VKRAY_KD_STACK_SIZE];
    uint stackPart[VKRAY_KD_STACK_SIZE];   // kdPartWord
    int top = 0;
    int packetSteps = subgroupMax(steps);
    uint node = 0u;
    bool live = true;   // whether the lane's segment reaches `node` and its search goes on
    bool done = false;  // the lane's search ended (kdFinished after one of its leaves)
    bool more = true;   // the packet has a node to visit
    // The next entry of the stack that some lane takes part in; with none, the walk ends.
#define VKRAY_KD_PACKET_POP()                                                                      \
    {                                                                                              \
        more = false;                                                                              \
        while (top > 0 && !more) {                                                                 \
            --top;                                                                                 \
            node = stackNode[top];                                                                 \
            const uint word = stackPart[top];                                                      \
            live = (word & 16u) != 0u && !done;                                                    \
            segMin = stackMin[top];                                                                \
            minAxis = word & 3u;                                                                   \
            segMax = stackMax[top];                                                                \
            maxAxis = (word >> 2) & 3u;                                                            \
            more = subgroupAny(live);                                                              \
        }                                                                                          \
    }
    while (more && packetSteps < VKRAY_KD_MAX_STEPS) {
        // Down to the next leaf (kd_common.glsl, "Loops").
        uvec2 n = kdNode(node);
        for (; more && !kdIsLeaf(n) && packetSteps < VKRAY_KD_MAX_STEPS; ++packetSteps) {
            // Near and far by the packet's signs: the same child for every lane that reaches both.
            uint near, far;
            KdPacketPart nearPart, farPart;
            kdPacketStep(r, n, node, octant, live, segMin, minAxis, segMax, maxAxis, pass, near, far, nearPart, farPart);
            const bool anyNear = subgroupAny(nearPart.takes), anyFar = subgroupAny(farPart.takes);
            if (anyNear && anyFar) {
                if (top == VKRAY_KD_STACK_SIZE) {  // deeper than the builder goes: malformed
                    packetSteps = VKRAY_KD_MAX_STEPS;
                    break;
                }
                stackNode[top] = far;
                stackMin[top] = farPart.segMin;
                stackMax[top] = farPart.segMax;
                stackPart[top] = kdPartWord(farPart);
                ++top;
            }
            if (anyNear || anyFar) {
                const KdPacketPart part = anyNear ? nearPart : farPart;
                node = anyNear ? near : far;
                live = part.takes;
                segMin = part.segMin;
                minAxis = part.minAxis;
                segMax = part.segMax;
                maxAxis = part.maxAxis;
            } else VKRAY_KD_PACKET_POP()
            n = kdNode(node);
        }
        if (!more || packetSteps >= VKRAY_KD_MAX_STEPS || !kdIsLeaf(n)) break;  // done, the cap, or the driver
        ++packetSteps;
        if (live) {
            countNode();
            kdVisitLeaf(n, w, false, best);
            done = kdFinished(best, false, segMax);
        } else {
            countIdleStep();
        }
        VKRAY_KD_PACKET_POP()
    }
#undef VKRAY_KD_PACKET_POP
    steps = packetSteps;
    return done || !more;
}

// Closest hit in (0, tmax), walked as packets with the lanes active at the call: the passes of
// kdTrace (kd_common.glsl), each pass one packet per octant of the lanes that need it.
Hit kdPacketTrace(vec3 origin, vec3 dir, float tmax) {
    Hit best = noHit(tmax);
    const KdRay r = makeKdRay(origin, dir);
    const WatertightRay w = makeWatertightRay(origin, dir);
    const uvec3 signs = uvec3(greaterThan(dir, vec3(0.0)));
    const uint octant = signs.x | (signs.y << 1) | (signs.z << 2);
    KdPass pass = kdFirstPass();
    uvec2 walked = uvec2(0u);
    int steps = 0;
    bool passDone = true;
    bool walking = true;  // the lane's ray needs another pass
    vec3 rootLo, rootHi;
    kdRootBox(rootLo, rootHi);
    for (uint passes = 0u; passes < 8u && subgroupAny(walking); ++passes) {
        float segMin = 0.0, segMax = tmax;
        uint minAxis = kKdHardBound, maxAxis = kKdHardBound;
        bool waiting = false;  // the lane's pass is still to be walked
        if (walking) {
            // The root box clip in the pass too: its faces may tie with each other.
            waiting = kdClipBox(r, rootLo, rootHi, segMin, minAxis, segMax, maxAxis, pass);
            passDone = true;
        }
        while (subgroupAny(waiting)) {  // one packet per octant, the first waiting lane's first
            if (waiting) {
                const uint packetOctant = subgroupBroadcastFirst(octant);
                if (octant == packetOctant) {
                    passDone = kdPacketPass(r, w, octant, segMin, minAxis, segMax, maxAxis, pass, steps, best);
                    waiting = false;
                }
            }
        }
        // Another pass for an in-plane node or a tie met, or the end.
        walking = walking && kdAnotherPass(passDone, false, best, pass, walked);
    }
    kdEndLoop(passDone, steps);
    return best;
}

#endif
