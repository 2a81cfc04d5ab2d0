// The three kd-tree traversals of Foley and Sugerman, "KD-Tree Acceleration Structures for a GPU
// Raytracer", Graphics Hardware 2005 (their pseudocode as reproduced in S. A. Mulia, "Penggunaan k-d Tree
// dalam Ray Tracing", ITB 2018), in double precision on the CPU over the very arrays the GPU kernels read
// (kd_layout.h), so the unit tests check the algorithms and the layout off the GPU.
// shaders/include/kd_{stack,restart,backtrack}.glsl are the float twins (kd-stack's kernel also
// passes leaves without triangles without stepping onto them: the same hits, fewer leaves counted).
//
// All three share (docs/kdtree.md, "Floating point"):
//  - Children in ray order by the sign of the direction (the pseudocode's order(ray.direction[a],
//    ...)); the ray's segment [tmin, tmax] goes to the first child only when the plane's hit thit >=
//    tmax, to the second only when thit <= tmin, else to both. A negative thit means the plane lies
//    behind: the segment is then on the second side, which `thit <= tmin` covers (tmin >= 0). Foley and
//    Sugerman's `thit < 0 -> first` assumes origin-side ordering; with direction order it is wrong.
//  - A direction component of +-0 never divides: the segment stays on the origin's side.
//  - In-plane rays: a ray lying in a node's split plane (dir[axis] == +-0 and origin[axis] == split,
//    both exact) is ambiguous: the builder puts a triangle touching the plane on one side only, so
//    the ray may hit triangles on either side. Each walk is a pass with a side mask (bit a set: at
//    an in-plane node of axis a take the above child, else the below one) that records the axes
//    where it met an in-plane node; further passes walk every other mask over those axes (a set that
//    grows during a later pass is honoured), at most 8 in all, and the best hit of all passes wins
//    (any hit: the first pass to find one ends the search). On one root-to-leaf path at most one
//    node per axis can split at the ray's coordinate (a descendant's box has that plane as a face),
//    so the masks enumerate every leaf whose closed box holds a point of the ray.
//  - Ties: a plane hit exactly equal to a segment end that lies on a plane of another axis (the ray
//    passes exactly through an edge or corner where leaves meet) is ordered by the pass's ranks
//    (PassState), and further passes take the other orders of the axes that tied, so the leaves
//    touched only at that edge or corner are visited too. Masks and orders: at most 8 passes.
//    A ray that meets no in-plane node and no tie walks once, as a plain walk would.
//  - Every plane is hit at t = (plane - origin) / direction, the same expression for splits and box
//    faces, so "the leaf's exit" and "the plane's hit" compare equal exactly when they are the same
//    plane; kd-restart and kd-backtrack rely on it to step past a leaf exactly once.
//  - A leaf's triangles are tested on the whole ray (0, best), not only inside the leaf: a hit found
//    beyond the leaf is kept as the candidate but does not end the search; the search ends when the
//    candidate lies before the current leaf's exit with a relative 1e-9 to spare (pbrt's rule,
//    robust to rounding at the leaf's faces; made strict so that a triangle of the next leaf hit at
//    the same t, up to rounding, can still win the tie). Ties in t go to the lowest triangle index,
//    as in brute force.
//  - A hard cap on loop iterations ends a runaway ray, counted in TraversalCounters::capped.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "accel/kd/kd_tree.h"
#include "geometry/ray_triangle.h"
#include "geometry/tracer.h"

namespace vkray::accel::kd {

// Part [tmin, tmax] of a ray. Each end remembers the axis of the plane it lies on (a split or a box
// face), 3 for a hard bound (0 or the caller's tmax): ties between planes are broken by axis.
struct Segment {
    double tmin = 0.0, tmax = 0.0;
    int minAxis = 3, maxAxis = 3;
};

// One pass of a walk: the choices that make every comparison of the walk strict, and what it met.
//  - mask: bit a set = at an in-plane node of axis a take the above child, else the below one.
//  - rank: when planes of two different axes are crossed at exactly the same t (the ray passes
//    exactly through an edge or corner where leaves meet), the one of lower rank counts as crossed
//    first: the walk then follows a ray moved infinitesimally off the edge, which visits the leaves
//    on one side of it; other passes take the other orders.
struct PassState {
    unsigned mask = 0;
    std::array<int, 3> rank{0, 1, 2};
    unsigned inPlane = 0;  // out: axes of the in-plane nodes met
    unsigned tied = 0;     // out: axes of the planes that tied with another axis' plane
    // -1, 0, +1 as plane (t0, a0) is crossed before, with, after plane (t1, a1).
    int compare(double t0, int a0, double t1, int a1) {
        if (t0 != t1) return t0 < t1 ? -1 : 1;
        if (a0 == a1 || a0 == 3 || a1 == 3) return 0;
        tied |= 1u << a0 | 1u << a1;
        return rank[a0] < rank[a1] ? -1 : 1;
    }
};

// What a traversal does with each leaf it reaches, in ray order; visit() returns true to stop.
class LeafVisitor {
public:
    virtual bool visit(const gpu::KdNode& leaf, double exit) = 0;
    // True once no further pass can change the answer (any hit: an occluder was found).
    virtual bool satisfied() const { return false; }

protected:
    ~LeafVisitor() = default;
};

class KdTracer : public geometry::Tracer {
public:
    // `tree` must outlive the tracer; `triangles` in scene order (the indices' meaning).
    KdTracer(const KdTree& tree, std::vector<geometry::TriangleVertices> triangles, int maxSteps = VKRAY_KD_MAX_STEPS);

    geometry::Hit closest(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters = nullptr) const override;
    bool occluded(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters = nullptr) const override;

    // Hands the leaves the ray's segment passes to `visitor`, in ray order, once per side mask that
    // the ray's in-plane nodes call for (see above); stops when the visitor is satisfied.
    void walk(const geometry::Ray& ray, Segment segment, LeafVisitor& visitor, geometry::TraversalCounters& counters) const;

    // One pass (PassState: side mask and tie order in, in-plane and tied axes out): what the three
    // traversals differ in. `steps` counts loop iterations over all passes. Returns false when the
    // iteration cap ended it (counted in counters.capped).
    virtual bool walkPass(const geometry::Ray& ray, Segment segment, PassState& pass, LeafVisitor& visitor,
                          geometry::TraversalCounters& counters, int& steps) const = 0;

protected:
    const KdTree& tree_;
    std::vector<geometry::TriangleVertices> triangles_;
    int maxSteps_;
};

// The standard traversal with a per-ray stack (Foley and Sugerman; Mulia 2018, figure 9): the baseline.
// With a short stack of `shortStack` entries (Horn, Sugerman, Houston and Hanrahan 2007, section
// 4.2; 0 = the full stack): a push onto a full stack drops the oldest entry, and when the stack
// runs dry with part of the ray left, the walk restarts past the leaf at the node push-down keeps
// (KdRestartTracer).
class KdStackTracer final : public KdTracer {
public:
    KdStackTracer(const KdTree& tree, std::vector<geometry::TriangleVertices> triangles, int maxSteps, int shortStack)
        : KdTracer(tree, std::move(triangles), maxSteps), shortStack_(shortStack) {}
    bool walkPass(const geometry::Ray& ray, Segment segment, PassState& pass, LeafVisitor& visitor,
                  geometry::TraversalCounters& counters, int& steps) const override;

private:
    int shortStack_;
};

// Where kd-restart's walk goes on after a leaf: the root (Foley and Sugerman 4.1), the push-down
// node (Horn, Sugerman, Houston and Hanrahan 2007, section 4.1), or the leaf's rope across the face
// the ray leaves it by (Popov, Guenther, Seidel and Slusallek 2007, section 3; needs tree.ropes).
enum class RestartFrom { Root, PushDown, Rope };

// Stackless kd-restart (Foley and Sugerman 4.1): after a leaf, tmin = the leaf's exit and the search
// starts again at the root. With push-down it starts again at the deepest node whose region holds
// the whole rest of the ray: the last node the descent entered before it first reached both
// children of a node. With ropes it starts at the rope of the leaf's exit face, the smallest node
// holding that whole face, with the rest of the ray clipped to that node's box (a descent from there
// crosses only the node's own splits); a rope off the root box ends the walk.
class KdRestartTracer final : public KdTracer {
public:
    KdRestartTracer(const KdTree& tree, std::vector<geometry::TriangleVertices> triangles, int maxSteps,
                    RestartFrom from)
        : KdTracer(tree, std::move(triangles), maxSteps), from_(from) {}
    bool walkPass(const geometry::Ray& ray, Segment segment, PassState& pass, LeafVisitor& visitor,
                  geometry::TraversalCounters& counters, int& steps) const override;

private:
    RestartFrom from_;
};

// Stackless kd-backtrack (Foley and Sugerman 4.2): after a leaf, climb by parent links to the
// nearest ancestor whose box still overlaps (tmin, tmax) and descend from there.
class KdBacktrackTracer final : public KdTracer {
public:
    using KdTracer::KdTracer;
    bool walkPass(const geometry::Ray& ray, Segment segment, PassState& pass, LeafVisitor& visitor,
                  geometry::TraversalCounters& counters, int& steps) const override;
};

// Passes are numbered code = mask | order << 3 (order: one of the 6 rank permutations, kKdRanks).
// The next pass to walk, or -1: the lowest code with mask within `inPlane` whose mask and order
// restricted to `tied` no walked pass had (bit c of `walked`: code c walked). The same function as
// kdNextPass() in kd_common.glsl.
int nextPass(unsigned inPlane, unsigned tied, uint64_t walked);

// kd-shortstack's stack size defaults to the kernel's (VKRAY_KD_SHORT_STACK_SIZE); `shortStack`
// other than 0 sets it, for experiments (the CPU only).
std::unique_ptr<KdTracer> makeKdTracer(kd::Traversal traversal, const KdTree& tree,
                                       std::vector<geometry::TriangleVertices> triangles, int maxSteps = VKRAY_KD_MAX_STEPS,
                                       int shortStack = 0);

// The ray's segment inside the closed box within `within`, or nothing (exposed for the tests).
std::optional<Segment> clipToBox(const geometry::Ray& ray, const glm::vec3& lo, const glm::vec3& hi, Segment within);
std::optional<Segment> clipToBox(const geometry::Ray& ray, const glm::vec3& lo, const glm::vec3& hi, Segment within,
                                 PassState& pass);

}  // namespace vkray::accel::kd
