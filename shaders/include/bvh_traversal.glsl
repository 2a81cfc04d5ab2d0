// The `bvh` accelerator (accel/bvh: AAC after Gu et al. 2013, or the binned-SAH reference): a
// depth-first array of 32-byte nodes (shared/bvh_layout.h) over the triangle buffer in leaf order.
//
// One loop for both queries, one iteration per node. Closest hit: at an inner node both children's
// boxes are tested; the nearer one is visited next and the farther one pushed, with its entry
// distance, on a short stack in local memory; a popped node entered beyond the best hit so far is
// skipped. Any hit (shadow rays) walks the same way without ordering and stops at the first
// triangle hit. Leaves test their triangles in the loop of leaf_triangles.glsl.
#ifndef VKRAY_BVH_TRAVERSAL_GLSL
#define VKRAY_BVH_TRAVERSAL_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "constants.glsl"
#include "leaf_triangles.glsl"
#include "shared/bvh_layout.h"
#include "trace_status.glsl"
#include "triangle.glsl"

layout(std430, set = 0, binding = VKRAY_BINDING_ACCEL_NODES) readonly buffer BvhNodes {
    GpuBvhNode bvhNodes[];
};

// Below this magnitude a direction component counts as zero: its inverse would overflow.
const float kFlatDirection = 1.0e-30;

// Per-ray constants of the slab test. A direction component of +-0 gets inverse 0 (never inf, so
// no 0 * inf = NaN can reach min/max) and a flag: the ray then stays in the plane x_a = origin_a,
// which is inside the slab for every t or for none.
struct BoxRay {
    vec3 origin;
    vec3 inv;
    bvec3 flat_;
    bool anyFlat;
};

BoxRay makeBoxRay(vec3 origin, vec3 dir) {
    BoxRay r;
    r.origin = origin;
    r.flat_ = lessThan(abs(dir), vec3(kFlatDirection));
    r.inv = mix(1.0 / dir, vec3(0.0), r.flat_);
    r.anyFlat = any(r.flat_);
    return r;
}

// Whether the ray meets the node's box for t in [0, tLimit]; tEnter = where it enters.
bool hitsBox(GpuBvhNode node, BoxRay r, float tLimit, out float tEnter) {
    const vec3 t0 = (node.lo - r.origin) * r.inv, t1 = (node.hi - r.origin) * r.inv;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    if (r.anyFlat) {  // rare: only rays with a zero direction component pay for it
        const bvec3 inside = bvec3(uvec3(lessThanEqual(node.lo, r.origin)) * uvec3(lessThanEqual(r.origin, node.hi)));
        tNear = mix(tNear, mix(vec3(kInfinity), vec3(-kInfinity), inside), r.flat_);
        tFar = mix(tFar, mix(vec3(-kInfinity), vec3(kInfinity), inside), r.flat_);
    }
    tEnter = max(max(tNear.x, tNear.y), max(tNear.z, 0.0));
    // The far distance widened for float rounding, so a box never rejects a ray that touches it.
    const float tExit = min(min(tFar.x, tFar.y), min(tFar.z, tLimit)) * kRoundingSlack;
    return tEnter <= tExit;
}

// Leaves are runs of the triangle buffer in leaf order: Hit.triangle is a slot of it.
uint slotTriangle(uint slot) { return slot; }

// Closest hit in (0, tmax), or with anyHit (a constant at both calls below, so the compiler folds
// every test of it) the first hit found. For any hit best.t stays tmax until the walk ends.
Hit bvhTrace(vec3 origin, vec3 dir, float tmax, const bool anyHit) {
    Hit best = noHit(tmax);
    float tRoot;
    const BoxRay boxRay = makeBoxRay(origin, dir);
    if (params.counts.x == 0u || !hitsBox(bvhNodes[0], boxRay, tmax, tRoot)) return best;
    const WatertightRay ray = makeWatertightRay(origin, dir);

    uint stackNode[VKRAY_BVH_STACK_SIZE];
    float stackEnter[VKRAY_BVH_STACK_SIZE];  // closest hit only
    int top = 0;
    uint node = 0;
    // A popped node entered beyond the best hit found since it was pushed is skipped: that costs
    // its iteration but reads no node. "Beyond" with the slab test's own widening: the triangle
    // test and the slab test round differently, and a triangle lying in a face of its box (axis-
    // aligned geometry) was measured to hit one ulp before the box's computed entry; compared
    // unwidened, that node was skipped and a closer hit, or an equal-t one of lower index
    // (beats(), triangle.glsl), lost (scenes/stress/split-planes.scene, 3 of 3969 camera rays).
    // Any hit never skips: it ends at its first hit.
    bool skip = false, done = false;
    int iteration = 0;
    for (; iteration < VKRAY_BVH_MAX_ITERATIONS && !done; ++iteration) {
        bool descend = false;
        if (!skip) {
            const GpuBvhNode n = bvhNodes[node];
            countNode();
            if (n.count > 0u) {
                countLeaf();
                const uint first = n.rightOrFirst;
                // Cut short by the driver (flagged there), or an occluder found: the walk ends.
                if (!testSlots(first, first + n.count, ray, anyHit, best) || (anyHit && best.triangle >= 0))
                    return best;
            } else {
                const uint left = node + 1u, right = n.rightOrFirst;
                float tl, tr;
                const bool hitLeft = hitsBox(bvhNodes[left], boxRay, best.t, tl);
                const bool hitRight = hitsBox(bvhNodes[right], boxRay, best.t, tr);
                if (hitLeft && hitRight) {
                    if (top == VKRAY_BVH_STACK_SIZE) {  // deeper than the stack: flag, never guess
                        gLoopCutShort = true;
                        return best;
                    }
                    // Closest hit: near child first, the far one waits. Any hit: left first.
                    const bool leftFirst = anyHit || tl <= tr;
                    stackNode[top] = leftFirst ? right : left;
                    if (!anyHit) stackEnter[top] = leftFirst ? tr : tl;
                    ++top;
                    node = leftFirst ? left : right;
                    descend = true;
                } else if (hitLeft || hitRight) {
                    node = hitLeft ? left : right;
                    descend = true;
                }
            }
        }
        if (!descend) {
            done = top == 0;
            if (!done) {
                --top;
                node = stackNode[top];
                if (!anyHit) skip = stackEnter[top] > best.t * kRoundingSlack;
            }
        }
    }
    if (!done) {
        if (iteration >= VKRAY_BVH_MAX_ITERATIONS) ++gCappedRays;
        else gLoopCutShort = true;
    }
    return best;
}

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return bvhTrace(origin, dir, tmax, false); }
bool traceAny(vec3 origin, vec3 dir, float tmax) { return bvhTrace(origin, dir, tmax, true).triangle >= 0; }

#endif
