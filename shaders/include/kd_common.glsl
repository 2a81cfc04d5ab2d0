// What the three kd-tree traversals share (Foley and Sugerman, "KD-Tree Acceleration Structures
// for a GPU Raytracer", Graphics Hardware 2005): the buffers of shared/kd_layout.h, node accessors,
// the ray-box clip, one inner-node step, the leaf test, and the walk over passes with the two
// queries built on it; each traversal include defines only kdWalkPass(), its walk of one pass.
// The float twins of host/accel/kd/kd_traversal.cpp (KdTracer::walk and the walkPass of each
// tracer), whose header explains the robustness rules; in short:
//  - children in ray order by the direction's sign; [tmin, tmax] goes first only if thit >= tmax,
//    second only if thit <= tmin (a plane behind the origin has thit < 0 <= tmin), else both;
//  - direction components of +-0 (or denormal: lavapipe flushes them) never divide: such a ray
//    stays on its origin's side; one lying in the plane (origin == split exactly) takes the side of
//    the pass's mask, and plane hits exactly equal to a segment end of another axis are ordered by
//    the pass's ranks; a walk repeats with the other masks and orders the ray met (KdPass, at most
//    8 passes; one for almost every ray);
//  - planes are always hit at (plane - origin) * invDir, `precise`, so a leaf's exit and the split
//    that made it compare equal exactly;
//  - a leaf's triangles are tested on the whole ray (0, best.t]; the search ends once the best hit
//    lies strictly before the current leaf's exit (a hit beyond the leaf does not end it; one at
//    the exit may still lose a tie to the next leaf); exact ties in t go to the lowest index.
// Loops: each walk is a loop over leaves around a loop over the node steps down to the next leaf;
// leaf triangles one (or 4) per iteration (leaf_triangles.glsl). Every step counts against
// VKRAY_KD_MAX_STEPS, and llvmpipe ends all loops of an invocation after 65535 iterations in total
// (trace_status.glsl). The leaf's triangle loop stands outside the node-step loop because llvmpipe
// runs every statement of a loop body for all SIMD lanes, masked: with the leaf test in the step
// loop, every node step of every lane would pay for a triangle test (Aila and Laine, "Understanding
// the Efficiency of Ray Traversal on GPUs", HPG 2009: the while-while loop).
#ifndef VKRAY_KD_COMMON_GLSL
#define VKRAY_KD_COMMON_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "constants.glsl"
#include "leaf_triangles.glsl"
#include "shared/kd_layout.h"
#include "trace_status.glsl"
#include "triangle.glsl"

// The root box, from the KdTreeHeader in the first VKRAY_KD_HEADER_TEXELS texels of the nodes:
// (lo.x, lo.y), (lo.z, nodeCount), (hi.x, hi.y), (hi.z, indexCount).
void kdRootBox(out vec3 lo, out vec3 hi) {
    const uvec2 a = nodeTexel(0).xy, b = nodeTexel(1).xy, c = nodeTexel(2).xy, d = nodeTexel(3).xy;
    lo = uintBitsToFloat(uvec3(a, b.x));
    hi = uintBitsToFloat(uvec3(c, d.x));
}

// Node i (KdNode: (word0, word1), see kd_layout.h).
uvec2 kdNode(uint i) { return nodeTexel(int(i) + VKRAY_KD_HEADER_TEXELS).xy; }

bool kdIsLeaf(uvec2 n) { return (n.y & 3u) == VKRAY_KD_LEAF_TAG; }
uint kdAxis(uvec2 n) { return n.y & 3u; }
float kdSplit(uvec2 n) { return uintBitsToFloat(n.x); }
uint kdAboveChild(uvec2 n) { return n.y >> VKRAY_KD_CHILD_SHIFT; }
uint kdFirstIndex(uvec2 n) { return n.x; }
uint kdTriangleCount(uvec2 n) { return n.y >> 2; }

const float kKdSmallestNormal = 1.17549435e-38;

struct KdRay {
    vec3 origin;
    vec3 dir;
    vec3 invDir;     // 0 where parallel (never used there)
    bvec3 parallel;  // direction component +-0 or denormal
};

KdRay makeKdRay(vec3 origin, vec3 dir) {
    KdRay r;
    r.origin = origin;
    r.dir = dir;
    r.parallel = lessThan(abs(dir), vec3(kKdSmallestNormal));
    r.invDir = mix(1.0 / mix(dir, vec3(1.0), r.parallel), vec3(0.0), r.parallel);
    return r;
}

float kdPlaneHit(KdRay r, uint axis, float plane) {
    precise const float t = (plane - r.origin[axis]) * r.invDir[axis];
    return t;
}

// One pass of a walk (kd_traversal.h, PassState): side mask for in-plane nodes, rank order for
// ties between planes of different axes, and what the walk met. code = mask | order << 3.
struct KdPass {
    uint code;
    uint mask;
    uint ranks;    // 2 bits per axis (x: bits 0-1): the tie order; bit fields, not an indexed array
    uint tieOrder; // kdCompare's answer for a tie of axes a0, a1: 2 signed bits at 8 a0 + 2 a1 (kdTieOrder)
    uint inPlane;  // axes of the in-plane nodes met, over all passes so far
    uint tied;     // axes of planes that tied with another axis' plane, over all passes so far
};

// The 6 tie orders of kd_traversal.cpp's kKdRanks as rank bit fields, 6 bits each: orders 0-4 packed
// in one constant, order 5 is (2, 1, 0) = 6. Dynamic indexing of an array or vector held per
// invocation makes llvmpipe keep the pass state in memory, read and written lane by lane.
uint kdRankBits(uint order) { return order < 5u ? (304449636u >> (6u * order)) & 63u : 6u; }
uint kdRank(uint ranks, uint axis) { return (ranks >> (2u * axis)) & 3u; }
const uint kKdHardBound = 3u;  // a segment end on no plane: 0 or the caller's tmax

// The order of two planes of different axes crossed at the same t, for every pair of axes at once:
// -1 (binary 11) where a0 ranks before a1, +1 (01) after, 0 where a0 == a1 or either is
// kKdHardBound (pairs with axis 3 stay 0). One table lookup per comparison instead of two rank
// extractions and three tests: a kd step compares twice, and ties cost every step on llvmpipe.
uint kdTiePair(uint ranks, uint a0, uint a1) {
    return (kdRank(ranks, a0) < kdRank(ranks, a1) ? 3u : 1u) << (8u * a0 + 2u * a1);
}
uint kdTieOrder(uint ranks) {
    return kdTiePair(ranks, 0u, 1u) | kdTiePair(ranks, 0u, 2u) | kdTiePair(ranks, 1u, 0u) |
           kdTiePair(ranks, 1u, 2u) | kdTiePair(ranks, 2u, 0u) | kdTiePair(ranks, 2u, 1u);
}

void kdSetOrder(inout KdPass p, uint order) {
    p.ranks = kdRankBits(order);
    p.tieOrder = kdTieOrder(p.ranks);
}

KdPass kdFirstPass() {
    KdPass p;
    p.code = 0u;
    p.mask = 0u;
    kdSetOrder(p, 0u);
    p.inPlane = 0u;
    p.tied = 0u;
    return p;
}

// -1, 0, +1 as plane (t0, a0) is crossed before, with, after plane (t1, a1) (PassState::compare).
int kdCompare(inout KdPass p, float t0, uint a0, float t1, uint a1) {
    const int tie = bitfieldExtract(int(p.tieOrder), int(8u * a0 + 2u * a1), 2);
    if (t0 == t1 && tie != 0) p.tied |= (1u << a0) | (1u << a1);
    return t0 != t1 ? (t0 < t1 ? -1 : 1) : tie;
}

uint kdOrderSignature(uint order, uint tied) {
    const uint r = kdRankBits(order), x = kdRank(r, 0u), y = kdRank(r, 1u), z = kdRank(r, 2u);
    uint sig = 0u;
    if ((tied & 3u) == 3u && x < y) sig |= 1u;
    if ((tied & 5u) == 5u && x < z) sig |= 2u;
    if ((tied & 6u) == 6u && y < z) sig |= 4u;
    return sig;
}

bool kdBit64(uvec2 set, uint i) { return ((i < 32u ? set.x >> i : set.y >> (i - 32u)) & 1u) != 0u; }
uvec2 kdSetBit64(uvec2 set, uint i) { return i < 32u ? uvec2(set.x | (1u << i), set.y) : uvec2(set.x, set.y | (1u << (i - 32u))); }

// Marks the pass just walked and moves `p` to the next one (nextPass() of kd_traversal.cpp); false
// when none is left. Loops only for the rare rays that met an in-plane node or a tie.
bool kdNextPass(inout KdPass p, inout uvec2 walked) {
    walked = kdSetBit64(walked, p.code);
    if ((p.inPlane | p.tied) == 0u) return false;
    uvec2 covered = uvec2(0u);
    for (uint c = 0u; c < 48u; ++c)
        if (kdBit64(walked, c)) covered = kdSetBit64(covered, (c & 7u) * 8u + kdOrderSignature(c >> 3, p.tied));
    for (uint c = 0u; c < 48u; ++c) {
        if (((c & 7u) & ~p.inPlane) != 0u) continue;
        if (!kdBit64(covered, (c & 7u) * 8u + kdOrderSignature(c >> 3, p.tied))) {
            p.code = c;
            p.mask = c & 7u;
            kdSetOrder(p, c >> 3);
            return true;
        }
    }
    return false;
}

// One slab of the box clip; false when the ray runs parallel to it outside. Ends carry their axis.
bool kdClipSlab(KdRay r, uint axis, float lo, float hi, inout float tmin, inout uint tminAxis, inout float tmax,
                inout uint tmaxAxis, inout KdPass p) {
    if (r.parallel[axis]) return r.origin[axis] >= lo && r.origin[axis] <= hi;
    float tNear = kdPlaneHit(r, axis, lo), tFar = kdPlaneHit(r, axis, hi);
    if (r.dir[axis] < 0.0) {
        const float swap = tNear;
        tNear = tFar;
        tFar = swap;
    }
    if (kdCompare(p, tNear, axis, tmin, tminAxis) > 0) {
        tmin = tNear;
        tminAxis = axis;
    }
    if (kdCompare(p, tFar, axis, tmax, tmaxAxis) < 0) {
        tmax = tFar;
        tmaxAxis = axis;
    }
    return true;
}

// [tmin, tmax] narrowed to the closed box; false when nothing is left. Unrolled: no loop iterations.
bool kdClipBox(KdRay r, vec3 lo, vec3 hi, inout float tmin, inout uint tminAxis, inout float tmax,
               inout uint tmaxAxis, inout KdPass p) {
    return kdClipSlab(r, 0u, lo.x, hi.x, tmin, tminAxis, tmax, tmaxAxis, p) &&
           kdClipSlab(r, 1u, lo.y, hi.y, tmin, tminAxis, tmax, tmaxAxis, p) &&
           kdClipSlab(r, 2u, lo.z, hi.z, tmin, tminAxis, tmax, tmaxAxis, p) &&
           kdCompare(p, tmin, tminAxis, tmax, tmaxAxis) <= 0;
}

// The exit of one slab of a box, when it comes before (t1, a1).
void kdExitSlab(KdRay r, uint axis, float exitPlane, inout float t1, inout uint a1, inout KdPass pass) {
    if (r.parallel[axis]) return;
    const float tFar = kdPlaneHit(r, axis, exitPlane);
    if (kdCompare(pass, tFar, axis, t1, a1) < 0) {
        t1 = tFar;
        a1 = axis;
    }
}

// Where the ray leaves box [lo, hi], when before (t1, a1): only the far faces, for a box that holds
// the point where the segment starts (kd-backtrack's ancestors, kd-ropes' rope nodes; exitFromBox in
// kd_traversal.cpp).
// Unrolled: no loop iterations.
void kdBoxExit(KdRay r, vec3 lo, vec3 hi, inout float t1, inout uint a1, inout KdPass pass) {
    const vec3 exitPlane = mix(lo, hi, greaterThan(r.dir, vec3(0.0)));
    kdExitSlab(r, 0u, exitPlane.x, t1, a1, pass);
    kdExitSlab(r, 1u, exitPlane.y, t1, a1, pass);
    kdExitSlab(r, 2u, exitPlane.z, t1, a1, pass);
}

// Whether inner node n's child below its plane (or above it) is a leaf without triangles: the node's
// flag bits (kd_layout.h), read without the child.
bool kdChildEmpty(uvec2 n, bool below) {
    return (n.y & (below ? VKRAY_KD_EMPTY_BELOW : VKRAY_KD_EMPTY_ABOVE)) != 0u;
}

const int kKdFirst = 0, kKdSecond = 1, kKdBoth = 2, kKdPastFirst = 3;

// One inner-node step: which children of inner node `index` the segment [tmin, tmax] reaches.
// kKdPastFirst: both, but the first is a leaf without triangles (the node's flag bits, kd_layout.h):
// the walk goes on in the second from the plane, as it would after visiting that leaf, without the
// step onto it and the restart, climb or pop after it.
int kdStepInner(KdRay r, uvec2 n, uint index, float tmin, uint tminAxis, float tmax, uint tmaxAxis,
                inout KdPass p, out uint first, out uint second, out float thit) {
    const uint axis = kdAxis(n);
    const float split = kdSplit(n);
    const uint below = index + 1u, above = kdAboveChild(n);
    // A ray parallel to the plane stays on its origin's side: it takes the step as one whose plane
    // lies behind it (thit = -inf: the second child only, and no tie), with the origin's side as the
    // second child; in the plane, the side of the pass's mask, and other passes take the other.
    // Selects, no branch and no early return: llvmpipe runs both sides of every branch, and this
    // step runs at every node of every walk.
    const bool parallel = r.parallel[axis];
    const float o = r.origin[axis];
    const bool inPlane = parallel && o == split;
    p.inPlane |= inPlane ? 1u << axis : 0u;
    const bool up = parallel ? o > split || (inPlane && ((p.mask >> axis) & 1u) != 0u) : r.dir[axis] > 0.0;
    first = up ? below : above;
    second = up ? above : below;
    thit = parallel ? -kInfinity : kdPlaneHit(r, axis, split);
    if (kdCompare(p, thit, axis, tmax, tmaxAxis) >= 0) return kKdFirst;
    if (kdCompare(p, thit, axis, tmin, tminAxis) <= 0) return kKdSecond;
    return kdChildEmpty(n, up) ? kKdPastFirst : kKdBoth;  // the first child is the one below when up
}

// Takes the step kdStepInner chose: the child to descend to, with the segment cut at the plane when
// both are reached (kd-stack pushes the second child first; kd-restart and kd-backtrack drop it), or
// starting there when the first is passed.
uint kdDescend(int visit, uvec2 n, uint first, uint second, float thit, inout float segMin, inout uint minAxis,
               inout float segMax, inout uint maxAxis) {
    if (visit == kKdBoth) {
        segMax = thit;
        maxAxis = kdAxis(n);
    }
    if (visit == kKdPastFirst) {
        segMin = thit;
        minAxis = kdAxis(n);
    }
    return visit == kKdSecond || visit == kKdPastFirst ? second : first;
}

// Whether the step at inner node `index` (n) reached one child alone, `child`, and it is a leaf
// without triangles: a walk may then go on as it would after visiting that leaf (kd_stack.glsl).
bool kdOnlyChildEmpty(uvec2 n, uint index, int visit, uint child) {
    return (visit == kKdFirst || visit == kKdSecond) && kdChildEmpty(n, child == index + 1u);
}

// Where a restart begins (kd-restart, kd-pushdown, and kd-shortstack once its stack ran dry): the
// root, or with push-down (Horn, Sugerman, Houston and Hanrahan, "Interactive k-D Tree GPU
// Raytracing", I3D 2007, section 4.1) the last node a descent entered before its first step that
// reached both children: every ancestor of that node sends the rest of the ray to it
// (KdRestartTracer::walkPass). The CPU twin is RestartPoint in kd_traversal.cpp.
struct KdRestartPoint {
    uint node;
    bool whole;  // no step of this descent has reached both children yet
};

KdRestartPoint kdRootRestart() { return KdRestartPoint(0u, true); }

// After a descending step to `child`: with push-down (a constant at every call, so it folds), the
// restart node follows the descent while it is whole.
void kdEntered(inout KdRestartPoint p, const bool pushDown, int visit, uint child) {
    if (!pushDown) return;
    p.whole = p.whole && visit != kKdBoth;
    p.node = p.whole ? child : p.node;
}

// Restarts past the leaf just left: the segment from its exit to the pass's end; returns the node
// to descend from.
uint kdRestart(inout KdRestartPoint p, float passMax, uint passMaxAxis, inout float segMin, inout uint minAxis,
               inout float segMax, inout uint maxAxis) {
    segMin = segMax;
    minAxis = maxAxis;
    segMax = passMax;
    maxAxis = passMaxAxis;
    p.whole = true;
    countRestart();
    return p.node;
}

// A leaf lists its triangles in the index list: a triangle may lie in several leaves.
uint slotTriangle(uint slot) { return indexTexel(int(slot)).x; }

// The step onto leaf `n` that a descent loop ended at: false when it ended elsewhere, at the step
// cap or cut short by the driver (the pass then ends unfinished).
bool kdLeafStep(uvec2 n, inout int steps) {
    if (!kdIsLeaf(n) || steps >= VKRAY_KD_MAX_STEPS) return false;
    countNode();
    ++steps;
    return true;
}

// The leaf's triangles against (0, best.t); with anyHit, stops at the first hit.
void kdVisitLeaf(uvec2 n, WatertightRay w, const bool anyHit, inout Hit best) {
    countLeaf();
    testSlots(kdFirstIndex(n), kdFirstIndex(n) + kdTriangleCount(n), w, anyHit, LEAF_SLOTS, best);
}

// Whether the search may stop after a leaf whose segment ends at `exit`: a hit before it, with a
// few ulps to spare (kRoundingSlack). A hit at the exit may tie with a triangle of the next leaf (a face lying in
// the split plane, an edge on it) whose index is lower and wins (beats()); and the triangle test
// and the plane hit round differently: a triangle of the next leaf can be hit an ulp before the
// plane's computed t (measured on scenes/stress/split-planes.scene: a ray through the edge where
// two faces lying in split planes x = 0 and y = 2 meet). That leaf is visited too.
bool kdFinished(Hit best, bool anyHit, float exit) {
    return best.triangle >= 0 && (anyHit || best.t * kRoundingSlack < exit);
}

// After a pass: whether another follows. Not when the pass was cut short (its node loop ran out:
// the walk ends unfinished), an occluder was found, or every pass the ray needs is walked.
bool kdAnotherPass(bool passDone, bool anyHit, Hit best, inout KdPass p, inout uvec2 walked) {
    return passDone && !(anyHit && best.triangle >= 0) && kdNextPass(p, walked);
}

// A traversal loop ended: if not by its own exit, either the cap (a runaway ray, counted) or the
// driver (llvmpipe's loop budget: the pixel is flagged).
void kdEndLoop(bool done, int steps) {
    if (done) return;
    if (steps >= VKRAY_KD_MAX_STEPS) ++gCappedRays;
    else gLoopCutShort = true;
}

// One pass of the walk, defined by each traversal include: from the root, over the segment
// [segMin, segMax] of the ray already clipped to the root box, visiting leaves (kdVisitLeaf) until
// kdFinished or nothing is left. Each node step counts in `steps`; the loop stops at
// VKRAY_KD_MAX_STEPS. Returns whether the pass ended by its own rule (false: the cap, or the driver).
bool kdWalkPass(KdRay r, WatertightRay w, const bool anyHit, float segMin, uint minAxis, float segMax,
                uint maxAxis, inout KdPass pass, inout int steps, inout Hit best);

// The walk (KdTracer::walk): passes over the tree until every pass the ray needs is walked. Passes
// are an outer loop: llvmpipe runs every statement of a loop body for all lanes, masked, so pass
// switching inside the node loop would weigh on every step. With anyHit (a constant at
// both calls below, so the compiler folds it) the first hit found ends the walk.
Hit kdTrace(vec3 origin, vec3 dir, float tmax, const bool anyHit) {
    Hit best = noHit(tmax);
    const KdRay r = makeKdRay(origin, dir);
    const WatertightRay w = makeWatertightRay(origin, dir);
    KdPass pass = kdFirstPass();
    uvec2 walked = uvec2(0u);
    int steps = 0;
    bool passDone = true;
    vec3 rootLo, rootHi;
    kdRootBox(rootLo, rootHi);
    for (uint passes = 0u; budgetLeft() && passes < 8u; ++passes) {
        // The root box clip in the pass too: its faces may tie with each other.
        float segMin = 0.0, segMax = tmax;
        uint minAxis = kKdHardBound, maxAxis = kKdHardBound;
        passDone = !kdClipBox(r, rootLo, rootHi, segMin, minAxis, segMax, maxAxis, pass) ||
                   kdWalkPass(r, w, anyHit, segMin, minAxis, segMax, maxAxis, pass, steps, best);
        // Another pass for an in-plane node or a tie met, or the end.
        if (!kdAnotherPass(passDone, anyHit, best, pass, walked)) break;
    }
    kdEndLoop(passDone, steps);
    return best;
}

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return kdTrace(origin, dir, tmax, false); }
bool traceAny(vec3 origin, vec3 dir, float tmax) { return kdTrace(origin, dir, tmax, true).triangle >= 0; }

#endif
