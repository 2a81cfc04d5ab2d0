// The SAH kd-tree's invariants: leaf boxes partition the root box, every point of a triangle lies in
// a leaf that references it, reached by taking one side (either) of each split plane the point lies
// on (so none is ever lost, flat ones included), the depth bound, the layout's packing, and the same
// tree whatever the thread count.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/kd/kd_traversal.h"
#include "accel/kd/kd_tree.h"
#include "accel/kd/sah_kd_builder.h"
#include "geometry/brute_force.h"
#include "geometry/ray_triangle.h"
#include "kd_test_util.h"

namespace vkray::accel::kd {
namespace {

// The tree with its node boxes and parent links, which the tests check.
KdTree build(const Scene& s, int threads = 1, KdConfig config = {}) {
    KdTree tree = buildSahKdTree(s.triangles, config, threads).tree;
    deriveNodeExtras(tree, threads);
    return tree;
}

bool boxHolds(const gpu::KdNodeExtra& b, const glm::dvec3& p) {
    return glm::all(glm::lessThanEqual(glm::dvec3(b.lo), p)) && glm::all(glm::lessThanEqual(p, glm::dvec3(b.hi)));
}

// Leaves whose closed box holds p, found from the splits (both sides when p lies in a plane).
void leavesHolding(const KdTree& t, uint32_t node, const glm::dvec3& p, std::vector<uint32_t>& out) {
    const gpu::KdNode& n = t.nodes[node];
    if (n.isLeaf()) {
        out.push_back(node);
        return;
    }
    if (p[n.axis()] <= double(n.split())) leavesHolding(t, node + 1, p, out);
    if (p[n.axis()] >= double(n.split())) leavesHolding(t, n.aboveChild(), p, out);
}

bool leafReferences(const KdTree& t, uint32_t leaf, uint32_t triangle) {
    const gpu::KdNode& n = t.nodes[leaf];
    const auto begin = t.indices.begin() + n.firstIndex(), end = begin + n.triangleCount();
    return std::find(begin, end, triangle) != end;
}

// Points of a triangle that are exact in double for float vertices (dyadic barycentrics): the
// vertices, edge midpoints and three interior points.
std::vector<glm::dvec3> exactPointsOf(const Triangle& t) {
    const glm::dvec3 a(t.p0), b(t.p1), c(t.p2);
    return {a, b, c, (a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5, (a + b) * 0.25 + c * 0.5,
            (b + c) * 0.25 + a * 0.5, (c + a) * 0.25 + b * 0.5};
}

// Whether every leaf whose box holds p in its interior side references the triangle. For a point
// on a split plane one side suffices: the builder puts a triangle that touches the plane, or lies in
// it, on one defined side (Wald and Havran's classification), and the traversals visit that side.
bool referencedAround(const KdTree& t, uint32_t node, const glm::dvec3& p, uint32_t k) {
    const gpu::KdNode& n = t.nodes[node];
    if (n.isLeaf()) return leafReferences(t, node, k);
    const int a = n.axis();
    const double split = n.split();
    if (p[a] < split) return referencedAround(t, node + 1, p, k);
    if (p[a] > split) return referencedAround(t, n.aboveChild(), p, k);
    return referencedAround(t, node + 1, p, k) || referencedAround(t, n.aboveChild(), p, k);
}

void expectConservative(const Scene& s, const KdTree& t) {
    size_t checked = 0;
    for (uint32_t k = 0; k < s.triangles.size(); ++k) {
        const Triangle& tri = s.triangles[k];
        if (geometry::isDegenerate({glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)})) continue;
        for (const glm::dvec3& p : exactPointsOf(tri)) {
            std::vector<uint32_t> leaves;
            leavesHolding(t, 0, p, leaves);
            ASSERT_FALSE(leaves.empty()) << "triangle " << k << " outside the root box";
            for (uint32_t leaf : leaves) ASSERT_TRUE(boxHolds(t.extra[leaf], p));
            ASSERT_TRUE(referencedAround(t, 0, p, k))
                << "triangle " << k << " missing from a leaf whose box holds its point";
            checked += leaves.size();
        }
    }
    EXPECT_GT(checked, s.triangles.size());
}

// Inner splits lie strictly inside their node's box, children's boxes are the two halves, parent
// links point back, an inner node flags exactly its children that are leaves without triangles, and
// the leaves' volumes add up to the root's (they tile it).
void expectPartition(const KdTree& t) {
    ASSERT_EQ(t.nodes.size(), t.extra.size());
    ASSERT_EQ(t.header.nodeCount, t.nodes.size());
    ASSERT_EQ(t.header.indexCount, t.indices.size());
    EXPECT_EQ(t.extra[0].parent, VKRAY_KD_NO_PARENT);
    const auto volume = [](const gpu::KdNodeExtra& e) {
        const glm::dvec3 d = glm::dvec3(e.hi) - glm::dvec3(e.lo);
        return d.x * d.y * d.z;
    };
    double leafVolume = 0.0;
    for (uint32_t i = 0; i < t.nodes.size(); ++i) {
        const gpu::KdNode& n = t.nodes[i];
        if (n.isLeaf()) {
            leafVolume += volume(t.extra[i]);
            ASSERT_LE(size_t(n.firstIndex()) + n.triangleCount(), t.indices.size());
            continue;
        }
        const gpu::KdNodeExtra& box = t.extra[i];
        const int a = n.axis();
        ASSERT_GT(n.split(), box.lo[a]);
        ASSERT_LT(n.split(), box.hi[a]);
        const uint32_t below = i + 1, above = n.aboveChild();
        ASSERT_GT(above, below);
        ASSERT_LT(above, t.nodes.size());
        EXPECT_EQ(t.extra[below].parent, i);
        EXPECT_EQ(t.extra[above].parent, i);
        const auto emptyLeaf = [&](uint32_t c) { return t.nodes[c].isLeaf() && t.nodes[c].triangleCount() == 0; };
        EXPECT_EQ(n.childEmpty(false), emptyLeaf(below)) << "node " << i;
        EXPECT_EQ(n.childEmpty(true), emptyLeaf(above)) << "node " << i;
        gpu::KdNodeExtra expectBelow = box, expectAbove = box;
        expectBelow.hi[a] = n.split();
        expectAbove.lo[a] = n.split();
        EXPECT_EQ(t.extra[below].lo, expectBelow.lo);
        EXPECT_EQ(t.extra[below].hi, expectBelow.hi);
        EXPECT_EQ(t.extra[above].lo, expectAbove.lo);
        EXPECT_EQ(t.extra[above].hi, expectAbove.hi);
    }
    const double root = volume(t.extra[0]);
    EXPECT_NEAR(leafVolume, root, 1e-9 * root);
}

TEST(KdBuilder, RandomSoupInvariants) {
    const Scene s = test::randomSoup(7, 3000);
    const KdTree t = build(s);
    expectPartition(t);
    expectConservative(s, t);
    const KdTreeFigures f = measureTree(t, KdConfig{});
    EXPECT_GT(f.leaves, 100u) << "the SAH should split a 3000-triangle soup";
    EXPECT_LE(f.maxDepth, KdConfig{}.resolvedMaxDepth(s.triangles.size()));
    EXPECT_GT(f.duplicatedReferences(), 0u) << "straddling triangles are referenced on both sides";
}

TEST(KdBuilder, MeshAndCornellInvariants) {
    for (const Scene& s : {test::meshScene(), test::sceneFile("cornell.scene")}) {
        const KdTree t = build(s);
        expectPartition(t);
        expectConservative(s, t);
        // Every triangle is referenced at least once (none lost, flat walls included).
        std::set<uint32_t> referenced(t.indices.begin(), t.indices.end());
        EXPECT_EQ(referenced.size(), s.triangles.size());
    }
}

TEST(KdBuilder, DepthBoundHolds) {
    const Scene s = test::randomSoup(11, 2000);
    EXPECT_EQ(KdConfig{}.resolvedMaxDepth(1u << 20), 34);  // pbrt: 8 + 1.3 * 20
    for (int maxDepth : {1, 3, 6}) {
        KdConfig c;
        c.maxDepth = maxDepth;
        const KdTree t = build(s, 1, c);
        EXPECT_EQ(measureTree(t, c).maxDepth, maxDepth);
        expectConservative(s, t);
    }
}

// Flat geometry in a split plane: a stack of axis-aligned squares. Each lies in a plane the SAH
// wants to split at; none may be lost whichever side it goes to.
TEST(KdBuilder, TrianglesInSplitPlanesAreKept) {
    Scene s;
    for (int k = 0; k < 40; ++k) {
        const float z = float(k) * 0.25f;
        s.triangles.push_back({{0, 0, z}, {1, 0, z}, {1, 1, z}, 0});
        s.triangles.push_back({{0, 0, z}, {1, 1, z}, {0, 1, z}, 0});
    }
    const KdTree t = build(s);
    expectPartition(t);
    expectConservative(s, t);
    EXPECT_GT(measureTree(t, KdConfig{}).leaves, 4u);
    bool zSplitAtASquare = false;
    for (const gpu::KdNode& n : t.nodes)
        if (!n.isLeaf() && n.axis() == 2 && std::fmod(n.split(), 0.25f) == 0.0f) zSplitAtASquare = true;
    EXPECT_TRUE(zSplitAtASquare) << "expected splits in the squares' planes";
}

TEST(KdBuilder, EmptyAndDegenerateScenes) {
    Scene none;
    const KdTree empty = build(none);
    ASSERT_EQ(empty.nodes.size(), 1u);
    EXPECT_TRUE(empty.nodes[0].isLeaf());
    EXPECT_EQ(empty.nodes[0].triangleCount(), 0u);
    Scene degenerate;
    degenerate.triangles.push_back({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, 0});  // collinear
    EXPECT_TRUE(build(degenerate).indices.empty());
}

// The build writes no node boxes or parent links (four times the nodes' memory, for kd-backtrack
// alone); deriveNodeExtras makes the same for any thread count, and kd-backtrack's walk refuses a
// tree without them rather than read past an empty array.
TEST(KdBuilder, NodeExtrasOnlyWhenDerived) {
    const Scene s = test::randomSoup(5, 3000);
    KdTree t = buildSahKdTree(s.triangles, KdConfig{}, 2).tree;
    EXPECT_TRUE(t.extra.empty());
    EXPECT_THROW(makeKdTracer(Traversal::Backtrack, t, geometry::triangleVertices(s)), std::logic_error);
    KdTree other = t;
    deriveNodeExtras(t, 1);
    deriveNodeExtras(other, 2);
    ASSERT_EQ(t.extra.size(), t.nodes.size());
    EXPECT_TRUE(t == other);
    expectPartition(t);
    EXPECT_NE(makeKdTracer(Traversal::Backtrack, t, geometry::triangleVertices(s)), nullptr);
}

TEST(KdBuilder, SameTreeForAnyThreadCount) {
    Scene s = test::randomSoup(3, 6000);
    const Scene mesh = test::meshScene();
    s.triangles.insert(s.triangles.end(), mesh.triangles.begin(), mesh.triangles.end());
    const KdTree one = build(s, 1);
    for (int threads : {2, 4}) {
        const KdTree many = build(s, threads);
        EXPECT_TRUE(many == one) << threads << " threads built another tree";
    }
}

// Big random triangles crossing each other everywhere: the SAH alone would cut the space between
// them down to the depth limit, referencing most triangles in most cells.
Scene denseSoup(uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> inBox(0.0f, 1.0f), corner(-0.4f, 0.4f);
    Scene s;
    for (int k = 0; k < count; ++k) {
        const glm::vec3 c(inBox(rng), inBox(rng), inBox(rng));
        const auto vertex = [&] { return c + glm::vec3(corner(rng), corner(rng), corner(rng)); };
        s.triangles.push_back({vertex(), vertex(), vertex(), 0});
    }
    return s;
}

// The reference budget: at most maxDuplication references per triangle over the whole tree, and the
// tree still correct (a budget of 1 allows only splits that duplicate nothing: none in this soup).
TEST(KdBuilder, ReferenceBudgetBoundsTheTree) {
    const Scene s = denseSoup(17, 1500);
    KdConfig unbounded;
    unbounded.maxDuplication = 1e6;
    const KdTreeFigures free = measureTree(build(s, 1, unbounded), unbounded);
    EXPECT_GT(double(free.references), 8.0 * double(free.indexedTriangles))
        << "the soup should need the budget, or this test checks nothing";
    for (double budget : {1.0, 2.5, 8.0}) {
        KdConfig c;
        c.maxDuplication = budget;
        const KdTree t = build(s, 1, c);
        const KdTreeFigures f = measureTree(t, c);
        EXPECT_EQ(f.indexedTriangles, s.triangles.size());
        EXPECT_LE(double(f.references), budget * double(f.indexedTriangles)) << "budget " << budget;
        if (budget == 1.0) EXPECT_EQ(f.references, f.indexedTriangles);
        else EXPECT_GT(f.leaves, 1u) << "budget " << budget << ": splits that duplicate little are still made";
        expectPartition(t);
        expectConservative(s, t);
    }
}

// Nodes big enough to sweep and distribute their three axes as parallel tasks (more than 2^16
// events) build the same tree as one thread.
TEST(KdBuilder, SameTreeWithParallelAxes) {
    Scene s = test::randomSoup(9, 40000);
    const KdTree one = build(s, 1);
    EXPECT_TRUE(build(s, 2) == one);
}

TEST(KdBuilder, ProgressReachesTheEnd) {
    const Scene s = test::randomSoup(5, 4000);
    double last = -1.0;
    bool monotonic = true;
    std::set<std::string> phases;
    buildSahKdTree(s.triangles, KdConfig{}, 2, [&](const std::string& phase, double fraction) {
        phases.insert(phase);
        if (phase == "kd-tree: splitting") {
            monotonic = monotonic && fraction >= last;
            last = fraction;
        }
    });
    EXPECT_TRUE(monotonic);
    EXPECT_NEAR(last, 1.0, 0.011);
    EXPECT_EQ(phases.size(), 3u);
}

TEST(KdLayout, NodePackingRoundTrips) {
    const gpu::KdNode inner = gpu::KdNode::inner(2, -1.5f, 12345);
    EXPECT_FALSE(inner.isLeaf());
    EXPECT_EQ(inner.axis(), 2);
    EXPECT_EQ(inner.split(), -1.5f);
    EXPECT_EQ(inner.aboveChild(), 12345u);
    EXPECT_FALSE(inner.childEmpty(false));
    EXPECT_FALSE(inner.childEmpty(true));
    for (const bool below : {false, true})
        for (const bool above : {false, true}) {
            const gpu::KdNode n = gpu::KdNode::inner(1, 2.0f, VKRAY_KD_MAX_NODES - 1, below, above);
            EXPECT_EQ(n.axis(), 1);
            EXPECT_FALSE(n.isLeaf());
            EXPECT_EQ(n.aboveChild(), VKRAY_KD_MAX_NODES - 1);
            EXPECT_EQ(n.childEmpty(false), below);
            EXPECT_EQ(n.childEmpty(true), above);
        }
    const gpu::KdNode leaf = gpu::KdNode::leaf(77, (1u << 30) - 1);
    EXPECT_TRUE(leaf.isLeaf());
    EXPECT_EQ(leaf.firstIndex(), 77u);
    EXPECT_EQ(leaf.triangleCount(), (1u << 30) - 1);
    EXPECT_THROW(gpu::KdNode::inner(3, 0.0f, 1), std::length_error);
    EXPECT_THROW(gpu::KdNode::inner(0, 0.0f, VKRAY_KD_MAX_NODES), std::length_error);
    EXPECT_THROW(gpu::KdNode::leaf(0, 1u << 30), std::length_error);
}

size_t largestLeaf(const KdTree& t) {
    size_t largest = 0;
    for (const gpu::KdNode& n : t.nodes)
        if (n.isLeaf()) largest = std::max<size_t>(largest, n.triangleCount());
    return largest;
}

// With pbrt's empty-space bonus for any empty side, every node first peels slivers of empty space,
// one level each, and the depth limit ends a grid of small spheres (much empty space) with leaves of
// hundreds of triangles; with the bonus kept for empty sides of at least 10% of the node, the
// levels separate triangles.
TEST(KdBuilder, EmptySliversDoNotSpendTheDepthLimit) {
    const Scene s = test::sceneFromText("generate spheres 20000 1\n");
    KdConfig pbrt;
    pbrt.emptyBonusMinFraction = 0.0;
    const size_t withSlivers = largestLeaf(build(s, 2, pbrt)), withRule = largestLeaf(build(s, 2));
    std::printf("measured: largest leaf %zu (bonus for any empty side), %zu (empty sides >= 10%%)\n",
                withSlivers, withRule);
    EXPECT_LE(withRule * 10, withSlivers);
    EXPECT_LE(withRule, 8u);
}

TEST(KdConfig, DescribesItsConvention) {
    KdConfig c;
    c.intersectionCost = 80;
    EXPECT_EQ(c.describe(), "pbrt SAH: Ct=1 Ci=80 eb=0.5 for empty sides >= 0.1 of the node");
}

}  // namespace
}  // namespace vkray::accel::kd
