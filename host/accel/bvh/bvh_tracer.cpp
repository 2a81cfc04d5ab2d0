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

    explicit BoxRay(const geometry::Ray& ray) : origin(ray.origin) {
        for (int a = 0; a < 3; ++a) {
            inv[a] = 1.0 / ray.dir[a];
            flat[a] = std::isinf(inv[a]);
        }
    }

    // Whether the ray meets the box within t in [0, limit]; tEnter = where it enters (widened).
    bool enters(const FlatNode& node, double limit, double& tEnter) const {
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
        tNear -= kSlabSlack * std::abs(tNear);
        tFar += kSlabSlack * std::abs(tFar);
        tEnter = tNear;
        return tNear <= tFar && tFar >= 0.0 && tNear <= limit;
    }
};

BvhTracer::BvhTracer(const FlatBvh& bvh, std::span<const Triangle> triangles) : bvh_(bvh) {
    triangles_.reserve(bvh_.triangleOrder.size());
    for (uint32_t k : bvh_.triangleOrder) triangles_.push_back(triangles[k]);
    // Near-first traversal keeps at most one far child per level, plus the root.
    stackSize_ = bvh_.maxDepth + 2;
}

geometry::Hit BvhTracer::closest(const geometry::Ray& ray, double tmax, geometry::TraversalCounters* counters) const {
    geometry::Hit best;
    if (bvh_.nodes.empty()) return best;
    const BoxRay boxRay(ray);
    const geometry::WatertightRay wray(ray);
    geometry::TraversalCounters work;
    // Hits must be below tmax until one is found, then at most its t (a tie may still win).
    const auto limit = [&] { return best.found() ? best.t : tmax; };

    TraversalStack stack(stackSize_);
    double tRoot = 0.0;
    if (boxRay.enters(bvh_.nodes[0], tmax, tRoot)) stack.push(0, tRoot);
    while (!stack.empty()) {
        const StackEntry e = stack.pop();
        if (e.tEnter > limit()) continue;  // a closer hit was found after it was pushed
        const FlatNode& node = bvh_.nodes[e.node];
        ++work.nodes;
        if (node.count > 0) {
            ++work.leaves;
            for (uint32_t k = node.rightOrFirst; k < node.rightOrFirst + node.count; ++k) {
                ++work.triangles;
                const double hi = best.found() ? std::nextafter(best.t, kInf) : tmax;
                const auto hit = wray.intersect(vertices(k), 0.0, hi);
                if (!hit) continue;
                if (!best.found() || hit->t < best.t || original(k) < best.triangle)
                    best = geometry::Hit{original(k), hit->t, hit->b0, hit->b1, hit->b2};
            }
            continue;
        }
        const uint32_t left = e.node + 1, right = node.rightOrFirst;
        double tl = 0.0, tr = 0.0;
        const bool hitLeft = boxRay.enters(bvh_.nodes[left], limit(), tl);
        const bool hitRight = boxRay.enters(bvh_.nodes[right], limit(), tr);
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
    TraversalStack stack(stackSize_);
    double tEnter = 0.0;
    if (boxRay.enters(bvh_.nodes[0], tmax, tEnter)) stack.push(0, tEnter);
    while (!stack.empty() && !hit) {
        const uint32_t id = stack.pop().node;
        const FlatNode& node = bvh_.nodes[id];
        ++work.nodes;
        if (node.count > 0) {  // any hit ends the search: no ordering needed
            ++work.leaves;
            for (uint32_t k = node.rightOrFirst; k < node.rightOrFirst + node.count && !hit; ++k) {
                ++work.triangles;
                hit = wray.intersect(vertices(k), 0.0, tmax).has_value();
            }
            continue;
        }
        if (boxRay.enters(bvh_.nodes[node.rightOrFirst], tmax, tEnter)) stack.push(node.rightOrFirst, tEnter);
        if (boxRay.enters(bvh_.nodes[id + 1], tmax, tEnter)) stack.push(id + 1, tEnter);
    }
    if (counters) *counters += work;
    return hit;
}

}  // namespace vkray::bvh
