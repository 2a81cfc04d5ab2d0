#include "accel/bvh/aac_builder.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/fork_join.h"
#include "accel/bvh/morton.h"
#include "accel/bvh/sphere_bounds.h"
#include "core/parallel_alloc.h"
#include "core/error.h"

namespace vkray::bvh {
namespace {

// Ranges at least this large split their halves into parallel tasks; smaller ones recurse on the
// calling thread. A range of 1024 primitives is hundreds of times a task's overhead in clustering
// work, and a larger threshold leaves too few tasks to balance two threads on meshes of tens of
// thousands of triangles, whose Morton splits are uneven near the root.
constexpr size_t kParallelRange = 1024;

// Per-thread working arrays of CombineClusters, reused across calls (one call per range). The
// clusters' boxes are kept as six arrays of floats (structure of arrays), so that the distance
// search over all partners, the clustering's inner loop, runs as vector instructions.
struct ClusterScratch {
    std::vector<float> lox, loy, loz, hix, hiy, hiz;
    std::vector<float> cx, cy, cz, r;  // sphere containers: the clusters' spheres
    std::vector<float> merged;      // findBestMatch: area of the box merging cluster i with each j
    std::vector<uint32_t> closest;  // position of each cluster's closest partner
    std::vector<float> distance;    // area of the box merging it with that partner
    std::vector<float> own;         // its distance to itself (its container's area), from its last search
    std::vector<uint8_t> stale;     // closest partner merged away: search again

    // Room for `count` clusters; grows only (most calls are small ranges of delta primitives).
    void reserve(size_t count, bool spheres) {
        if (lox.size() < count)
            for (std::vector<float>* v : {&lox, &loy, &loz, &hix, &hiy, &hiz, &merged, &distance, &own})
                v->resize(count);
        if (spheres && cx.size() < count)
            for (std::vector<float>* v : {&cx, &cy, &cz, &r}) v->resize(count);
        if (closest.size() < count) closest.resize(count);
        if (stale.size() < count) stale.resize(count);
        std::fill_n(stale.begin(), count, uint8_t(0));
    }
    Aabb box(size_t i) const { return Aabb{{lox[i], loy[i], loz[i]}, {hix[i], hiy[i], hiz[i]}}; }
    void setBox(size_t i, const Aabb& b) {
        lox[i] = b.lo.x, loy[i] = b.lo.y, loz[i] = b.lo.z;
        hix[i] = b.hi.x, hiy[i] = b.hi.y, hiz[i] = b.hi.z;
    }
    Sphere sphere(size_t i) const { return Sphere{{cx[i], cy[i], cz[i]}, r[i]}; }
    void setSphere(size_t i, const Sphere& sp) { cx[i] = sp.centre.x, cy[i] = sp.centre.y, cz[i] = sp.centre.z, r[i] = sp.radius; }
    void move(size_t from, size_t to, bool spheres) {
        for (std::vector<float>* v : {&lox, &loy, &loz, &hix, &hiy, &hiz, &distance, &own}) (*v)[to] = (*v)[from];
        if (spheres)
            for (std::vector<float>* v : {&cx, &cy, &cz, &r}) (*v)[to] = (*v)[from];
        closest[to] = closest[from];
    }
};

// The two best clusters offered, in position order, by primitive count (the fewest, or with
// `largest` the most), the lower position first among equal counts.
struct TwoBest {
    static constexpr size_t kNone = std::numeric_limits<size_t>::max();
    bool largest;
    size_t first = kNone, second = kNone;
    uint32_t firstSize = 0, secondSize = 0;

    bool better(uint32_t x, uint32_t y) const { return largest ? x > y : x < y; }
    void offer(size_t i, uint32_t size) {
        if (first == kNone || better(size, firstSize)) {
            second = first, secondSize = firstSize, first = i, firstSize = size;
        } else if (second == kNone || better(size, secondSize)) {
            second = i, secondSize = size;
        }
    }
};

class AacBuilder {
public:
    AacBuilder(const PrimitiveSet& prims, const Config& config, BuildArray<MortonKey> sortedKeys,
               CollapsedTree* collapsed)
        : prims_(prims), config_(config), keys_(std::move(sortedKeys)), collapsed_(collapsed),
          spheres_(config.container == Config::Container::Sphere), reduce_(config.delta, config.epsilon),
          leafReduction_(reduce_(size_t(config.delta))) {}

    BinaryTree build() {
        const size_t n = keys_.size();
        BinaryTree tree;
        tree.primitives = uint32_t(n);
        if (n == 0) return tree;
        resizeForOverwrite(nodes_, 2 * n - 1);  // primitives, then the n - 1 merges fill every slot
        resizeFirstTouched(clusters_, n);
        resizeFirstTouched(free_, n);
        resizeForOverwrite(counts_, n - 1);
        if (spheres_) resizeFirstTouched(sphereOf_, 2 * n - 1);
        if (collapsed_) recorder_.emplace(config_, 2 * n - 1);
        makePrimitiveNodes();
        const size_t k = buildRange(0, n);
        combineClusters(0, k, 1);
        tree.root = clusters_[0];
        if (collapsed_) *collapsed_ = recorder_->finish(tree.root, area(tree.root));
        tree.nodes = std::move(nodes_);
        tree.spheres = std::move(sphereOf_);
        return tree;
    }

private:
    // Node i is the primitive at sorted position i.
    // The boxes are read in Morton order, scattered over the primitive array: each is asked for a
    // few iterations before it is needed, so the cache misses overlap.
    void makePrimitiveNodes() {
        constexpr size_t kAhead = 16;
        const size_t n = keys_.size();
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                if (i + kAhead < r.end()) __builtin_prefetch(&prims_.boxes[keyPrimitive(keys_[i + kAhead])]);
                const uint32_t prim = keyPrimitive(keys_[i]);
                nodes_[i].box = prims_.boxes[prim];
                nodes_[i].child[0] = prim;
                nodes_[i].child[1] = kPrimitive;
                if (recorder_ && !spheres_) recorder_->primitive(uint32_t(i), nodes_[i].box.halfArea());
            }
        });
        if (!spheres_) return;
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t i = r.begin(); i < r.end(); ++i) {
                sphereOf_[i] = prims_.spheres[nodes_[i].child[0]];
                if (recorder_) recorder_->primitive(uint32_t(i), sphereOf_[i].halfArea());
            }
        });
    }

    // Node slots. The range [begin, end) of n primitives owns the merge slots
    // [N + begin - 1, N + end - 1), or [N, N + end - 1) when begin = 0 (N = primitive count), so the
    // halves of a range own disjoint parts of its slots and the whole tree owns [N, 2N - 1). Its
    // subtree merges exactly n - k times (k = the clusters it returns), which its n (n - 1 at
    // begin = 0, where k >= 1) slots always hold. The slots a range leaves unused, k of them
    // (k - 1 at begin = 0), are listed at free_[begin, ...), parallel to its clusters; a combine
    // takes them in list order. So node ids depend only on the Morton order, never on the thread
    // count, and threads write nodes in disjoint regions of nodes_ without any shared counter.
    static size_t spare(size_t begin, size_t k) { return begin == 0 ? k - 1 : k; }

    // The paper's BuildTree on sorted positions [begin, end): leaves its clusters (node ids) in
    // clusters_[begin, begin + k), its unused slots in free_[begin, begin + spare(begin, k)), and
    // returns k.
    size_t buildRange(size_t begin, size_t end) {
        const size_t n = end - begin;
        if (n <= size_t(config_.delta)) {
            const size_t first = keys_.size() + begin - (begin == 0 ? 0 : 1);
            const size_t slots = begin == 0 ? n - 1 : n;
            for (size_t i = begin; i < end; ++i) clusters_[i] = uint32_t(i);
            for (size_t i = 0; i < slots; ++i) free_[begin + i] = uint32_t(first + i);
            return combineClusters(begin, n, leafReduction_);
        }
        const size_t mid = splitPoint(begin, end);
        size_t left = 0, right = 0;
        forkJoin(n >= kParallelRange, [&] { left = buildRange(begin, mid); }, [&] { right = buildRange(mid, end); });
        // Gather both halves' clusters and free slots into one run each (the destination never
        // overtakes the source).
        std::copy(clusters_.begin() + std::ptrdiff_t(mid), clusters_.begin() + std::ptrdiff_t(mid + right),
                  clusters_.begin() + std::ptrdiff_t(begin + left));
        std::copy(free_.begin() + std::ptrdiff_t(mid), free_.begin() + std::ptrdiff_t(mid + right),
                  free_.begin() + std::ptrdiff_t(begin + spare(begin, left)));
        return combineClusters(begin, left + right, reduce_(n));
    }

    // Where [begin, end) splits: the first position whose code has the highest differing bit set
    // (binary search), or the middle when all codes are equal.
    size_t splitPoint(size_t begin, size_t end) const {
        const uint32_t first = keyCode(keys_[begin]), last = keyCode(keys_[end - 1]);
        if (first == last) return begin + (end - begin) / 2;
        const uint32_t bit = 1u << (31 - std::countl_zero(first ^ last));
        const auto it = std::partition_point(keys_.begin() + std::ptrdiff_t(begin), keys_.begin() + std::ptrdiff_t(end),
                                             [bit](MortonKey k) { return (keyCode(k) & bit) == 0; });
        return size_t(it - keys_.begin());
    }

    // The paper's CombineClusters on clusters_[begin, begin + count): merges the closest pair until
    // `target` clusters remain, which it leaves at clusters_[begin, begin + target); the merges
    // take the first free slots of free_[begin, ...), the rest move to its front.
    // Spheres or boxes decided once per call, so the box clustering's loops carry no test of it.
    size_t combineClusters(size_t begin, size_t count, size_t target) {
        return spheres_ ? combine<true>(begin, count, target) : combine<false>(begin, count, target);
    }

    template <bool Spheres>
    size_t combine(size_t begin, size_t count, size_t target) {
        if (count <= target) return count;
        thread_local ClusterScratch s;
        std::span<uint32_t> ids(clusters_.data() + begin, count);
        uint32_t* slot = free_.data() + begin;
        s.reserve(count, Spheres);
        for (size_t i = 0; i < count; ++i) s.setBox(i, nodes_[ids[i]].box);
        if constexpr (Spheres)
            for (size_t i = 0; i < count; ++i) s.setSphere(i, sphereOf_[ids[i]]);
        for (size_t i = 0; i < count; ++i) findBestMatch<Spheres>(s, count, i);

        size_t k = count;
        while (k > target) {
            // The closest pair; ties go to the lowest position, so the choice is deterministic,
            // except for a pair of equal containers (equalContainerPair).
            size_t a = 0;
            for (size_t i = 1; i < k; ++i)
                if (s.distance[i] < s.distance[a]) a = i;
            size_t b = s.closest[a];
            if (s.distance[a] == s.own[a] && s.distance[a] == s.own[b])
                std::tie(a, b) = equalContainerPair<Spheres>(s, k, ids, a, b);
            const Aabb box = Aabb::merged(s.box(a), s.box(b));
            const uint32_t node = *slot++;
            nodes_[node].box = box;
            nodes_[node].child[0] = ids[a];
            nodes_[node].child[1] = ids[b];
            counts_[node - keys_.size()] = primitives(ids[a]) + primitives(ids[b]);
            if constexpr (Spheres) sphereOf_[node] = mergeSpheres(s.sphere(a), s.sphere(b));
            if (recorder_) recorder_->inner(node, Spheres ? sphereOf_[node].halfArea() : box.halfArea(), ids[a], ids[b]);

            // The merged cluster takes the lower position, the last cluster fills the higher one.
            const size_t lo = std::min(a, b), hi = std::max(a, b), last = k - 1;
            ids[lo] = node;
            s.setBox(lo, box);
            if constexpr (Spheres) s.setSphere(lo, sphereOf_[node]);
            if (hi != last) {
                ids[hi] = ids[last];
                s.move(last, hi, Spheres);
            }
            --k;
            if (k == target) break;  // no later merge reads the partners
            // Whoever was closest to a merged cluster searches again (merging only grows boxes, so
            // no other cluster can have become closer to the new one than to its cached partner).
            for (size_t i = 0; i < k; ++i) {
                if (i == lo || s.closest[i] == lo || s.closest[i] == hi) {
                    s.stale[i] = 1;
                } else if (s.closest[i] == last) {
                    s.closest[i] = uint32_t(hi);
                }
            }
            for (size_t i = 0; i < k; ++i)
                if (s.stale[i]) {
                    s.stale[i] = 0;
                    findBestMatch<Spheres>(s, k, i);
                }
        }
        // count - k merges took count - k slots; the spare(begin, k) left move to the front.
        std::copy(slot, slot + spare(begin, k), free_.data() + begin);
        return k;
    }

    // The pair to merge when the closest pair (a, b) is of equal containers (copies of a
    // triangle, an axis-aligned quad's two triangles), which Gu et al. 2013 leave to the order of
    // the search. Clusters of one container merge into that same container: every such merge adds
    // no area, so the paper's distance and the SAH price them alike, and by the lowest position
    // they would merge in a chain (each merged cluster, at the lower position, is again in the
    // closest pair), which the leaf collapse (leaf_collapse.h) leaves one copy a level. They differ
    // only in how the primitives are shared among subtrees, which the collapse prices: a subtree of
    // equal boxes costs its area once per primitive and once per inner node the collapse leaves,
    // one fewer than its leaves, so it is cheapest with full leaves. A merge of p + q <=
    // maxLeafSize primitives joins two leaves into one for nothing; a larger one closes each side
    // of fewer than maxLeafSize primitives as a leaf of its own, giving up its empty slots. So of
    // all clusters of that container, the pair merged is the one giving up the fewest slots, then
    // of fewest primitives (which keeps the subtree balanced), then of lowest positions; it is at
    // the same distance, so the clustering still merges in the paper's order of distances.
    template <bool Spheres>
    std::pair<size_t, size_t> equalContainerPair(ClusterScratch& s, size_t k, std::span<const uint32_t> ids, size_t a,
                                                 size_t b) const {
        const float own = s.own[a];
        // Every cluster of that container is at this distance from its partner: fewer than three
        // at it, and a and b are the only ones.
        size_t tied = 0;
        for (size_t i = 0; i < k; ++i) tied += s.distance[i] == own;
        if (tied < 3) return {a, b};
        mergedAreas<Spheres>(s, k, a);  // a's own included: its distance to itself
        // One pass over them, by (primitives, position): the two smallest, the two smallest of at
        // least maxLeafSize (full), the two largest below it (open).
        const uint32_t leaf = uint32_t(config_.maxLeafSize);
        TwoBest smallest{false}, fullSmallest{false}, openLargest{true};
        for (size_t i = 0; i < k; ++i) {
            if (s.merged[i] != own || s.own[i] != own) continue;
            const uint32_t size = primitives(ids[i]);
            smallest.offer(i, size);
            (size >= leaf ? fullSmallest : openLargest).offer(i, size);
        }
        if (smallest.firstSize + smallest.secondSize <= leaf) return {smallest.first, smallest.second};
        if (fullSmallest.second != TwoBest::kNone) return {fullSmallest.first, fullSmallest.second};
        if (fullSmallest.first != TwoBest::kNone) return {fullSmallest.first, openLargest.first};
        return {openLargest.first, openLargest.second};
    }

    // The primitives below node `id`.
    uint32_t primitives(uint32_t id) const {
        return id < keys_.size() ? 1 : counts_[id - keys_.size()];
    }

    // Half the surface area of node `id`'s container.
    double area(size_t id) const { return spheres_ ? sphereOf_[id].halfArea() : nodes_[id].box.halfArea(); }

    // The partner of cluster i among the first k whose merged container has the smallest area (the
    // paper's distance function d; Mahmuda 2017's "areaWithClosest", for boxes or spheres); ties
    // to the lowest position.
    template <bool Spheres>
    static void findBestMatch(ClusterScratch& s, size_t k, size_t i) {
        mergedAreas<Spheres>(s, k, i);
        float best = std::numeric_limits<float>::infinity();
        uint32_t partner = i == 0 ? 1u : 0u;
        float* __restrict area = s.merged.data();
        s.own[i] = area[i];
        area[i] = best;  // not its own partner
        for (size_t j = 0; j < k; ++j) {
            if (area[j] < best) {
                best = area[j];
                partner = uint32_t(j);
            }
        }
        s.closest[i] = partner;
        s.distance[i] = best;
    }

    // The distances from cluster i to each of the first k, into s.merged.
    template <bool Spheres>
    static void mergedAreas(ClusterScratch& s, size_t k, size_t i) {
        if constexpr (Spheres) {
            mergedSphereAreas(s, k, i);
        } else {
            mergedBoxAreas(s, k, i);
        }
    }

    // The areas of cluster i's box merged with every cluster's, in one loop without branches
    // (vectorised; the same operations, in the same order, as Aabb::merged(a, b).halfArea() of two
    // non-empty boxes).
    static void mergedBoxAreas(ClusterScratch& s, size_t k, size_t i) {
        const float lx = s.lox[i], ly = s.loy[i], lz = s.loz[i], hx = s.hix[i], hy = s.hiy[i], hz = s.hiz[i];
        const float* __restrict lox = s.lox.data();
        const float* __restrict loy = s.loy.data();
        const float* __restrict loz = s.loz.data();
        const float* __restrict hix = s.hix.data();
        const float* __restrict hiy = s.hiy.data();
        const float* __restrict hiz = s.hiz.data();
        float* __restrict area = s.merged.data();
        for (size_t j = 0; j < k; ++j) {
            const float dx = std::max(hx, hix[j]) - std::min(lx, lox[j]);
            const float dy = std::max(hy, hiy[j]) - std::min(ly, loy[j]);
            const float dz = std::max(hz, hiz[j]) - std::min(lz, loz[j]);
            area[j] = dx * dy + dy * dz + dz * dx;
        }
    }

    // The same for spheres: the radius of the sphere merging i's with each (mergedRadius), squared
    // (the area's constant factor orders nothing).
    static void mergedSphereAreas(ClusterScratch& s, size_t k, size_t i) {
        const float x = s.cx[i], y = s.cy[i], z = s.cz[i], ri = s.r[i];
        const float* __restrict cx = s.cx.data();
        const float* __restrict cy = s.cy.data();
        const float* __restrict cz = s.cz.data();
        const float* __restrict r = s.r.data();
        float* __restrict area = s.merged.data();
        for (size_t j = 0; j < k; ++j) {
            const float m = mergedRadius(x, y, z, ri, cx[j], cy[j], cz[j], r[j]);
            area[j] = m * m;
        }
    }

    const PrimitiveSet& prims_;
    const Config& config_;
    BuildArray<MortonKey> keys_;       // sorted by code
    CollapsedTree* collapsed_;         // where the recorded collapse goes, if asked for
    std::optional<CollapseRecorder> recorder_;
    BuildArray<BinaryNode> nodes_;    // primitives at [0, n), then merges in the slots of their ranges
    BuildArray<uint32_t> clusters_;   // per range, its current clusters (node ids)
    BuildArray<uint32_t> free_;       // per range, its unused merge slots
    BuildArray<uint32_t> counts_;     // per merge node (id - N), the primitives below it
    bool spheres_;                     // sphere containers: every node's sphere in sphereOf_
    std::vector<Sphere> sphereOf_;
    AacReduction reduce_;              // f
    size_t leafReduction_;             // f(delta), computed once: every range of at most delta primitives asks for it
};

// Morton codes cannot order primitives whose centroids share a cell: a run of equal codes longer
// than delta is split by the downward phase in the middle of its order (Gu et al. 2013, section
// 4.1, splits only by the codes' bits), so in primitive order its halves are arbitrary mixes, and
// a burst of triangles around one centre clusters the large with the small. Such runs are ordered
// by box surface area instead (then by primitive index): the middle split becomes a median split
// by size, which keeps small boxes in subtrees of small boxes, as a binned-SAH build over the
// boxes' extents would. Only runs longer than kLongTiedRun (and than delta) are reordered: at 2^30
// cells a dense mesh puts a few centroids in a cell, a run the clustering of its leaf range
// handles whatever its order, and its tree stays the paper's; a run of hundreds is a burst.
constexpr size_t kLongTiedRun = 256;

void orderTiedRuns(BuildArray<MortonKey>& keys, const PrimitiveSet& prims, size_t delta) {
    const size_t n = keys.size();
    for (size_t begin = 0; begin < n;) {
        size_t end = begin + 1;
        while (end < n && keyCode(keys[end]) == keyCode(keys[begin])) ++end;
        if (end - begin > std::max(delta, kLongTiedRun))
            std::sort(keys.begin() + std::ptrdiff_t(begin), keys.begin() + std::ptrdiff_t(end), [&](MortonKey a, MortonKey b) {
                const float areaA = prims.boxes[keyPrimitive(a)].halfArea(), areaB = prims.boxes[keyPrimitive(b)].halfArea();
                return areaA != areaB ? areaA < areaB : keyPrimitive(a) < keyPrimitive(b);
            });
        begin = end;
    }
}

}  // namespace

AacReduction::AacReduction(int delta, double epsilon)
    : c(std::pow(double(delta), 0.5 + epsilon) / 2.0), alpha(0.5 - epsilon) {
    constexpr size_t kSmall = 4096;
    small_.resize(kSmall);
    for (size_t n = 0; n < kSmall; ++n) small_[n] = uint32_t(compute(n));
}

size_t AacReduction::compute(size_t n) const {
    // The tiny slack keeps f(delta) = delta / 2 exact despite pow's rounding.
    const double f = std::floor(c * std::pow(double(n), alpha) + 1e-9);
    return f < 1.0 ? 1 : size_t(f);
}

size_t aacReduction(size_t n, int delta, double epsilon) { return AacReduction(delta, epsilon)(n); }

void validateAacConfig(const Config& config) {
    if (config.delta < 1)
        throw Error("AAC delta must be at least 1 (got " + std::to_string(config.delta) + ")");
    if (!(config.epsilon >= 0.0 && config.epsilon < 0.5))
        throw Error("AAC epsilon must be in [0, 0.5) (got " + std::to_string(config.epsilon) + ")");
}

BinaryTree buildAac(const PrimitiveSet& prims, const Config& config, PhaseLog& log, CollapsedTree* collapsed) {
    validateAacConfig(config);
    BuildArray<MortonKey> keys = log.run("morton", 0.1, [&] { return mortonKeys(prims.centroids, prims.centroidBounds); });
    log.run("sort", 0.2, [&] {
        radixSortByCode(keys);
        orderTiedRuns(keys, prims, size_t(config.delta));
    });
    return log.run("cluster", 0.85, [&] { return AacBuilder(prims, config, std::move(keys), collapsed).build(); });
}

}  // namespace vkray::bvh
