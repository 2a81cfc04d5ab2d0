#include "accel/kd/sah_kd_builder.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <new>
#include <optional>
#include <stdexcept>
#include <string>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/scalable_allocator.h>
#include <tbb/task_arena.h>

#if defined(__x86_64__) || defined(__i386__)
#include <x86intrin.h>
#endif

#include "core/error.h"
#include "core/fork_join.h"
#include "core/worker_arena.h"
#include "core/parallel_alloc.h"
#include "core/radix_sort.h"
#include "core/timing.h"
#include "geometry/ray_triangle.h"
#include "accel/kd/kd_clip.h"
#include "accel/kd/kd_build_tree.h"
#include "accel/kd/kd_events.h"
#include "accel/kd/kd_split.h"

namespace vkray::accel::kd {
namespace {

// Nodes with at least this many events build their two subtrees as parallel tasks; below it the
// task overhead outweighs the work.
constexpr size_t kParallelEvents = 1 << 13;
// Nodes with at least this many events also sweep and distribute their three axes as parallel tasks.
constexpr size_t kParallelAxesEvents = 1 << 16;

struct SplitChoice {
    int axis = -1;
    float pos = 0.0f;
    bool planarBelow = true;  // where triangles lying in the plane go
    double cost = std::numeric_limits<double>::infinity();
    size_t below = 0, above = 0;  // triangles on each side

    SplitPlane plane() const { return {axis, pos, planarBelow}; }
};

// A leaf's triangles, appended to `out` in index order: one a start or planar event of an axis's
// list (a triangle has one of those on each axis).
void appendTrianglesOf(EventSpan axisEvents, TriangleList& out) {
    const size_t first = out.size();
    for (const Event& e : axisEvents)
        if (e.type() != EventType::End) out.push_back(e.triangle());
    std::sort(out.begin() + std::ptrdiff_t(first), out.end());
}

// The node's `n` triangles, ascending.
TriangleList trianglesOf(const NodeEvents& ev, size_t n) {
    TriangleList tris;
    tris.reserve(n);
    appendTrianglesOf(ev[0], tris);
    return tris;
}

// A float split the GPU reads back unchanged: strictly inside the box (a split on the boundary cuts
// nothing) and not denormal (lavapipe flushes denormals to zero).
bool usableSplit(const Box& box, int axis, float pos) {
    return pos > box.lo[axis] && pos < box.hi[axis] && (pos == 0.0f || std::abs(pos) >= std::numeric_limits<float>::min());
}

// The SAH cost of a split along one axis (KdConfig), with what depends only on the node and the axis
// set once per sweep. The children's surface areas are linear in the split position: the two faces
// across the axis (`caps`) plus the four along it (`sides` per unit of length), so a candidate costs
// a few multiplications instead of two boxes' areas. The products are formed as in KdConfig's
// formula, Ct + Ci * bonus / SA(N) * (SA(L) nL + SA(R) nR), left to right, so every candidate's cost
// is the same double whichever way the sweep reaches it. Counts are signed: a signed integer
// converts to double in one instruction, an unsigned one does not.
struct AxisCost {
    double lo, hi, caps, sides, traversal, fullScale, emptyScale, minEmpty;

    AxisCost(const Box& box, int axis, double invArea, const KdConfig& config) {
        const glm::dvec3 e = glm::dvec3(box.hi) - glm::dvec3(box.lo);
        const double a = e[(axis + 1) % 3], b = e[(axis + 2) % 3];
        lo = box.lo[axis];
        hi = box.hi[axis];
        caps = 2.0 * a * b;
        sides = 2.0 * (a + b);
        traversal = config.traversalCost;
        fullScale = config.intersectionCost * 1.0 * invArea;
        emptyScale = config.intersectionCost * (1.0 - config.emptyBonus) * invArea;
        // The bonus only for empty space worth a level of the tree (KdConfig::emptyBonusMinFraction).
        minEmpty = config.emptyBonusMinFraction * (hi - lo);
    }

    double operator()(float pos, int64_t nBelow, int64_t nAbove) const {
        const double below = caps + sides * (double(pos) - lo);
        const double above = caps + sides * (hi - double(pos));
        const double emptyExtent = nBelow == 0 ? double(pos) - lo : nAbove == 0 ? hi - double(pos) : 0.0;
        const bool emptySide = (nBelow == 0 || nAbove == 0) && emptyExtent >= minEmpty;
        return traversal + (emptySide ? emptyScale : fullScale) * (below * double(nBelow) + above * double(nAbove));
    }
};

// The build's phases (KdBuildTimes), timed per worker in processor ticks, turned into milliseconds
// once, against the wall clock, at the end. Nodes of at least kTimedEvents events are timed phase by
// phase; a subtree below that is timed as a whole (kSmall), on the one worker that builds it (its
// nodes are below kParallelEvents), so the timing costs nothing that matters where nodes are many
// and small. One node in kSampledSmallNodes of the small subtrees (a worker's first, and every
// kSampledSmallNodes-th after it) is timed phase by phase as well, and the small subtrees' share
// of each phase is estimated from those nodes in proportion to the count: tens of thousands of
// samples where whole subtrees would give a few (a few hundred subtrees hold a mesh's work), for
// 0.5% more instructions (the dragon's build).
enum Phase : size_t { kSweep, kClassify, kClip, kDistribute, kLeaves, kSmall, kPhaseCount };
constexpr size_t kTimedEvents = kSmallSubtreeEvents;
static_assert(kTimedEvents <= kParallelEvents);

uint64_t ticks() {
#if defined(__x86_64__) || defined(__i386__)
    return __rdtsc();
#else
    return uint64_t(Clock::now().time_since_epoch().count());
#endif
}

// Where a small subtree's node finds its lists on its worker's stack (WorkerScratch::stack).
struct StackLists {
    std::array<size_t, 3> at{}, size{};
};

// What one worker reuses from node to node instead of allocating it anew. The splitter's state is
// used only within one node's split, where no other node's task runs on this worker (splitEvents).
// A small subtree's event lists live on `stack`, each node's children's above its own and popped
// when they are built (buildFlat): its thousands of nodes allocate and free no list.
struct WorkerScratch {
    ListSplitter splitter;
    AxisEvents stack;
    size_t top = 0;            // the stack's first free event
    FlatSubtree flat;          // the small subtree being built (buildFlat)
    TriangleList flatIndices;  // its index list
    std::array<uint64_t, kPhaseCount> ticks{};
    std::array<uint64_t, kPhaseCount> sampledTicks{};  // the phases of the sampled small-subtree nodes
    bool inSmallSubtree = false;  // timed as a whole (kSmall): its phases only at sampled nodes
    bool sampled = false;         // this small-subtree node is timed phase by phase
    uint64_t smallNodes = 0;      // small-subtree nodes built (numbers 0, 64, ... sampled)
    uint64_t doneWeight = 0;      // leaves' progress weights not yet added to the build's
};

// Workers add their leaves' progress weights to the shared sum in steps of 2^-16 of the tree: an
// atomic add (and a lock, with a progress callback) for every one of millions of leaves would have
// the workers queue for one cache line.
constexpr uint64_t kProgressStep = uint64_t(1) << (62 - 16);

class Builder {
public:
    Builder(const std::vector<Triangle>& tris, const KdConfig& config, const BuildProgress& progress)
        : tris_(tris), config_(config), progress_(progress) {}

    // scratch: this worker's, when the caller has it at hand (else looked up).
    NodePtr build(NodeEvents ev, const Box& box, int depth, size_t n, double budget,
                                     WorkerScratch* scratch = nullptr);
    void setMaxDepth(int d) { maxDepth_ = d; }
    // Adds the weights the workers hold back (after the build, on one thread).
    void finishProgress();
    // Ticks of each phase, summed over the workers: all nodes', or only the sampled small-subtree nodes'.
    std::array<uint64_t, kPhaseCount> phaseTicks(bool sampledSmall) const;
    // Small-subtree nodes over those sampled, summed over the workers (0 when none was sampled).
    double smallNodesPerSample() const;

private:
    // invArea: 1 / the box's surface area.
    void sweepAxis(int axis, EventSpan ev, const Box& box, double invArea, size_t n, double budget,
                   SplitChoice& best) const;
    SplitChoice findBestSplit(WorkerScratch& w, const NodeSpans& ev, const Box& box, size_t n, double budget,
                              bool parallel);
    std::pair<NodeEvents, NodeEvents> splitEvents(WorkerScratch& w, NodeEvents ev, const SplitChoice& s,
                                                  const Box& below, const Box& above, bool parallel);
    void splitEventsOn(WorkerScratch& w, NodeEvents& ev, const SplitChoice& s, const Box& below, const Box& above,
                       bool parallel, NodeEvents& belowEv, NodeEvents& aboveEv);
    NodePtr makeLeaf(WorkerScratch& w, const NodeEvents& ev, int depth, size_t n);
    // A small subtree (under kTimedEvents events) from buildFlat, as a leaf when it is one.
    NodePtr buildSmall(WorkerScratch& w, NodeEvents ev, const Box& box, int depth, size_t n, double budget);
    // Appends the subtree of the node whose lists are `lists` to w.flat in depth-first order.
    void buildFlat(WorkerScratch& w, const StackLists& lists, const Box& box, int depth, size_t n, double budget);
    std::pair<StackLists, StackLists> splitOnStack(WorkerScratch& w, const StackLists& lists, const SplitChoice& s,
                                                   const Box& below, const Box& above);
    // The lists' events, valid until the stack grows.
    static NodeSpans spansOn(const WorkerScratch& w, const StackLists& lists);
    void addProgress(WorkerScratch& w);
    // The split's sides marked and its straddlers clipped to both children (w.splitter), each step
    // timed to its phase; returns the clip's end (the list split's start).
    uint64_t classifyAndClip(WorkerScratch& w, EventSpan splitAxis, const SplitChoice& s, const Box& below,
                             const Box& above);
    // A leaf at `depth`, made since `start`: its time to the leaves' phase, its weight to the progress.
    void leafDone(WorkerScratch& w, int depth, uint64_t start);
    // Whether `w`'s phases are timed now: outside the small subtrees (timed as a whole), and at their
    // sampled nodes (to the sampled ticks).
    static bool timed(const WorkerScratch& w) { return !w.inSmallSubtree || w.sampled; }
    static uint64_t start(const WorkerScratch& w) { return timed(w) ? ticks() : 0; }
    // Ticks since `start` to `phase` of `w`, when timed; returns the next phase's start.
    static uint64_t lap(WorkerScratch& w, Phase phase, uint64_t start) {
        if (!timed(w)) return 0;
        const uint64_t now = ticks();
        (w.inSmallSubtree ? w.sampledTicks : w.ticks)[phase] += now - start;
        return now;
    }
    // f(0), f(1), f(2), its time added to `phase` of the worker that ran it: as three oneTBB tasks
    // when `parallel`, each on its own worker's account, else in a row on `w`, this worker's.
    template <class F>
    void forEachAxisTimed(bool parallel, Phase phase, WorkerScratch& w, const F& f);

    const std::vector<Triangle>& tris_;
    KdConfig config_;
    int maxDepth_ = 0;
    // The key per instance: local() is a thread-local lookup, which every node makes.
    tbb::enumerable_thread_specific<WorkerScratch, tbb::cache_aligned_allocator<WorkerScratch>,
                                    tbb::ets_key_per_instance>
        scratch_;

    // Progress: a leaf at depth d completes 2^-d of the tree (the weights of a binary tree's leaves
    // sum to 1), kept in fixed point; the workers add theirs in steps (kProgressStep).
    const BuildProgress& progress_;
    std::atomic<uint64_t> doneWeight_{0};
    std::mutex progressMutex_;
    double reported_ = 0.0;
};

double Builder::smallNodesPerSample() const {
    uint64_t nodes = 0, sampled = 0;
    for (const WorkerScratch& w : scratch_) {
        nodes += w.smallNodes;
        sampled += (w.smallNodes + kSampledSmallNodes - 1) / kSampledSmallNodes;  // nodes 0, 64, 128, ...
    }
    return sampled > 0 ? double(nodes) / double(sampled) : 0.0;
}

std::array<uint64_t, kPhaseCount> Builder::phaseTicks(bool sampledSmall) const {
    std::array<uint64_t, kPhaseCount> sum{};
    for (const WorkerScratch& w : scratch_)
        for (size_t p = 0; p < kPhaseCount; ++p) sum[p] += sampledSmall ? w.sampledTicks[p] : w.ticks[p];
    return sum;
}

template <class F>
void Builder::forEachAxisTimed(bool parallel, Phase phase, WorkerScratch& w, const F& f) {
    if (parallel) {
        const auto timed = [&](int k) {
            const uint64_t t = ticks();
            f(k);
            scratch_.local().ticks[phase] += ticks() - t;
        };
        tbb::parallel_invoke([&] { timed(0); }, [&] { timed(1); }, [&] { timed(2); });
    } else {
        const uint64_t t = start(w);
        for (int k = 0; k < 3; ++k) f(k);
        lap(w, phase, t);
    }
}

// The plane sweep of Wald and Havran (section 4.2, Algorithm 4) with their classification: at plane
// p, below = triangles starting before p (those ending at p touch it from below), above = triangles
// ending after p (those starting at p touch it from above); triangles flat in p are tried on each side.
// A split whose two sides together hold more references than `budget` is not a candidate (the half
// absorbs the rounding of budgets handed down in proportion: counts are whole).
void Builder::sweepAxis(int axis, EventSpan ev, const Box& box, double invArea, size_t n, double budget,
                        SplitChoice& best) const {
    const AxisCost cost(box, axis, invArea, config_);
    int64_t startedBefore = 0, endingAfter = int64_t(n);
    const Event* e = ev.data();
    const Event* const end = e + ev.size();
    while (e != end) {
        const float p = e->pos();
        const uint32_t at = e->orderedPos();
        // The events at p, counted by type without branching on it: ends and starts alternate
        // unpredictably along an axis, and a branch on the type would be mispredicted half the time.
        int64_t ends = 0, planars = 0, starts = 0;
        do {
            const EventType type = e->type();
            ends += type == EventType::End;
            planars += type == EventType::Planar;
            starts += type == EventType::Start;
        } while (++e != end && e->orderedPos() == at);
        endingAfter -= ends + planars;
        if (usableSplit(box, axis, p) && double(startedBefore + endingAfter + planars) <= budget + 0.5) {
            const int64_t below = startedBefore, above = endingAfter;
            // Without planar triangles both placements are the same split, costed once.
            const double planarBelowCost = cost(p, below + planars, above);
            const double planarAboveCost = planars == 0 ? planarBelowCost : cost(p, below, above + planars);
            const bool planarBelow = planarBelowCost <= planarAboveCost;
            const double c = planarBelow ? planarBelowCost : planarAboveCost;
            if (c < best.cost)
                best = SplitChoice{axis, p, planarBelow, c, size_t(below + (planarBelow ? planars : 0)),
                                   size_t(above + (planarBelow ? 0 : planars))};
        }
        startedBefore += starts + planars;
    }
}

// The three axes' sweeps are independent: a big node sweeps them as parallel tasks (the top levels
// would otherwise run on one thread while the others wait), then takes the best in axis order with
// the same strict comparison as one sweep after the other, so the choice is the same either way.
SplitChoice Builder::findBestSplit(WorkerScratch& w, const NodeSpans& ev, const Box& box, size_t n, double budget,
                                   bool parallel) {
    const double area = box.surfaceArea();
    if (!(area > 0.0)) return {};
    std::array<SplitChoice, 3> perAxis;
    forEachAxisTimed(parallel, kSweep, w,
                     [&](int axis) { sweepAxis(axis, ev[axis], box, 1.0 / area, n, budget, perAxis[axis]); });
    SplitChoice best = perAxis[0];
    for (int axis = 1; axis < 3; ++axis)
        if (perAxis[axis].cost < best.cost) best = perAxis[axis];
    return best;
}

// Wald and Havran 5.2-5.3: classify the triangles by the chosen split's axis events, clip the
// straddling triangles to both children and sort their few new events, then hand each one-sided
// triangle's events to its side in order, the new ones merged in on the way (one pass, where a
// merge after the copy would move the events again). Everything stays sorted without a full sort.
// A big node's axes are distributed and merged as parallel tasks that read this worker's scratch,
// so the wait is isolated: this worker runs no other node's task (which would overwrite the
// scratch) until its own are done.
std::pair<NodeEvents, NodeEvents> Builder::splitEvents(WorkerScratch& w, NodeEvents ev, const SplitChoice& s,
                                                       const Box& below, const Box& above, bool parallel) {
    std::pair<NodeEvents, NodeEvents> children;
    // Empty space cut off: every triangle is on the other side (a straddler would count on both),
    // so that side's lists are the parent's as they are, in order, and nothing is classified,
    // copied or clipped. Most splits of a deep tree over small triangles are of this kind.
    if (s.below == 0 || s.above == 0) {
        (s.above == 0 ? children.first : children.second) = std::move(ev);
        return children;
    }
    const auto split = [&] { splitEventsOn(w, ev, s, below, above, parallel, children.first, children.second); };
    if (parallel) tbb::this_task_arena::isolate(split);
    else split();
    return children;
}

void Builder::splitEventsOn(WorkerScratch& w, NodeEvents& ev, const SplitChoice& s, const Box& below,
                            const Box& above, bool parallel, NodeEvents& belowEv, NodeEvents& aboveEv) {
    classifyAndClip(w, ev[s.axis], s, below, above);
    forEachAxisTimed(parallel, kDistribute, w, [&](int k) {
        AxisEvents &toBelow = belowEv[k], &toAbove = aboveEv[k];
        // A triangle has at most two events per axis, so twice a side's count (straddlers included)
        // holds its kept events and the straddlers' new ones: no reallocation below.
        toBelow.reserve(2 * s.below);
        toAbove.reserve(2 * s.above);
        w.splitter.distribute(
            k, ev[k], [&](const Event& e) { toBelow.push_back(e); }, [&](const Event& e) { toAbove.push_back(e); });
        AxisEvents().swap(ev[k]);  // free the parent's lists before the children grow theirs
    });
}

NodePtr Builder::makeLeaf(WorkerScratch& w, const NodeEvents& ev, int depth, size_t n) {
    const uint64_t t = start(w);
    NodePtr leaf(ev[0].empty() ? &kEmptyLeaf : new BuildNode);  // every triangle has an event on each axis
    if (leaf.get() != &kEmptyLeaf) {
        leaf->triangles = trianglesOf(ev, n);
        leaf->subtreeRefs = leaf->triangles.size();
    }
    leafDone(w, depth, t);
    return leaf;
}

inline void Builder::leafDone(WorkerScratch& w, int depth, uint64_t start) {
    lap(w, kLeaves, start);  // before the progress report, which may print
    w.doneWeight += uint64_t(1) << (62 - depth);
    if (w.doneWeight >= kProgressStep) addProgress(w);
}

inline uint64_t Builder::classifyAndClip(WorkerScratch& w, EventSpan splitAxis, const SplitChoice& s,
                                         const Box& below, const Box& above) {
    uint64_t t = start(w);
    w.splitter.classify(splitAxis, s.plane(), tris_.size());
    t = lap(w, kClassify, t);
    w.splitter.clip(tris_, below, above, s.axis);
    return lap(w, kClip, t);
}

NodePtr Builder::buildSmall(WorkerScratch& w, NodeEvents ev, const Box& box, int depth, size_t n, double budget) {
    w.flat.clear();
    w.flatIndices.clear();
    StackLists lists;
    w.top = 0;
    for (int k = 0; k < 3; ++k) {
        lists.at[k] = w.top;
        lists.size[k] = ev[k].size();
        w.top += ev[k].size();
    }
    if (w.stack.size() < w.top) w.stack.resize(w.top);
    for (int k = 0; k < 3; ++k) {
        std::copy(ev[k].begin(), ev[k].end(), w.stack.begin() + std::ptrdiff_t(lists.at[k]));
        AxisEvents().swap(ev[k]);
    }
    buildFlat(w, lists, box, depth, n, budget);
    const gpu::KdNode& root = w.flat[0];
    if (root.isLeaf() && root.triangleCount() == 0) return NodePtr(&kEmptyLeaf);
    NodePtr node(new BuildNode);
    node->axis = root.isLeaf() ? BuildNode::kLeaf : BuildNode::kFlat;
    node->triangles.assign(w.flatIndices.begin(), w.flatIndices.end());
    node->subtreeRefs = node->triangles.size();
    if (node->axis == BuildNode::kFlat) {
        node->flat.assign(w.flat.begin(), w.flat.end());
        node->subtreeNodes = uint32_t(w.flat.size());
    }
    return node;
}

NodeSpans Builder::spansOn(const WorkerScratch& w, const StackLists& lists) {
    NodeSpans ev;
    for (int k = 0; k < 3; ++k) ev[k] = EventSpan(w.stack.data() + lists.at[k], lists.size[k]);
    return ev;
}

// The split of a small subtree's node: as splitEvents, the children's lists written on the stack
// from its top, in room for two events per triangle and axis (at most that many: no bounds checks).
std::pair<StackLists, StackLists> Builder::splitOnStack(WorkerScratch& w, const StackLists& lists,
                                                        const SplitChoice& s, const Box& below, const Box& above) {
    std::pair<StackLists, StackLists> children;
    if (s.below == 0 || s.above == 0) {  // empty space cut off: the other side's lists are the parent's
        (s.above == 0 ? children.first : children.second) = lists;
        return children;
    }
    const size_t base = w.top, end = base + 6 * (s.below + s.above);
    if (w.stack.size() < end) w.stack.resize(std::max(end, 2 * w.stack.size()));
    const NodeSpans ev = spansOn(w, lists);  // after the stack's growth, which moves it
    const uint64_t t = classifyAndClip(w, ev[s.axis], s, below, above);
    Event* const stack = w.stack.data();
    for (int k = 0; k < 3; ++k) {
        children.first.at[k] = base + 2 * s.below * size_t(k);
        children.second.at[k] = base + 6 * s.below + 2 * s.above * size_t(k);
        Event* toBelow = stack + children.first.at[k];
        Event* toAbove = stack + children.second.at[k];
        w.splitter.distribute(k, ev[k], [&](const Event& e) { *toBelow++ = e; }, [&](const Event& e) { *toAbove++ = e; });
        children.first.size[k] = size_t(toBelow - (stack + children.first.at[k]));
        children.second.size[k] = size_t(toAbove - (stack + children.second.at[k]));
    }
    lap(w, kDistribute, t);
    w.top = end;
    return children;
}

// build() below kTimedEvents, with the same choices, written as flatten() would write them.
void Builder::buildFlat(WorkerScratch& w, const StackLists& lists, const Box& box, int depth, size_t n,
                        double budget) {
    const auto index = uint32_t(w.flat.size());
    w.flat.emplace_back();
    // This node's phases all run before its children's, which sample themselves.
    w.sampled = w.smallNodes++ % kSampledSmallNodes == 0;
    SplitChoice s;
    if (n > 0 && depth < maxDepth_) s = findBestSplit(w, spansOn(w, lists), box, n, budget, false);
    if (s.axis < 0 || s.cost >= config_.intersectionCost * double(n)) {
        const uint64_t t = start(w);
        const auto first = uint32_t(w.flatIndices.size());
        appendTrianglesOf(spansOn(w, lists)[0], w.flatIndices);
        w.flat[index] = gpu::KdNode::leaf(first, uint32_t(w.flatIndices.size() - first));
        leafDone(w, depth, t);
        return;
    }
    const auto [belowBox, aboveBox] = splitBox(box, s.axis, s.pos);
    const size_t top = w.top;
    const auto [belowLists, aboveLists] = splitOnStack(w, lists, s, belowBox, aboveBox);
    const double share = budget / double(s.below + s.above);
    buildFlat(w, belowLists, belowBox, depth + 1, s.below, share * double(s.below));
    const auto aboveIndex = uint32_t(w.flat.size());
    buildFlat(w, aboveLists, aboveBox, depth + 1, s.above, share * double(s.above));
    w.top = top;  // the children's lists popped
    const auto empty = [&](uint32_t i) { return w.flat[i].isLeaf() && w.flat[i].triangleCount() == 0; };
    w.flat[index] = gpu::KdNode::inner(s.axis, s.pos, aboveIndex, empty(index + 1), empty(aboveIndex));
}

void Builder::addProgress(WorkerScratch& w) {
    const uint64_t done = doneWeight_.fetch_add(w.doneWeight) + w.doneWeight;
    w.doneWeight = 0;
    if (!progress_) return;
    const double fraction = double(done) / double(uint64_t(1) << 62);
    std::lock_guard lock(progressMutex_);
    if (fraction >= reported_ + 0.01) {
        reported_ = fraction;
        progress_("kd-tree: splitting", fraction);
    }
}

void Builder::finishProgress() {
    for (WorkerScratch& w : scratch_)
        if (w.doneWeight > 0) addProgress(w);
}

// `budget`: the most references this subtree's leaves may hold together (KdConfig::maxDuplication).
// A split hands it on in proportion to the two sides' counts, so a child's budget over its count is
// the parent's divided by the split's duplication (nBelow + nAbove) / n: along any path the
// duplications multiply to at most maxDuplication, and the whole tree holds at most that many
// references per triangle, whatever the geometry.
// `n`: the node's triangles (the split that made it counted them).
NodePtr Builder::build(NodeEvents ev, const Box& box, int depth, size_t n, double budget,
                                          WorkerScratch* scratch) {
    // This worker's scratch, valid until the fork below (the subtrees may run on other workers);
    // a subtree built on this worker after this node gets it handed on.
    WorkerScratch& w = scratch ? *scratch : scratch_.local();
    if (!w.inSmallSubtree && ev[0].size() < kTimedEvents) {
        const uint64_t t = ticks();
        w.inSmallSubtree = true;
        NodePtr subtree = buildSmall(w, std::move(ev), box, depth, n, budget);
        w.inSmallSubtree = false;
        w.ticks[kSmall] += ticks() - t;
        return subtree;
    }
    if (n == 0 || depth >= maxDepth_) return makeLeaf(w, ev, depth, n);
    const bool parallel = ev[0].size() >= kParallelEvents, parallelAxes = ev[0].size() >= kParallelAxesEvents;
    const SplitChoice s = findBestSplit(w, spansOf(ev), box, n, budget, parallelAxes);
    // SAH termination (Wald and Havran, section 3): split only when it is cheaper than a leaf.
    if (s.axis < 0 || s.cost >= config_.intersectionCost * double(n)) return makeLeaf(w, ev, depth, n);

    NodePtr node(new BuildNode);
    node->axis = s.axis;
    node->split = s.pos;
    const auto [belowBox, aboveBox] = splitBox(box, s.axis, s.pos);
    auto [belowEv, aboveEv] = splitEvents(w, std::move(ev), s, belowBox, aboveBox, parallelAxes);
    const double share = budget / double(s.below + s.above);
    WorkerScratch* const handOn = parallel ? nullptr : &w;
    const auto buildBelow = [&, &bEv = belowEv, &bBox = belowBox] {
        node->below = build(std::move(bEv), bBox, depth + 1, s.below, share * double(s.below), handOn);
    };
    const auto buildAbove = [&, &aEv = aboveEv, &aBox = aboveBox] {
        node->above = build(std::move(aEv), aBox, depth + 1, s.above, share * double(s.above), handOn);
    };
    forkJoin(parallel, buildBelow, buildAbove);
    node->subtreeNodes = 1 + node->below->subtreeNodes + node->above->subtreeNodes;
    node->subtreeRefs = node->below->subtreeRefs + node->above->subtreeRefs;
    return node;
}

}  // namespace

KdBuildResult buildSahKdTree(const std::vector<Triangle>& triangles, const KdConfig& config, int threads,
                             const BuildProgress& progress) {
    const Clock::time_point start = Clock::now();
    KdBuildResult result;
    tbb::task_arena arena(arenaThreads(threads));
    arena.execute([&] {
        if (progress) progress("kd-tree: events", 0.0);
        if (triangles.size() > Event::kMaxTriangles)
            throw Error("the kd-tree builder takes at most " + std::to_string(Event::kMaxTriangles) +
                        " triangles (the scene has " + std::to_string(triangles.size()) + ")");
        // Which triangles are degenerate, in parallel (double-precision cross products).
        std::vector<uint8_t> degenerate(triangles.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, triangles.size(), 1 << 14), [&](const auto& r) {
            for (size_t t = r.begin(); t != r.end(); ++t) {
                const Triangle& tri = triangles[t];
                degenerate[t] = geometry::isDegenerate({glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)});
            }
        });
        Box root;
        NodeEvents ev = rootEvents(triangles, degenerate, root);
        const size_t n = triangleCount(ev);
        // Each list ascends by triangle, so a stable sort on position and type
        // (the key's upper 34 bits) is the sort on the whole key.
        for (AxisEvents& e : ev) radixSortBits(e, 30, 34, [](const Event& x) { return x.key(); });
        result.times.eventsMs = msSince(start);

        const Clock::time_point treeStart = Clock::now();
        const uint64_t treeTicks = ticks();
        Builder builder(triangles, config, progress);
        builder.setMaxDepth(config.resolvedMaxDepth(n));
        NodePtr tree = builder.build(std::move(ev), root, 0, n, config.maxDuplication * double(n));
        builder.finishProgress();
        result.times.treeMs = msSince(treeStart);
        const double msPerTick = result.times.treeMs / double(std::max<uint64_t>(1, ticks() - treeTicks));
        const std::array<uint64_t, kPhaseCount> phase = builder.phaseTicks(false), sampled = builder.phaseTicks(true);
        const double smallScale = builder.smallNodesPerSample();  // the sampled nodes' phases, scaled to all
        KdBuildTimes& t = result.times;
        for (auto [p, ms] : {std::pair{kSweep, &t.sweepMs}, {kClassify, &t.classifyMs}, {kDistribute, &t.distributeMs},
                             {kClip, &t.clipMs}, {kLeaves, &t.leavesMs}})
            *ms = (double(phase[p]) + double(sampled[p]) * smallScale) * msPerTick;
        t.smallMs = double(phase[kSmall]) * msPerTick;

        const Clock::time_point flattenStart = Clock::now();
        if (progress) progress("kd-tree: flattening", 1.0);
        if (tree->subtreeRefs > UINT32_MAX)  // a leaf's first entry is a 32-bit word (kd_layout.h)
            throw Error("the kd-tree holds " + std::to_string(tree->subtreeRefs) +
                        " triangle references; its GPU layout addresses at most " + std::to_string(UINT32_MAX));
        // The walk below writes every node and index entry.
        resizeForOverwrite(result.tree.nodes, tree->subtreeNodes);
        resizeForOverwrite(result.tree.indices, size_t(tree->subtreeRefs));
        flattenKdTree(std::move(tree), 0, 0, result.tree, 0);
        result.tree.header = gpu::KdTreeHeader{root.lo, uint32_t(result.tree.nodes.size()), root.hi,
                                               uint32_t(result.tree.indices.size())};
        result.times.flattenMs = msSince(flattenStart);
    });
    result.times.totalMs = msSince(start);
    return result;
}

}  // namespace vkray::accel::kd
