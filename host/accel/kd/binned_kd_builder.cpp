#include "accel/kd/binned_kd_builder.h"

#include <algorithm>
#include <cstdlib>
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/scalable_allocator.h>
#include <tbb/task_arena.h>

#include "accel/kd/kd_build_tree.h"
#include "accel/kd/kd_clip.h"
#include "accel/kd/kd_cost.h"
#include "accel/kd/kd_events.h"
#include "accel/kd/kd_split.h"
#include "core/error.h"
#include "core/fork_join.h"
#include "core/timing.h"
#include "core/worker_arena.h"

namespace vkray::accel::kd {
namespace {

// Nodes with at least this many references bin and split them in parallel chunks of kChunkRefs.
constexpr size_t kParallelRefs = size_t(1) << 15;
constexpr size_t kChunkRefs = size_t(1) << 13;
// Nodes of at most this many references are split exactly: their few events sort and sweep in less
// time than the bins take to clear and sweep.
static const size_t kExactRefs = getenv("XR") ? size_t(atoi(getenv("XR"))) : 64;

// A triangle's reference in a node: the bounds of its part inside the node.
struct Ref {
    Box box;
    uint32_t triangle;
};
using RefList = std::vector<Ref, tbb::scalable_allocator<Ref>>;
using RefSpan = std::span<const Ref>;

// One axis of a node cut into `bins` equal bins: the planes between them, 1 .. bins - 1, are the
// candidates, and a bound goes to the bin its distance from the node's low face, over the bins'
// width, falls in (min-max binning, Shevtsov et al. 2007). The bin is not checked against the
// plane's float, so a bound within rounding of a plane may be counted on its other side: the
// counts, and so the SAH, are estimates; the split's classification compares against the plane
// itself (sideOf), and the children are sized by it.
class AxisBins {
public:
    void set(float lo, float hi, int bins) {
        bins_ = bins;
        lo_ = lo;
        p_.resize(size_t(bins));
        const double step = (double(hi) - double(lo)) / bins;
        for (int b = 1; b < bins; ++b) p_[size_t(b)] = float(double(lo) + step * b);
        inv_ = step > 0.0 ? float(1.0 / step) : 0.0f;
    }
    int binOf(float x) const {
        const float g = (x - lo_) * inv_;  // NaN (0 times an infinite inverse) goes to bin 0
        return g >= float(bins_ - 1) ? bins_ - 1 : g > 0.0f ? int(g) : 0;
    }
    float plane(int b) const { return p_[size_t(b)]; }

private:
    std::vector<float> p_;
    float lo_ = 0.0f, inv_ = 0.0f;
    int bins_ = 1;
};
using NodeBins = std::array<AxisBins, 3>;

// A node's counts, axis k's at k * bins: starts[c], the references whose low bound lies in bin c;
// ends[d], those whose high bound lies in bin d. Plane b then has about the starts of the bins
// before it below it, and all but the ends of the bins before it above it. `content`: the
// references' bounds together.
struct Counts {
    std::vector<int32_t> starts, ends;
    Box content{glm::vec3(std::numeric_limits<float>::max()), glm::vec3(std::numeric_limits<float>::lowest())};

    void reset(int bins) {
        starts.assign(3 * size_t(bins), 0);
        ends.assign(3 * size_t(bins), 0);
        content = Counts{}.content;
    }
    void add(const Counts& o) {
        for (size_t i = 0; i < starts.size(); ++i) {
            starts[i] += o.starts[i];
            ends[i] += o.ends[i];
        }
        content = Box{glm::min(content.lo, o.content.lo), glm::max(content.hi, o.content.hi)};
    }
    void count(RefSpan refs, const NodeBins& axes, int bins) {
        for (const Ref& r : refs) {
            content = Box{glm::min(content.lo, r.box.lo), glm::max(content.hi, r.box.hi)};
            for (int k = 0; k < 3; ++k) {
                const size_t at = size_t(k) * size_t(bins);
                ++starts[at + size_t(axes[size_t(k)].binOf(r.box.lo[k]))];
                ++ends[at + size_t(axes[size_t(k)].binOf(r.box.hi[k]))];
            }
        }
    }
};

enum class Side : uint8_t { Below, Above, Both };

// sah_kd_builder.h's classification: ending at or before the plane = below only, starting at or
// after it = above only, flat in it = where the split puts planar triangles, else both.
Side sideOf(const Box& b, const SplitChoice& s) {
    const float lo = b.lo[s.axis], hi = b.hi[s.axis];
    if (lo == hi && lo == s.pos) return s.planarBelow ? Side::Below : Side::Above;
    if (hi <= s.pos) return Side::Below;
    if (lo >= s.pos) return Side::Above;
    return Side::Both;
}

enum Phase : size_t { kBin, kSplitRefs, kClip, kLeaves, kSmall, kPhaseCount };

// What one worker reuses from node to node. A small subtree's references live on `stack`, each
// node's children's above its own (buildFlat).
struct Worker {
    NodeBins axes;
    int binsUsed = 0;
    Counts counts;
    std::vector<Counts> chunkCounts;
    NodeEvents events;  // a small node's (exactSplit)
    RefList stack;
    size_t top = 0;
    FlatSubtree flat;
    TriangleList flatIndices;
    std::array<uint64_t, kPhaseCount> ticks{};
    bool inSmallSubtree = false;  // timed as a whole (kSmall): its phases are not
    uint64_t doneWeight = 0;      // SplitProgress
};

// The references each child of a split gets, straddlers on both sides.
struct Sides {
    size_t below = 0, above = 0;
};

Sides countSides(RefSpan refs, const SplitChoice& s) {
    Sides n;
    for (const Ref& r : refs) {
        const Side side = sideOf(r.box, s);
        n.below += side != Side::Above;
        n.above += side != Side::Below;
    }
    return n;
}

class Builder {
public:
    Builder(const std::vector<Triangle>& tris, const KdConfig& config, int maxDepth, const BuildProgress& progress)
        : tris_(tris), config_(config), maxDepth_(maxDepth), progress_(progress) {}

    NodePtr build(RefList refs, const Box& box, int depth, double budget);
    void finishProgress() {
        for (Worker& w : workers_)
            if (w.doneWeight > 0) progress_.add(w.doneWeight);
    }
    std::array<uint64_t, kPhaseCount> phaseTicks() const {
        std::array<uint64_t, kPhaseCount> sum{};
        for (const Worker& w : workers_)
            for (size_t p = 0; p < kPhaseCount; ++p) sum[p] += w.ticks[p];
        return sum;
    }

private:
    // The node's split, or none (no axis) where a leaf is cheaper or the reference budget forbids
    // every candidate; `sides` gets its children's sizes.
    SplitChoice chooseSplit(Worker& w, RefSpan refs, const Box& box, int depth, double budget, Sides& sides);
    SplitChoice findSplit(Worker& w, RefSpan refs, const Box& box, double budget, bool parallel);
    SplitChoice exactSplit(Worker& w, RefSpan refs, const Box& box, double invArea, double budget) const;
    void sweepAxis(int k, const Worker& w, const Box& box, double invArea, int64_t n, double budget,
                   SplitChoice& best) const;
    // Writes `in`'s references to `below` and `above` in order, the straddlers clipped to each
    // child; the clipping's ticks added to *clipTicks unless it is null.
    void splitRefs(RefSpan in, const SplitChoice& s, const Box& belowBox, const Box& aboveBox, Ref* below, Ref* above,
                   uint64_t* clipTicks) const;
    void splitBig(Worker& w, RefSpan in, const SplitChoice& s, const Box& belowBox, const Box& aboveBox,
                  RefList& below, RefList& above);
    NodePtr makeLeaf(Worker& w, const RefList& refs, int depth);
    NodePtr buildSmall(Worker& w, const RefList& refs, const Box& box, int depth, double budget);
    void buildFlat(Worker& w, size_t at, size_t n, const Box& box, int depth, double budget);
    void lap(Worker& w, Phase phase, uint64_t start) const {
        if (!w.inSmallSubtree) w.ticks[phase] += ticks() - start;
    }
    static uint64_t start(const Worker& w) { return w.inSmallSubtree ? 0 : ticks(); }

    const std::vector<Triangle>& tris_;
    KdConfig config_;
    int maxDepth_;
    tbb::enumerable_thread_specific<Worker, tbb::cache_aligned_allocator<Worker>, tbb::ets_key_per_instance> workers_;
    SplitProgress progress_;
};

// Candidates in a fixed order (axes 0-2; on each the cut below the content, the planes upwards,
// the cut above it) taken by strict comparison, so ties go the same way every time. The cuts at
// the content's bounds are counted exactly: nothing lies below the lower (triangles flat in it go
// above), nothing above the upper.
void Builder::sweepAxis(int k, const Worker& w, const Box& box, double invArea, int64_t n, double budget,
                        SplitChoice& best) const {
    const AxisCost cost(box, k, invArea, config_);
    const auto consider = [&](float pos, int64_t below, int64_t above, bool planarBelow) {
        if (!usableSplit(box, k, pos) || double(below + above) > budget + 0.5) return;
        const double c = cost(pos, below, above);
        if (c < best.cost) best = SplitChoice{k, pos, planarBelow, c, size_t(below), size_t(above)};
    };
    const Counts& counts = w.counts;
    const size_t at = size_t(k) * size_t(w.binsUsed);
    consider(counts.content.lo[k], 0, n, false);
    int64_t started = 0, ended = 0;
    for (int b = 1; b < w.binsUsed; ++b) {
        started += counts.starts[at + size_t(b) - 1];
        ended += counts.ends[at + size_t(b) - 1];
        consider(w.axes[size_t(k)].plane(b), started, n - ended, true);
    }
    consider(counts.content.hi[k], n, 0, true);
}

// A small node's best split among all its triangles' bounds, as sah_kd_builder.h finds it: its
// events sorted on each axis and swept.
SplitChoice Builder::exactSplit(Worker& w, RefSpan refs, const Box& box, double invArea, double budget) const {
    for (AxisEvents& e : w.events) e.clear();
    for (const Ref& r : refs) appendEvents(r.triangle, r.box, w.events);
    SplitChoice best;
    for (int k = 0; k < 3; ++k) {
        std::sort(w.events[size_t(k)].begin(), w.events[size_t(k)].end());
        sweepEvents(k, w.events[size_t(k)], box, invArea, refs.size(), budget, config_, best);
    }
    return best;
}

// A big node's chunks are counted as parallel tasks, isolated: this worker runs no other node's
// task, which would overwrite its bins and counts, until they are done.
SplitChoice Builder::findSplit(Worker& w, RefSpan refs, const Box& box, double budget, bool parallel) {
    const double area = box.surfaceArea();
    if (!(area > 0.0) || refs.empty()) return {};
    const uint64_t t = start(w);
    if (refs.size() <= kExactRefs) {
        const SplitChoice best = exactSplit(w, refs, box, 1.0 / area, budget);
        lap(w, kBin, t);
        return best;
    }
    static const int kDiv = getenv("AD") ? atoi(getenv("AD")) : 0;
    const int bins = kDiv ? std::clamp(int(refs.size()) / kDiv, 4, config_.bins) : config_.bins;
    w.binsUsed = bins;
    for (int k = 0; k < 3; ++k) w.axes[size_t(k)].set(box.lo[k], box.hi[k], bins);
    w.counts.reset(bins);
    if (!parallel) {
        w.counts.count(refs, w.axes, bins);
    } else {
        const size_t chunks = (refs.size() + kChunkRefs - 1) / kChunkRefs;
        w.chunkCounts.resize(chunks);
        tbb::this_task_arena::isolate([&] {
            tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
                w.chunkCounts[c].reset(bins);
                w.chunkCounts[c].count(refs.subspan(c * kChunkRefs, std::min(kChunkRefs, refs.size() - c * kChunkRefs)),
                                       w.axes, bins);
            });
        });
        for (size_t c = 0; c < chunks; ++c) w.counts.add(w.chunkCounts[c]);
    }
    SplitChoice best;
    for (int k = 0; k < 3; ++k) sweepAxis(k, w, box, 1.0 / area, int64_t(refs.size()), budget, best);
    lap(w, kBin, t);
    return best;
}

// SAH termination (Wald and Havran 2006, section 3): split only when it is cheaper than a leaf. The
// binned counts are estimates, so the budget is checked again on the split's true sizes.
SplitChoice Builder::chooseSplit(Worker& w, RefSpan refs, const Box& box, int depth, double budget, Sides& sides) {
    if (depth >= maxDepth_) return {};
    const bool parallel = refs.size() >= kParallelRefs;
    const SplitChoice s = findSplit(w, refs, box, budget, parallel);
    if (s.axis < 0 || s.cost >= config_.intersectionCost * double(refs.size())) return {};
    if (refs.size() <= kExactRefs) {
        sides = Sides{s.below, s.above};
    } else {
        const uint64_t t = start(w);
        if (!parallel) {
            sides = countSides(refs, s);
        } else {
            const size_t chunks = (refs.size() + kChunkRefs - 1) / kChunkRefs;
            std::vector<Sides> part(chunks);
            tbb::this_task_arena::isolate([&] {
                tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
                    part[c] = countSides(refs.subspan(c * kChunkRefs, std::min(kChunkRefs, refs.size() - c * kChunkRefs)), s);
                });
            });
            sides = {};
            for (const Sides& p : part) sides = Sides{sides.below + p.below, sides.above + p.above};
        }
        lap(w, kSplitRefs, t);
    }
    if (double(sides.below + sides.above) > budget + 0.5) return {};
    return s;
}

void Builder::splitRefs(RefSpan in, const SplitChoice& s, const Box& belowBox, const Box& aboveBox, Ref* below,
                        Ref* above, uint64_t* clipTicks) const {
    for (const Ref& r : in) {
        switch (sideOf(r.box, s)) {
        case Side::Below: *below++ = r; break;
        case Side::Above: *above++ = r; break;
        case Side::Both: {
            const uint64_t t = clipTicks ? ticks() : 0;
            const auto [inBelow, inAbove] = clippedBoundsOfSplit(tris_[r.triangle], belowBox, aboveBox, s.axis);
            if (clipTicks) *clipTicks += ticks() - t;
            *below++ = Ref{inBelow, r.triangle};
            *above++ = Ref{inAbove, r.triangle};
            break;
        }
        }
    }
}

// In parallel chunks, each writing its references at the place its predecessors' counts give
// (below and above are sized already).
void Builder::splitBig(Worker& w, RefSpan in, const SplitChoice& s, const Box& belowBox, const Box& aboveBox,
                       RefList& below, RefList& above) {
    const uint64_t t = ticks();
    const size_t chunks = (in.size() + kChunkRefs - 1) / kChunkRefs;
    const auto chunk = [&](size_t c) { return in.subspan(c * kChunkRefs, std::min(kChunkRefs, in.size() - c * kChunkRefs)); };
    std::vector<Sides> first(chunks + 1);
    uint64_t clip = 0;
    tbb::this_task_arena::isolate([&] {
        tbb::parallel_for(size_t(0), chunks, [&](size_t c) { first[c + 1] = countSides(chunk(c), s); });
        for (size_t c = 0; c < chunks; ++c)
            first[c + 1] = Sides{first[c + 1].below + first[c].below, first[c + 1].above + first[c].above};
        tbb::enumerable_thread_specific<uint64_t> clipTicks(0);
        tbb::parallel_for(size_t(0), chunks, [&](size_t c) {
            splitRefs(chunk(c), s, belowBox, aboveBox, below.data() + first[c].below, above.data() + first[c].above,
                      &clipTicks.local());
        });
        clip = clipTicks.combine([](uint64_t a, uint64_t b) { return a + b; });
    });
    const uint64_t spent = ticks() - t;
    w.ticks[kClip] += clip;
    w.ticks[kSplitRefs] += spent - std::min(spent, clip);  // the workers' clipping may exceed the wall's ticks
}

NodePtr Builder::makeLeaf(Worker& w, const RefList& refs, int depth) {
    const uint64_t t = ticks();
    progress_.leaf(w.doneWeight, depth);
    if (refs.empty()) return NodePtr(&kEmptyLeaf);
    NodePtr leaf(new BuildNode);
    leaf->triangles.reserve(refs.size());
    for (const Ref& r : refs) leaf->triangles.push_back(r.triangle);  // ascending: splits keep the order
    leaf->subtreeRefs = leaf->triangles.size();
    w.ticks[kLeaves] += ticks() - t;
    return leaf;
}

NodePtr Builder::buildSmall(Worker& w, const RefList& refs, const Box& box, int depth, double budget) {
    const uint64_t t = ticks();
    w.inSmallSubtree = true;
    w.flat.clear();
    w.flatIndices.clear();
    if (w.stack.size() < refs.size()) w.stack.resize(refs.size());
    std::copy(refs.begin(), refs.end(), w.stack.begin());
    w.top = refs.size();
    buildFlat(w, 0, refs.size(), box, depth, budget);
    w.inSmallSubtree = false;
    w.ticks[kSmall] += ticks() - t;
    return nodeOfFlat(w.flat, w.flatIndices);
}

// build() below kSmallSubtreeRefs, with the same choices, written as flattenKdTree would write
// them; the node's references are stack[at, at + n).
void Builder::buildFlat(Worker& w, size_t at, size_t n, const Box& box, int depth, double budget) {
    const auto index = uint32_t(w.flat.size());
    w.flat.emplace_back();
    Sides sides;
    const SplitChoice s = chooseSplit(w, RefSpan(w.stack.data() + at, n), box, depth, budget, sides);
    if (s.axis < 0) {
        const auto first = uint32_t(w.flatIndices.size());
        for (size_t i = at; i < at + n; ++i) w.flatIndices.push_back(w.stack[i].triangle);
        w.flat[index] = gpu::KdNode::leaf(first, uint32_t(n));
        progress_.leaf(w.doneWeight, depth);
        return;
    }
    const auto [belowBox, aboveBox] = splitBox(box, s.axis, s.pos);
    const size_t top = w.top;
    size_t belowAt = at, aboveAt = at;  // empty space cut off: the other side's references are the node's
    if (sides.below > 0 && sides.above > 0) {
        belowAt = top;
        aboveAt = top + sides.below;
        w.top = aboveAt + sides.above;
        if (w.stack.size() < w.top) w.stack.resize(std::max(w.top, 2 * w.stack.size()));
        Ref* const stack = w.stack.data();
        splitRefs(RefSpan(stack + at, n), s, belowBox, aboveBox, stack + belowAt, stack + aboveAt, nullptr);
    }
    const double share = budget / double(sides.below + sides.above);
    buildFlat(w, belowAt, sides.below, belowBox, depth + 1, share * double(sides.below));
    const auto aboveIndex = uint32_t(w.flat.size());
    buildFlat(w, aboveAt, sides.above, aboveBox, depth + 1, share * double(sides.above));
    w.top = top;
    setFlatInner(w.flat, index, s.axis, s.pos, aboveIndex);
}

// `budget`: as in sah_kd_builder.cpp, the most references the subtree's leaves may hold, handed to
// the children in proportion to their counts.
NodePtr Builder::build(RefList refs, const Box& box, int depth, double budget) {
    Worker& w = workers_.local();
    if (refs.size() < kSmallSubtreeRefs) return buildSmall(w, refs, box, depth, budget);
    Sides sides;
    const SplitChoice s = chooseSplit(w, refs, box, depth, budget, sides);
    if (s.axis < 0) return makeLeaf(w, refs, depth);

    NodePtr node(new BuildNode);
    node->axis = s.axis;
    node->split = s.pos;
    const auto [belowBox, aboveBox] = splitBox(box, s.axis, s.pos);
    RefList below, above;
    if (sides.below == 0 || sides.above == 0) {
        (sides.above == 0 ? below : above) = std::move(refs);
    } else {
        below.resize(sides.below);
        above.resize(sides.above);
        splitBig(w, refs, s, belowBox, aboveBox, below, above);
        RefList().swap(refs);  // freed before the children grow theirs
    }
    const double share = budget / double(sides.below + sides.above);
    forkJoin(
        true,
        [&, &b = below, &bBox = belowBox] { node->below = build(std::move(b), bBox, depth + 1, share * double(sides.below)); },
        [&, &a = above, &aBox = aboveBox] { node->above = build(std::move(a), aBox, depth + 1, share * double(sides.above)); });
    node->subtreeNodes = 1 + node->below->subtreeNodes + node->above->subtreeNodes;
    node->subtreeRefs = node->below->subtreeRefs + node->above->subtreeRefs;
    return node;
}

// The non-degenerate triangles' references with their bounding boxes, in triangle order, and the
// root box around them (left as it is when there are none).
RefList rootRefs(const std::vector<Triangle>& tris, Box& root) {
    const std::vector<uint8_t> degenerate = degenerateTriangles(tris);
    RefList refs;
    refs.reserve(tris.size() - size_t(std::count(degenerate.begin(), degenerate.end(), uint8_t(1))));
    for (size_t t = 0; t < tris.size(); ++t) {
        if (degenerate[t]) continue;
        const Box b = boundsOf(tris[t]);
        root = refs.empty() ? b : Box{glm::min(root.lo, b.lo), glm::max(root.hi, b.hi)};
        refs.push_back(Ref{b, uint32_t(t)});
    }
    return refs;
}

}  // namespace

KdBuildResult buildBinnedKdTree(const std::vector<Triangle>& triangles, const KdConfig& config, int threads,
                                const BuildProgress& progress) {
    if (config.bins < 1 || config.bins > KdConfig::kMaxBins)
        throw Error("kd-tree bins must be 1.." + std::to_string(KdConfig::kMaxBins) + " (got " +
                    std::to_string(config.bins) + ")");
    const Clock::time_point start = Clock::now();
    KdBuildResult result;
    tbb::task_arena arena(arenaThreads(threads));
    arena.execute([&] {
        if (progress) progress("kd-tree: bounds", 0.0);
        Box root;
        RefList refs = rootRefs(triangles, root);
        result.times.eventsMs = msSince(start);

        const Clock::time_point treeStart = Clock::now();
        const uint64_t treeTicks = ticks();
        const size_t n = refs.size();
        Builder builder(triangles, config, config.resolvedMaxDepth(n), progress);
        NodePtr tree = builder.build(std::move(refs), root, 0, config.maxDuplication * double(n));
        builder.finishProgress();
        KdBuildTimes& t = result.times;
        t.treeMs = msSince(treeStart);
        const double msPerTick = t.treeMs / double(std::max<uint64_t>(1, ticks() - treeTicks));
        const std::array<uint64_t, kPhaseCount> phase = builder.phaseTicks();
        for (auto [p, ms] : {std::pair{kBin, &t.sweepMs}, {kSplitRefs, &t.distributeMs}, {kClip, &t.clipMs},
                             {kLeaves, &t.leavesMs}, {kSmall, &t.smallMs}})
            *ms = double(phase[p]) * msPerTick;

        const Clock::time_point flattenStart = Clock::now();
        if (progress) progress("kd-tree: flattening", 1.0);
        flattenBuiltTree(std::move(tree), root, result.tree);
        t.flattenMs = msSince(flattenStart);
    });
    result.times.totalMs = msSince(start);
    return result;
}

}  // namespace vkray::accel::kd
