#include "accel/bvh/bvh_tracer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace vkray::bvh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Relative widening of every slab interval (see the header).
constexpr double kSlabSlack = 1e-7;

struct StackEntry {
    uint32_t node;
    double tEnter;  // where the ray enters its box: skipped if a closer hit is found meanwhile
};

// Fixed storage for the usual tree depth, heap storage for degenerate deep trees.
class TraversalStack {
public:
    explicit TraversalStack(uint32_t capacity) {
        if (capacity > inline_.size()) {
            heap_.resize(capacity);
            data_ = heap_.data();
        }
    }
    void push(uint32_t node, double tEnter) { data_[size_++] = {node, tEnter}; }
    StackEntry pop() { return data_[--size_]; }
    bool empty() const { return size_ == 0; }

private:
    std::array<StackEntry, 64> inline_;
    std::vector<StackEntry> heap_;
    StackEntry* data_ = inline_.data();
    uint32_t size_ = 0;
};

}  // namespace

// Per-ray constants of the slab test.
struct BvhTracer::BoxRay {
    glm::dvec3 origin, inv;
    bool flat[3];  // direction component +-0 (or so small its inverse overflows)

    explicit BoxRay(const geometry::Ray& ray) : origin(ray.origin), dir(ray.dir) {
        for (int a = 0; a < 3; ++a) {
            inv[a] = 1.0 / ray.dir[a];
            flat[a] = std::isinf(inv[a]);
        }
    }

    glm::dvec3 dir;

    // Whether the ray meets the container of node i (its box, or its sphere when the tree has
    // spheres) within t in [0, limit]; tEnter = where it enters (widened).
    bool enters(const FlatBvh& bvh, uint32_t i, double limit, double& tEnter) const {
        return bvh.spheres.empty() ? entersBox(bvh.nodes[i], limit, tEnter) : entersSphere(bvh.spheres[i], limit, tEnter);
    }

    bool entersBox(const FlatNode& node, double limit, double& tEnter) const {
        const glm::dvec3 lo(node.lo), hi(node.hi);
        double tNear = -kInf, tFar = kInf;
        for (int a = 0; a < 3; ++a) {
            if (flat[a]) {
                // The ray stays in the plane x_a = origin_a: inside the slab for every t or for none.
                // Never computes (lo - o) * inf, which is NaN when the plane is a face of the box.
                if (origin[a] < lo[a] || origin[a] > hi[a]) return false;
                continue;
            }
            const double t0 = (lo[a] - origin[a]) * inv[a], t1 = (hi[a] - origin[a]) * inv[a];
            tNear = std::max(tNear, std::min(t0, t1));
            tFar = std::min(tFar, std::max(t0, t1));
        }
        return meets(tNear, tFar, limit, tEnter);
    }

    // The sphere test from the centre's squared distance to the ray's line (as the GPU kernel does,
    // bvh_common.glsl), the radius widened by kSlabSlack and by far more than the rounding of that
    // distance, the interval as the slab test widens it.
    bool entersSphere(const Sphere& sphere, double limit, double& tEnter) const {
        const glm::dvec3 oc = glm::dvec3(sphere.centre) - origin;
        const double a = glm::dot(dir, dir), tc = glm::dot(oc, dir) / a;
        const glm::dvec3 l = oc - tc * dir;
        const double radius = double(sphere.radius) * (1.0 + kSlabSlack) +
                              1e-12 * (std::abs(oc.x) + std::abs(oc.y) + std::abs(oc.z));
        const double h2 = radius * radius - glm::dot(l, l);
        if (h2 < 0.0) return false;
        const double half = std::sqrt(h2 / a);
        return meets(tc - half, tc + half, limit, tEnter);
    }

    // Whether the container's interval [tNear, tFar], widened by kSlabSlack, meets [0, limit].
    static bool meets(double tNear, double tFar, double limit, double& tEnter) {
        tNear -= kSlabSlack * std::abs(tNear);
        tFar += kSlabSlack * std::abs(tFar);
        tEnter = tNear;
        return tNear <= tFar && tFar >= 0.0 && tNear <= limit;
    }
};

BvhTracer::BvhTracer(const FlatBvh& bvh, std::span<const Triangle> triangles, bool stackless) : bvh_(bvh) {
    triangles_.reserve(bvh_.triangleOrder.size());
    for (uint32_t k : bvh_.triangleOrder) triangles_.push_back(triangles[k]);
    // Near-first traversal keeps at most one far child per level, plus the root.
    stackSize_ = bvh_.maxDepth + 2;
    if (!stackless) return;
    parents_.assign(bvh_.nodes.size(), kPrimitive);
    for (uint32_t i = 0; i < bvh_.nodes.size(); ++i)
        if (bvh_.nodes[i].count == 0) parents_[i + 1] = parents_[bvh_.nodes[i].rightOrFirst] = i;
}

// The children of `inner` in the walk's order: along the axis on which their boxes' centres lie
// furthest apart, the one on the side the ray comes from first (Hapala et al. order by the split
// axis; a BVH built by clustering has none, and this is its nearest equivalent).
BvhTracer::Order BvhTracer::order(uint32_t inner, const glm::dvec3& dir) const {
    const uint32_t left = inner + 1, right = bvh_.nodes[inner].rightOrFirst;
    const FlatNode &l = bvh_.nodes[left], &r = bvh_.nodes[right];
    const glm::vec3 gap = (r.lo + r.hi) - (l.lo + l.hi);
    const int axis = std::abs(gap.x) >= std::abs(gap.y) ? (std::abs(gap.x) >= std::abs(gap.z) ? 0 : 2)
                                                          : (std::abs(gap.y) >= std::abs(gap.z) ? 1 : 2);
    const bool leftFirst = (dir[axis] >= 0.0) == (gap[axis] >= 0.0f);
    return leftFirst ? Order{left, right} : Order{right, left};
}

// Hapala et al. 2011, section 3: from the parent, a node that is entered is descended into (its
// near child next) or, a leaf, tested; either way, once done, the walk moves to the far sibling
// (from the near one) or up (from the far one). Coming up from a child: from the near child on to
// its sibling, from the far one further up, until the root.
template <class Limit, class Leaf>
void BvhTracer::walkStackless(const BoxRay& boxRay, const glm::dvec3& dir, const Limit& limit, const Leaf& leaf,
                              geometry::TraversalCounters& work) const {
    enum class From { Parent, Sibling, Child };
    double tEnter = 0.0;
    ++work.nodes;
    if (!boxRay.enters(bvh_, 0, limit(), tEnter)) return;
    if (bvh_.nodes[0].count > 0) {
        ++work.leaves;
        leaf(0u);
        return;
    }
    uint32_t current = order(0, dir).nearChild;
    From state = From::Parent;
    for (;;) {
        ++work.nodes;
        if (state == From::Child) {
            if (current == 0) return;
            const uint32_t parent = parents_[current];
            const Order o = order(parent, dir);
            if (current == o.nearChild) {
                current = o.farChild;
                state = From::Sibling;
            } else {
                current = parent;
            }
            continue;
        }
        const FlatNode& node = bvh_.nodes[current];
        const bool entered = boxRay.enters(bvh_, current, limit(), tEnter);
        if (entered && node.count == 0) {
            current = order(current, dir).nearChild;
            state = From::Parent;
            continue;
        }
        if (entered) {
            ++work.leaves;
            if (leaf(current)) return;
        }
        if (state == From::Parent) {  // on to the far sibling
            current = order(parents_[current], dir).farChild;
            state = From::Sibling;
        } else {  // the far one done: back up
            current = parents_[current];
            state = From::Child;
        }
    }
}


geometry::Hit BvhTracer::closest(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters) const {
    geometry::Hit best;
    if (bvh_.nodes.empty()) return best;
    const BoxRay boxRay(ray);
    const geometry::WatertightRay wray(ray);
    geometry::TraversalCounters work;
    // Hits must be below tmax until one is found, then at most its t (a tie may still win).
    const auto limit = [&] { return best.found() ? best.t : tmax; };
    const auto testLeaf = [&](const FlatNode& node) {
        for (uint32_t k = node.rightOrFirst; k < node.rightOrFirst + node.count; ++k) {
            ++work.triangles;
            const double hi = best.found() ? std::nextafter(best.t, kInf) : tmax;
            const auto hit = wray.intersect(vertices(k), 0.0, hi);
            if (!hit) continue;
            if (!best.found() || hit->t < best.t || original(k) < best.triangle)
                best = geometry::Hit{original(k), hit->t, hit->b0, hit->b1, hit->b2};
        }
    };
    if (!parents_.empty()) {
        walkStackless(boxRay, ray.dir, limit, [&](uint32_t node) { testLeaf(bvh_.nodes[node]); return false; }, work);
        if (counters) *counters += work;
        return best;
    }
    TraversalStack stack(stackSize_);
    double tRoot = 0.0;
    if (boxRay.enters(bvh_, 0, tmax, tRoot)) stack.push(0, tRoot);
    while (!stack.empty()) {
        const StackEntry e = stack.pop();
        if (e.tEnter > limit()) continue;  // a closer hit was found after it was pushed
        const FlatNode& node = bvh_.nodes[e.node];
        ++work.nodes;
        if (node.count > 0) {
            ++work.leaves;
            testLeaf(node);
            continue;
        }
        const uint32_t left = e.node + 1, right = node.rightOrFirst;
        double tl = 0.0, tr = 0.0;
        const bool hitLeft = boxRay.enters(bvh_, left, limit(), tl);
        const bool hitRight = boxRay.enters(bvh_, right, limit(), tr);
        if (hitLeft && hitRight) {  // the nearer child is popped first
            if (tl <= tr) {
                stack.push(right, tr);
                stack.push(left, tl);
            } else {
                stack.push(left, tl);
                stack.push(right, tr);
            }
        } else if (hitLeft) {
            stack.push(left, tl);
        } else if (hitRight) {
            stack.push(right, tr);
        }
    }
    if (counters) *counters += work;
    return best;
}

bool BvhTracer::occluded(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters) const {
    if (bvh_.nodes.empty()) return false;
    const BoxRay boxRay(ray);
    const geometry::WatertightRay wray(ray);
    geometry::TraversalCounters work;
    bool hit = false;
    const auto testLeaf = [&](const FlatNode& node) {  // any hit ends the search: no ordering needed
        for (uint32_t k = node.rightOrFirst; k < node.rightOrFirst + node.count && !hit; ++k) {
            ++work.triangles;
            hit = wray.intersect(vertices(k), 0.0, tmax).has_value();
        }
        return hit;
    };
    if (!parents_.empty()) {
        walkStackless(boxRay, ray.dir, [tmax] { return tmax; }, [&](uint32_t node) { return testLeaf(bvh_.nodes[node]); },
                      work);
        if (counters) *counters += work;
        return hit;
    }
    TraversalStack stack(stackSize_);
    double tEnter = 0.0;
    if (boxRay.enters(bvh_, 0, tmax, tEnter)) stack.push(0, tEnter);
    while (!stack.empty() && !hit) {
        const uint32_t id = stack.pop().node;
        const FlatNode& node = bvh_.nodes[id];
        ++work.nodes;
        if (node.count > 0) {
            ++work.leaves;
            testLeaf(node);
            continue;
        }
        if (boxRay.enters(bvh_, node.rightOrFirst, tmax, tEnter)) stack.push(node.rightOrFirst, tEnter);
        if (boxRay.enters(bvh_, id + 1, tmax, tEnter)) stack.push(id + 1, tEnter);
    }
    if (counters) *counters += work;
    return hit;
}

}  // namespace vkray::bvh
