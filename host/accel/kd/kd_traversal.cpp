#include "accel/kd/kd_traversal.h"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace vkray::accel::kd {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Where the ray meets the plane x[axis] = plane: the one expression every traversal step and box
// clip uses (see the header). Only called with dir[axis] != 0.
double planeHit(const geometry::Ray& ray, int axis, float plane) {
    return (double(plane) - ray.origin[axis]) / ray.dir[axis];
}

// PastFirst: both children, but the first is a leaf without triangles (the node's flag bits,
// kd_layout.h): the walk goes on in the second from the plane, as it would after visiting that
// leaf, without the step onto it and the pop, restart or climb after it.
enum class Visit { First, Second, Both, PastFirst };

struct SplitStep {
    Visit visit;
    uint32_t first, second;  // children in ray order
    double thit;
    int axis;
};

// One inner node of Foley and Sugerman's search-split() (2005): which children the segment [tmin, tmax]
// reaches. A ray lying in the plane takes the side the pass's mask names and records the axis; plane hits
// equal to an end of the segment are ordered by the pass's ranks (PassState::compare).
SplitStep stepInner(const geometry::Ray& ray, const gpu::KdNode& node, uint32_t index, const Segment& seg,
                    PassState& pass) {
    const int axis = node.axis();
    const uint32_t below = index + 1, above = node.aboveChild();
    const double d = ray.dir[axis];
    if (d == 0.0) {  // parallel to the plane: stays on the origin's side
        const double o = ray.origin[axis], split = double(node.split());
        uint32_t side = o < split ? below : above;
        if (o == split) {  // in the plane: the mask's side, and another pass for the other one
            pass.inPlane |= 1u << axis;
            side = (pass.mask >> axis) & 1u ? above : below;
        }
        return {Visit::First, side, side, kInf, axis};
    }
    const uint32_t first = d > 0.0 ? below : above, second = d > 0.0 ? above : below;
    const double thit = planeHit(ray, axis, node.split());
    if (pass.compare(thit, axis, seg.tmax, seg.maxAxis) >= 0) return {Visit::First, first, second, thit, axis};
    if (pass.compare(thit, axis, seg.tmin, seg.minAxis) <= 0) return {Visit::Second, first, second, thit, axis};
    return {node.childEmpty(d < 0.0) ? Visit::PastFirst : Visit::Both, first, second, thit, axis};
}

// Takes step `s`: the child to descend to, with the segment cut at the plane when both are reached
// (the stack traversal pushes the second child first; the stackless ones drop it), or starting
// there when the first is passed.
uint32_t descend(const SplitStep& s, Segment& seg) {
    if (s.visit == Visit::Both) {
        seg.tmax = s.thit;
        seg.maxAxis = s.axis;
    }
    if (s.visit == Visit::PastFirst) {
        seg.tmin = s.thit;
        seg.minAxis = s.axis;
    }
    return s.visit == Visit::Second || s.visit == Visit::PastFirst ? s.second : s.first;
}

// Where a restart begins (kd-restart, kd-pushdown, and kd-shortstack once its stack ran dry): the
// root, or with push-down (Horn, Sugerman, Houston and Hanrahan 2007, section 4.1) the last node a
// descent entered before its first step that reached both children (KdRestartTracer::walkPass says
// why that is safe). kdEntered/kdRestart in kd_common.glsl are the float twins.
struct RestartPoint {
    bool pushDown;
    uint32_t node = 0;
    bool whole = true;  // no step of this descent has reached both children yet

    void entered(Visit visit, uint32_t child) {
        if (!pushDown) return;
        whole = whole && visit != Visit::Both;
        if (whole) node = child;
    }
    // The segment from the leaf's exit, where `seg` ends, to the pass's end.
    static Segment rest(const Segment& seg, const Segment& global) {
        return {seg.tmax, global.tmax, seg.maxAxis, global.maxAxis};
    }
    // The rest of the pass (above); returns the node to descend from.
    uint32_t restart(Segment& seg, const Segment& global) {
        seg = rest(seg, global);
        whole = true;
        return node;
    }
};

// Where the ray leaves box [lo, hi], or `within`'s end if sooner. Only the exit: the callers' boxes
// hold the segment's start (kd-backtrack's ancestor holds the leaf just left; kd-ropes checks with
// ropeHoldsExit), so the near planes are hit at or before it, and a direction component of zero keeps
// the ray inside that slab.
std::pair<double, int> exitFromBox(const geometry::Ray& ray, const glm::vec3& lo, const glm::vec3& hi, Segment within,
                                   PassState& pass) {
    double exit = within.tmax;
    int exitAxis = within.maxAxis;
    for (int axis = 0; axis < 3; ++axis) {
        if (ray.dir[axis] == 0.0) continue;
        const double tFar = planeHit(ray, axis, ray.dir[axis] > 0.0 ? hi[axis] : lo[axis]);
        if (pass.compare(tFar, axis, exit, exitAxis) < 0) {
            exit = tFar;
            exitAxis = axis;
        }
    }
    return {exit, exitAxis};
}

// kd-ropes: whether the rope's node holds the ray at the exit of the leaf whose segment is `s`, in
// this pass's order of tied planes. The node holds the leaf's whole exit face, so on each other axis
// its near plane lies at or behind the leaf's own, and plane hits grow with the plane: it is hit at
// or before the leaf's near plane, which every descent step and box clip ordered at or before
// s.tmin. So it comes strictly before the exit when the segment has length. Without length it still
// comes no later when the segment starts and ends on planes of one axis past the pass's start (a
// flat leaf: the exit is the start, plane and axis, and each near plane compares with it as with
// the start); at the pass's start the chain of comparisons may pass through the walk's own start, a
// bound that ties with every plane, and the pass's order is not transitive there. Otherwise the ray
// left through an edge or corner where a tie may order a near plane of the node after the exit: the
// walk restarts. This replaces a test of the node's near planes against the exit at every step
// onto a rope (two plane hits and two tie-ordered compares), which the argument shows redundant.
bool ropeHoldsExit(const Segment& s, double passStart) {
    return s.tmin != s.tmax || (s.minAxis == s.maxAxis && s.tmin > passStart);
}

// Relative slack of the stop rule below: far above the few ulps by which a triangle's t and a plane's
// t round apart, far below any distance between leaves.
constexpr double kStopSlack = 1e-9;

// Closest hit over the leaves in ray order; ends once the best hit lies before the leaf's exit with
// a relative kStopSlack to spare. A hit at the exit may tie with a triangle of the next leaf (an edge
// or a face lying in the split plane, say) whose index is lower: that leaf is visited too, so ties
// still go to the lowest index as in brute force (measured on scenes/stress/split-planes.scene:
// with `<=`, 2 of 3969 camera rays kept a higher index).
class ClosestVisitor final : public LeafVisitor {
public:
    ClosestVisitor(const KdTree& tree, const std::vector<geometry::TriangleVertices>& tris, const geometry::Ray& ray,
                   double tmax, geometry::TraversalCounters& counters)
        : tree_(tree), tris_(tris), wray_(ray), counters_(counters) {
        best.t = tmax;
    }

    bool visit(const gpu::KdNode& leaf, double exit) override {
        const uint32_t begin = leaf.firstIndex(), end = begin + leaf.triangleCount();
        counters_.triangles += end - begin;
        for (uint32_t i = begin; i < end; ++i) {
            const uint32_t k = tree_.indices[i];
            // (0, best.t] once a hit exists, so an equal-t triangle of lower index can still win.
            const double upper = best.found() ? std::nextafter(best.t, kInf) : best.t;
            const auto hit = wray_.intersect(tris_[k], 0.0, upper);
            if (hit && (hit->t < best.t || (hit->t == best.t && int32_t(k) < best.triangle)))
                best = geometry::Hit{int32_t(k), hit->t, hit->b0, hit->b1, hit->b2};
        }
        return best.found() && best.t * (1.0 + kStopSlack) < exit;
    }

    geometry::Hit best;

private:
    const KdTree& tree_;
    const std::vector<geometry::TriangleVertices>& tris_;
    geometry::WatertightRay wray_;
    geometry::TraversalCounters& counters_;
};

// Any hit in (0, tmax): the first occluder ends the search, wherever on the ray it lies.
class AnyHitVisitor final : public LeafVisitor {
public:
    AnyHitVisitor(const KdTree& tree, const std::vector<geometry::TriangleVertices>& tris, const geometry::Ray& ray,
                  double tmax, geometry::TraversalCounters& counters)
        : tree_(tree), tris_(tris), wray_(ray), tmax_(tmax), counters_(counters) {}

    bool visit(const gpu::KdNode& leaf, double) override {
        const uint32_t begin = leaf.firstIndex(), end = begin + leaf.triangleCount();
        for (uint32_t i = begin; i < end; ++i) {
            ++counters_.triangles;
            if (wray_.intersect(tris_[tree_.indices[i]], 0.0, tmax_)) return occluded = true;
        }
        return false;
    }

    bool satisfied() const override { return occluded; }

    bool occluded = false;

private:
    const KdTree& tree_;
    const std::vector<geometry::TriangleVertices>& tris_;
    geometry::WatertightRay wray_;
    double tmax_;
    geometry::TraversalCounters& counters_;
};

}  // namespace

std::optional<Segment> clipToBox(const geometry::Ray& ray, const glm::vec3& lo, const glm::vec3& hi, Segment s,
                                 PassState& pass) {
    for (int axis = 0; axis < 3; ++axis) {
        if (ray.dir[axis] == 0.0) {  // no division by +-0 (0 * inf would be NaN): test the slab
            if (ray.origin[axis] < double(lo[axis]) || ray.origin[axis] > double(hi[axis])) return std::nullopt;
            continue;
        }
        double tNear = planeHit(ray, axis, lo[axis]), tFar = planeHit(ray, axis, hi[axis]);
        if (ray.dir[axis] < 0.0) std::swap(tNear, tFar);
        if (pass.compare(tNear, axis, s.tmin, s.minAxis) > 0) {
            s.tmin = tNear;
            s.minAxis = axis;
        }
        if (pass.compare(tFar, axis, s.tmax, s.maxAxis) < 0) {
            s.tmax = tFar;
            s.maxAxis = axis;
        }
    }
    if (pass.compare(s.tmin, s.minAxis, s.tmax, s.maxAxis) > 0) return std::nullopt;
    return s;
}

std::optional<Segment> clipToBox(const geometry::Ray& ray, const glm::vec3& lo, const glm::vec3& hi, Segment s) {
    PassState pass;
    return clipToBox(ray, lo, hi, s, pass);
}

namespace {
// Tie orders: ranks of x, y, z.
constexpr int kKdRanks[6][3] = {{0, 1, 2}, {1, 0, 2}, {0, 2, 1}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

// The order of `order` restricted to the axes of `tied`: one bit per pair of axes both in it.
unsigned orderSignature(int order, unsigned tied) {
    const int* r = kKdRanks[order];
    unsigned sig = 0;
    if ((tied & 3u) == 3u && r[0] < r[1]) sig |= 1u;
    if ((tied & 5u) == 5u && r[0] < r[2]) sig |= 2u;
    if ((tied & 6u) == 6u && r[1] < r[2]) sig |= 4u;
    return sig;
}
}  // namespace

int nextPass(unsigned inPlane, unsigned tied, uint64_t walked) {
    if ((inPlane | tied) == 0) return -1;  // the usual case: one pass did it all
    uint64_t covered = 0;  // bit mask * 8 + signature
    for (int c = 0; c < 48; ++c)
        if ((walked >> c) & 1u) covered |= uint64_t(1) << ((c & 7) * 8 + int(orderSignature(c >> 3, tied)));
    for (int c = 0; c < 48; ++c) {
        if ((unsigned(c & 7) & ~inPlane) != 0) continue;
        if (!((covered >> ((c & 7) * 8 + int(orderSignature(c >> 3, tied)))) & 1u)) return c;
    }
    return -1;
}

// At most 8 passes: in-plane axes have no plane crossings, so they never tie; the masks over the
// in-plane axes times the orders of the tied ones are 8 (two in-plane axes), 4 (one, and two tied),
// or 6 (none, three tied).
void KdTracer::walk(const geometry::Ray& ray, Segment segment, LeafVisitor& visitor, geometry::TraversalCounters& c) const {
    unsigned inPlane = 0, tied = 0;
    uint64_t walked = 0;
    int steps = 0;
    for (int code = 0; code >= 0; code = nextPass(inPlane, tied, walked)) {
        PassState pass;
        pass.mask = unsigned(code & 7);
        for (int a = 0; a < 3; ++a) pass.rank[a] = kKdRanks[code >> 3][a];
        // The root box clip too: its faces may tie with each other.
        const auto s = clipToBox(ray, tree_.header.lo, tree_.header.hi, segment, pass);
        const bool ok = !s || walkPass(ray, *s, pass, visitor, c, steps);
        inPlane |= pass.inPlane;
        tied |= pass.tied;
        walked |= uint64_t(1) << code;
        if (!ok || visitor.satisfied()) return;
    }
}

KdTracer::KdTracer(const KdTree& tree, std::vector<geometry::TriangleVertices> triangles, int maxSteps)
    : tree_(tree), triangles_(std::move(triangles)), maxSteps_(maxSteps) {}

geometry::Hit KdTracer::closest(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters) const {
    geometry::TraversalCounters local;
    geometry::TraversalCounters& c = counters ? *counters : local;
    ClosestVisitor visitor(tree_, triangles_, ray, tmax, c);
    walk(ray, {0.0, tmax}, visitor, c);
    geometry::Hit best = visitor.best;
    if (!best.found()) best.t = kInf;
    return best;
}

bool KdTracer::occluded(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters) const {
    geometry::TraversalCounters local;
    geometry::TraversalCounters& c = counters ? *counters : local;
    AnyHitVisitor visitor(tree_, triangles_, ray, tmax, c);
    walk(ray, {0.0, tmax}, visitor, c);
    return visitor.occluded;
}

// Foley and Sugerman's standard traversal (2005; figure 9 of S. A. Mulia, "Penggunaan k-d Tree dalam
// Ray Tracing", 2018), as a loop: one iteration per node; the stack holds the far children with
// their segments, nearest on top. The short stack (Horn et al. 2007, 4.2) is a ring of shortStack_
// entries at logical positions [bottom, top): a push onto a full ring drops the bottom one; when the
// ring runs dry before the segment reaches the global tmax (something was dropped), the walk
// restarts past the leaf with (exit, global tmax) at the push-down node (see KdRestartTracer).
bool KdStackTracer::walkPass(const geometry::Ray& ray, Segment global, PassState& pass, LeafVisitor& visitor,
                             geometry::TraversalCounters& c, int& steps) const {
    struct Pending {
        uint32_t node;
        Segment seg;
    };
    std::array<Pending, VKRAY_KD_STACK_SIZE> stack;
    const size_t slots = shortStack_ > 0 ? size_t(shortStack_) : stack.size();
    size_t top = 0, bottom = 0;
    uint32_t node = 0;
    RestartPoint restart{.pushDown = shortStack_ > 0};
    Segment seg = global;
    for (;; ++steps) {
        if (steps >= maxSteps_) {
            ++c.capped;
            return false;
        }
        ++c.nodes;
        const gpu::KdNode& n = tree_.nodes[node];
        if (!n.isLeaf()) {
            const SplitStep s = stepInner(ray, n, node, seg, pass);
            if (s.visit == Visit::Both) {
                if (top - bottom == slots) {
                    if (shortStack_ == 0) {  // deeper than any tree the builder makes: malformed
                        ++c.capped;
                        return false;
                    }
                    ++bottom;  // drop the oldest
                }
                stack[top++ % slots] = {s.second, {s.thit, seg.tmax, s.axis, seg.maxAxis}};
            }
            node = descend(s, seg);
            restart.entered(s.visit, node);
            continue;
        }
        ++c.leaves;
        if (visitor.visit(n, seg.tmax)) return true;
        if (top > bottom) {  // continue-search(): pop
            --top;
            node = stack[top % slots].node;
            seg = stack[top % slots].seg;
            continue;
        }
        if (shortStack_ == 0 || pass.compare(seg.tmax, seg.maxAxis, global.tmax, global.maxAxis) >= 0) return true;
        top = bottom = 0;  // the short stack ran dry: restart
        node = restart.restart(seg, global);
        ++c.restarts;
    }
}

// Foley and Sugerman 4.1: continue-search() sets tmin to the leaf's exit and restarts at the root.
// The descent sends the segment to the first child only when the plane lies strictly beyond tmin
// (stepInner: thit <= tmin goes second), so the leaf just left, whose exit is tmin, is never entered
// again: every restart advances strictly past the exit, and each leaf is visited once.
//
// Push-down: while a descent has reached only one child at every node, the rest of the ray up to
// the global tmax lies in the node it entered, so a restart may begin there; the first node with
// both children reached ends that (RestartPoint). Restarting there with (exit, global tmax) takes the
// steps a restart from the root would take below it: every ancestor sent the larger segment to
// one child, the same one the smaller segment goes to.
//
// Ropes: the rope's node holds the ray's point at the exit, and every ancestor above it sends
// (exit, global tmax) towards it (kd_ropes.cpp); clipped to its box, the segment is the one a
// restart from the root would bring there, so kd-ropes takes kd-restart's steps below it and
// visits the same leaves in the same order.
bool KdRestartTracer::walkPass(const geometry::Ray& ray, Segment global, PassState& pass, LeafVisitor& visitor,
                               geometry::TraversalCounters& c, int& steps) const {
    uint32_t node = 0;
    RestartPoint restart{.pushDown = from_ == RestartFrom::PushDown};
    Segment seg = global;
    for (;; ++steps) {
        if (steps >= maxSteps_) {
            ++c.capped;
            return false;
        }
        ++c.nodes;
        const gpu::KdNode& n = tree_.nodes[node];
        if (!n.isLeaf()) {
            const SplitStep s = stepInner(ray, n, node, seg, pass);
            node = descend(s, seg);  // the stack traversal's push, dropped
            restart.entered(s.visit, node);
            continue;
        }
        ++c.leaves;
        if (visitor.visit(n, seg.tmax) || pass.compare(seg.tmax, seg.maxAxis, global.tmax, global.maxAxis) >= 0)
            return true;
        if (from_ == RestartFrom::Rope) {  // before the global end: the exit is a face of the leaf (maxAxis < 3)
            const uint32_t rope = gpu::kdRope(tree_.ropes[node], 2 * seg.maxAxis + (ray.dir[seg.maxAxis] > 0.0 ? 1 : 0));
            if (rope == VKRAY_KD_NO_ROPE) return true;
            const gpu::KdRopeRecord& box = tree_.ropes[rope];
            if (ropeHoldsExit(seg, global.tmin)) {
                node = rope;
                seg = RestartPoint::rest(seg, global);
                std::tie(seg.tmax, seg.maxAxis) = exitFromBox(ray, box.lo, box.hi, seg, pass);
                continue;
            }
            // The ray leaves the leaf through an edge or corner in no length, where in this pass's
            // order of the tied planes it may not be inside the rope's node yet: it restarts from the
            // root, as kd-restart does.
        }
        node = restart.restart(seg, global);
        ++c.restarts;
    }
}


// Foley and Sugerman 4.2: after a leaf, backtrack() climbs the parent links, clipping the ray's
// remaining segment (tmin, global tmax) to each ancestor's box, and descends from the first
// ancestor the segment still passes through for a positive length (box exit > tmin: an ancestor
// whose box the ray leaves exactly at tmin holds nothing new). Climbing steps share the loop (and
// the cap) with descending steps.
bool KdBacktrackTracer::walkPass(const geometry::Ray& ray, Segment global, PassState& pass, LeafVisitor& visitor,
                                 geometry::TraversalCounters& c, int& steps) const {
    uint32_t node = 0;
    Segment seg = global;
    bool climbing = false;
    for (;; ++steps) {
        if (steps >= maxSteps_) {
            ++c.capped;
            return false;
        }
        ++c.nodes;
        if (climbing) {
            if (node == VKRAY_KD_NO_PARENT) return true;  // climbed past the root: nothing left
            const gpu::KdNodeExtra& e = tree_.extra[node];
            const auto [exit, exitAxis] = exitFromBox(ray, e.lo, e.hi, global, pass);
            if (pass.compare(exit, exitAxis, seg.tmin, seg.minAxis) > 0) {
                seg = {seg.tmin, exit, seg.minAxis, exitAxis};
                climbing = false;
            } else {
                node = e.parent;
            }
            continue;
        }
        const gpu::KdNode& n = tree_.nodes[node];
        if (!n.isLeaf()) {
            node = descend(stepInner(ray, n, node, seg, pass), seg);
            continue;
        }
        ++c.leaves;
        if (visitor.visit(n, seg.tmax) || pass.compare(seg.tmax, seg.maxAxis, global.tmax, global.maxAxis) >= 0)
            return true;
        seg.tmin = seg.tmax;
        seg.minAxis = seg.maxAxis;
        node = tree_.extra[node].parent;
        climbing = true;
        ++c.restarts;
    }
}

std::unique_ptr<KdTracer> makeKdTracer(kd::Traversal traversal, const KdTree& tree,
                                       std::vector<geometry::TriangleVertices> triangles, int maxSteps,
                                       int shortStack) {
    switch (traversal) {
    case kd::Traversal::Stack:
    case kd::Traversal::Packet: return std::make_unique<KdStackTracer>(tree, std::move(triangles), maxSteps, 0);
    case kd::Traversal::ShortStack:
        return std::make_unique<KdStackTracer>(tree, std::move(triangles), maxSteps,
                                               shortStack > 0 ? shortStack : VKRAY_KD_SHORT_STACK_SIZE);
    case kd::Traversal::Restart:
        return std::make_unique<KdRestartTracer>(tree, std::move(triangles), maxSteps, RestartFrom::Root);
    case kd::Traversal::PushDown:
        return std::make_unique<KdRestartTracer>(tree, std::move(triangles), maxSteps, RestartFrom::PushDown);
    case kd::Traversal::Ropes:
        if (tree.ropes.size() != tree.nodes.size()) throw std::logic_error("kd-ropes: the tree has no ropes (buildRopes)");
        return std::make_unique<KdRestartTracer>(tree, std::move(triangles), maxSteps, RestartFrom::Rope);
    case kd::Traversal::Backtrack:
        if (tree.extra.size() != tree.nodes.size())
            throw std::logic_error("kd-backtrack: the tree has no parent links (deriveNodeExtras)");
        return std::make_unique<KdBacktrackTracer>(tree, std::move(triangles), maxSteps);
    }
    return nullptr;
}

}  // namespace vkray::accel::kd
