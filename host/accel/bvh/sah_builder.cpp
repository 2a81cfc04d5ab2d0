#include "accel/bvh/sah_builder.h"

#include <algorithm>
#include <array>
#include <limits>
#include <numeric>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "core/fork_join.h"
#include "core/parallel_alloc.h"
#include "core/error.h"

namespace vkray::bvh {
namespace {

constexpr int kMaxBins = 64;
// Nodes at least this large bin in parallel and build their children as parallel tasks.
constexpr size_t kParallelNode = 4096;

struct Bin {
    Aabb box;
    uint32_t count = 0;
};

// Bins of all three axes for one node, plus the node's bounds.
struct Binning {
    std::array<std::array<Bin, kMaxBins>, 3> bins{};
    Aabb bounds;

    void merge(const Binning& o) {
        bounds.grow(o.bounds);
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < kMaxBins; ++b) {
                bins[a][b].box.grow(o.bins[a][b].box);
                bins[a][b].count += o.bins[a][b].count;
            }
    }
};

struct Split {
    int axis = -1;  // -1: no useful split (all centroids in one bin): split in the middle
    int bin = 0;    // primitives in bins [0, bin] go left
};

class SahBuilder {
public:
    SahBuilder(const PrimitiveSet& prims, const Config& config) : prims_(prims), config_(config) {
        if (config.sahBins < 2 || config.sahBins > kMaxBins)
            throw Error("binned SAH: bins must be in 2.." + std::to_string(kMaxBins));
    }

    BinaryTree build() {
        const size_t n = prims_.size();
        BinaryTree tree;
        tree.primitives = uint32_t(n);
        if (n == 0) return tree;
        resizeForOverwrite(order_, n);
        std::iota(order_.begin(), order_.end(), 0u);
        resizeForOverwrite(nodes_, 2 * n - 1);  // the ranges' ids cover [0, 2n - 1)
        tree.root = buildNode(0, n);
        tree.nodes = std::move(nodes_);
        return tree;
    }

private:
    // Builds the subtree of order_[begin, end) and returns its node id. Node ids come from the
    // ranges, not a shared counter: the subtree of [begin, end) owns ids [2 begin, 2 end - 1), a
    // leaf 2 begin, and an inner node split at mid the one id its halves leave, 2 mid - 1. So the
    // threads never contend for a counter's cache line (an atomic increment per node from every
    // thread at once bounces it between the cores), ids do not depend on the thread count, and a
    // subtree's nodes lie together.
    uint32_t buildNode(size_t begin, size_t end) {
        if (end - begin == 1) {
            const uint32_t id = uint32_t(2 * begin);
            BinaryNode& node = nodes_[id];
            node.box = prims_.boxes[order_[begin]];
            node.child[0] = order_[begin];
            node.child[1] = kPrimitive;
            return id;
        }
        const Aabb centroids = centroidBounds(begin, end);
        const Binning binning = binAll(begin, end, centroids);
        const Split split = cheapestSplit(binning);
        const size_t mid = split.axis < 0 ? begin + (end - begin) / 2 : partition(begin, end, centroids, split);
        const uint32_t id = uint32_t(2 * mid - 1);
        BinaryNode& node = nodes_[id];
        node.box = binning.bounds;
        forkJoin(end - begin >= kParallelNode, [&] { node.child[0] = buildNode(begin, mid); },
                 [&] { node.child[1] = buildNode(mid, end); });
        return id;
    }

    Aabb centroidBounds(size_t begin, size_t end) const {
        using Range = tbb::blocked_range<size_t>;
        return tbb::parallel_reduce(
            Range(begin, end, kParallelNode), Aabb{},
            [&](const Range& r, Aabb acc) {
                for (size_t i = r.begin(); i < r.end(); ++i) acc.grow(prims_.centroids[order_[i]]);
                return acc;
            },
            [](Aabb a, const Aabb& b) { return Aabb::merged(a, b); });
    }

    int binOf(const glm::vec3& c, const Aabb& centroids, int axis) const {
        const float extent = centroids.hi[axis] - centroids.lo[axis];
        if (!(extent > 0.0f)) return 0;
        const int b = int((c[axis] - centroids.lo[axis]) / extent * float(config_.sahBins));
        return std::clamp(b, 0, config_.sahBins - 1);
    }

    Binning binAll(size_t begin, size_t end, const Aabb& centroids) const {
        using Range = tbb::blocked_range<size_t>;
        return tbb::parallel_reduce(
            Range(begin, end, kParallelNode), Binning{},
            [&](const Range& r, Binning acc) {
                for (size_t i = r.begin(); i < r.end(); ++i) {
                    const uint32_t p = order_[i];
                    acc.bounds.grow(prims_.boxes[p]);
                    for (int a = 0; a < 3; ++a) {
                        Bin& bin = acc.bins[a][binOf(prims_.centroids[p], centroids, a)];
                        bin.box.grow(prims_.boxes[p]);
                        ++bin.count;
                    }
                }
                return acc;
            },
            [](Binning a, const Binning& b) {
                a.merge(b);
                return a;
            });
    }

    // The boundary with the least A(left) N(left) + A(right) N(right) over all axes (the constant
    // Ct and the division by the parent's area do not change which is least); ties to the lowest
    // axis, then the lowest bin.
    Split cheapestSplit(const Binning& binning) const {
        const int nb = config_.sahBins;
        Split best;
        double bestCost = std::numeric_limits<double>::infinity();
        for (int a = 0; a < 3; ++a) {
            const auto& bins = binning.bins[a];
            std::array<double, kMaxBins> rightCost{};
            std::array<uint32_t, kMaxBins> rightCount{};
            Aabb box;
            uint32_t count = 0;
            for (int b = nb - 1; b > 0; --b) {  // bins [b, nb) on the right
                box.grow(bins[b].box);
                count += bins[b].count;
                rightCost[b] = double(box.halfArea()) * count;
                rightCount[b] = count;
            }
            box = Aabb{};
            count = 0;
            for (int b = 0; b < nb - 1; ++b) {
                box.grow(bins[b].box);
                count += bins[b].count;
                if (count == 0 || rightCount[b + 1] == 0) continue;
                const double cost = double(box.halfArea()) * count + rightCost[b + 1];
                if (cost < bestCost) {
                    bestCost = cost;
                    best = Split{a, b};
                }
            }
        }
        return best;
    }

    size_t partition(size_t begin, size_t end, const Aabb& centroids, const Split& split) {
        const auto it = std::partition(order_.begin() + std::ptrdiff_t(begin), order_.begin() + std::ptrdiff_t(end),
                                       [&](uint32_t p) { return binOf(prims_.centroids[p], centroids, split.axis) <= split.bin; });
        return size_t(it - order_.begin());
    }

    const PrimitiveSet& prims_;
    const Config& config_;
    BuildArray<uint32_t> order_;  // primitive indices; each node owns a contiguous run
    BuildArray<BinaryNode> nodes_;
};

}  // namespace

BinaryTree buildBinnedSah(const PrimitiveSet& prims, const Config& config, PhaseLog& log) {
    return log.run("sah_split", 0.85, [&] { return SahBuilder(prims, config).build(); });
}

}  // namespace vkray::bvh
