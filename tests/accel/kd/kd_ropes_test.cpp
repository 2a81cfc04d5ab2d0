// kd-ropes (Popov, Guenther, Seidel and Slusallek 2007) on the CPU: the ropes the builder links
// (each the smallest node beyond its leaf's face), and the walk along them against kd-restart's,
// which visits the same leaves by restarting from the root: the same hits and leaves on random rays
// and on rays through leaf corners, in fewer node steps. kd_traversal_test.cpp checks kd-ropes with
// every other traversal against brute force.
#include <cstdio>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "accel/kd/kd_ropes.h"
#include "accel/kd/kd_traversal.h"
#include "kd_test_util.h"
#include "kd_tracer_fixture.h"

namespace vkray::accel::kd {
namespace {

using test::Fixture;
using test::kInf;

// Every leaf a walk reaches, with its exit, in order (all passes; never stops).
class LeafLog final : public LeafVisitor {
public:
    explicit LeafLog(const KdTree& tree) : tree_(tree) {}
    bool visit(const gpu::KdNode& leaf, double exit) override {
        leaves.push_back({uint32_t(&leaf - tree_.nodes.data()), exit});
        return false;
    }
    std::vector<std::pair<uint32_t, double>> leaves;

private:
    const KdTree& tree_;
};

// kd-restart's leaves along the whole ray in kd-restart's order, with in between only leaves that
// hold no triangle (ropes lead onto empty leaves that kd-restart passes by their parents' flags) or
// that the ray crosses in no length (a leaf thinner than the rounding of t, which kd-restart's
// descent steps over); counts those in `extra`.
void expectLeavesOfRestart(const KdTree& tree, const KdTracer& ropes, const KdTracer& restart, const geometry::Ray& ray,
                           size_t& extra) {
    geometry::TraversalCounters unused;
    LeafLog mine(tree), theirs(tree);
    ropes.walk(ray, {0.0, kInf}, mine, unused);
    restart.walk(ray, {0.0, kInf}, theirs, unused);
    size_t j = 0;
    double lastExit = 0.0;
    for (const auto& [leaf, exit] : mine.leaves) {
        if (j < theirs.leaves.size() && theirs.leaves[j].first == leaf) {
            ASSERT_EQ(theirs.leaves[j].second, exit) << "leaf " << leaf;
            ++j;
        } else {
            ASSERT_TRUE(tree.nodes[leaf].triangleCount() == 0 || exit == lastExit) << "leaf " << leaf;
            ++extra;
        }
        lastExit = exit;
    }
    ASSERT_EQ(j, theirs.leaves.size()) << "a leaf of kd-restart's walk was not reached";
}

// Ropes go on from a leaf where a restart from the root would arrive: the same hits as kd-restart
// and its leaves (expectLeavesOfRestart); no restart, and fewer node steps than kd-restart and
// kd-stack in all.
TEST(KdRopes, SameLeavesAsRestartInFewerSteps) {
    const Fixture f(test::meshScene(), kd::Traversal::Ropes);
    const auto vertices = geometry::triangleVertices(f.scene);
    const auto restart = makeKdTracer(kd::Traversal::Restart, f.tree, vertices);
    const auto stack = makeKdTracer(kd::Traversal::Stack, f.tree, vertices);
    std::mt19937 rng(19);
    geometry::TraversalCounters roped, rooted, stacked;
    size_t extra = 0;
    for (int k = 0; k < 2000; ++k) {
        const geometry::Ray ray{test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 1.0), test::randomDirection(rng)};
        geometry::TraversalCounters a, b;
        const geometry::Hit got = f.kd->closest(ray, kInf, &a), want = restart->closest(ray, kInf, &b);
        stack->closest(ray, kInf, &stacked);
        ASSERT_EQ(got.triangle, want.triangle) << "ray " << k;
        ASSERT_EQ(got.t, want.t) << "ray " << k;
        ASSERT_EQ(a.restarts, 0u) << "ray " << k;
        SCOPED_TRACE("ray " + std::to_string(k));
        expectLeavesOfRestart(f.tree, *f.kd, *restart, ray, extra);
        if (HasFatalFailure()) return;
        roped.nodes += a.nodes;
        rooted.nodes += b.nodes;
    }
    std::printf("node steps: ropes %llu, restart %llu, stack %llu; %zu leaves beyond kd-restart's\n",
                (unsigned long long)roped.nodes, (unsigned long long)rooted.nodes, (unsigned long long)stacked.nodes, extra);
    EXPECT_LT(roped.nodes, rooted.nodes);
    EXPECT_LT(roped.nodes, stacked.nodes);
}

// Rays through the exact corners of leaves (as in RaysThroughLeafCornersVisitEachLeafOnce: two or
// three split planes crossed at the same t), where a leaf may be left through an edge or corner in
// no length and the rope's node is entered without a test of its near faces only when that cannot
// be wrong (ropeHoldsExit): still kd-restart's hits and leaves.
TEST(KdRopes, SameLeavesAsRestartThroughLeafCorners) {
    const Fixture f(test::randomSoup(21, 2000), kd::Traversal::Ropes);
    const auto restart = makeKdTracer(kd::Traversal::Restart, f.tree, geometry::triangleVertices(f.scene));
    std::mt19937 rng(5);
    size_t rays = 0, extra = 0;
    geometry::TraversalCounters roped;
    for (uint32_t i = 0; i < f.tree.nodes.size(); ++i) {
        if (!f.tree.nodes[i].isLeaf()) continue;
        const gpu::KdNodeExtra& box = f.tree.extra[i];
        const glm::dvec3 corner(rng() % 2 ? box.lo.x : box.hi.x, rng() % 2 ? box.lo.y : box.hi.y,
                                rng() % 2 ? box.lo.z : box.hi.z);
        const glm::dvec3 d(rng() % 2 ? 1.0 : -1.0, rng() % 2 ? 1.0 : -1.0, rng() % 2 ? 1.0 : -1.0);
        const geometry::Ray ray{corner - 3.0 * d, d};
        const geometry::Hit got = f.kd->closest(ray, kInf, &roped), want = restart->closest(ray, kInf);
        ASSERT_EQ(got.triangle, want.triangle) << "leaf " << i;
        ASSERT_EQ(got.t, want.t) << "leaf " << i;
        SCOPED_TRACE("corner of leaf " + std::to_string(i));
        expectLeavesOfRestart(f.tree, *f.kd, *restart, ray, extra);
        if (HasFatalFailure()) return;
        ++rays;
    }
    ASSERT_EQ(roped.capped, 0u);
    EXPECT_GT(roped.restarts, 0u);  // some leave a leaf through its edge in no length: the restart is taken
    std::printf("%zu rays through leaf corners: %llu restarts, %zu leaves beyond kd-restart's\n", rays,
                (unsigned long long)roped.restarts, extra);
}

// Every rope of every leaf names the smallest node beyond its face: a node whose box starts at the
// face's plane, holds the whole face, and is a leaf or split by a plane the face straddles; none on
// the root box's faces.
TEST(KdRopes, EachRopeIsTheSmallestNodeBeyondItsFace) {
    const Fixture f(test::randomSoup(23, 3000), kd::Traversal::Ropes);
    const KdTree& t = f.tree;
    size_t ropes = 0, none = 0;
    for (uint32_t i = 0; i < t.nodes.size(); ++i) {
        if (!t.nodes[i].isLeaf()) {  // a rope may lead here: its box, no ropes of its own
            ASSERT_EQ(t.ropes[i].lo, t.nodeBox(i).lo);
            ASSERT_EQ(t.ropes[i].hi, t.nodeBox(i).hi);
            for (int face = 0; face < 6; ++face) ASSERT_EQ(gpu::kdRope(t.ropes[i], face), VKRAY_KD_NO_ROPE);
            continue;
        }
        const Box leaf = t.nodeBox(i);
        ASSERT_EQ(t.ropes[i].lo, leaf.lo);
        ASSERT_EQ(t.ropes[i].hi, leaf.hi);
        for (int face = 0; face < 6; ++face) {
            const int axis = face / 2;
            const bool hi = face % 2 == 1;
            const float c = hi ? leaf.hi[axis] : leaf.lo[axis];
            const uint32_t r = gpu::kdRope(t.ropes[i], face);
            ASSERT_EQ(r, ropeOf(t, leaf, face)) << "leaf " << i << " face " << face << ": top-down and per-leaf differ";
            if (c == (hi ? t.header.hi[axis] : t.header.lo[axis])) {
                ASSERT_EQ(r, VKRAY_KD_NO_ROPE) << "leaf " << i << " face " << face;
                ++none;
                continue;
            }
            ASSERT_LT(r, t.nodes.size()) << "leaf " << i << " face " << face;
            const Box box = t.nodeBox(r);
            ASSERT_EQ(hi ? box.lo[axis] : box.hi[axis], c) << "leaf " << i << " face " << face;
            for (int a = 0; a < 3; ++a) {
                if (a == axis) continue;
                ASSERT_LE(box.lo[a], leaf.lo[a]) << "leaf " << i << " face " << face;
                ASSERT_GE(box.hi[a], leaf.hi[a]) << "leaf " << i << " face " << face;
            }
            const gpu::KdNode& n = t.nodes[r];
            if (!n.isLeaf()) {
                ASSERT_NE(n.axis(), axis) << "leaf " << i << " face " << face << ": could go one level down";
                ASSERT_LT(leaf.lo[n.axis()], n.split()) << "leaf " << i << " face " << face;
                ASSERT_GT(leaf.hi[n.axis()], n.split()) << "leaf " << i << " face " << face;
            }
            ++ropes;
        }
    }
    std::printf("%zu ropes, %zu faces on the root box\n", ropes, none);
    EXPECT_GT(ropes, 1000u);
    EXPECT_GT(none, 0u);
}

}  // namespace
}  // namespace vkray::accel::kd
