// kd-stack, kd-restart and kd-backtrack against brute force: the same closest triangle (t within
// 1e-5 relative) and the same any-hit answer, on seeded random rays, axis-parallel rays (direction
// components exactly +0 and -0), rays lying in split planes, rays through mesh edges and vertices,
// rays through the corners where split planes meet, and the Cornell box, whose walls lie in the
// root box's faces. Plus the loop guarantees: each leaf visited once, and the iteration cap.
//
// Ties: brute force gives an exact tie in t to the lowest triangle index, and so do the kd tracers.
// A different triangle is accepted only as an explained tie: the brute-force ray hits it too, at the
// same t within 1e-12 relative (a shared edge or vertex whose two t values round differently; the
// tree references a triangle touching a split plane on one side only, so at a vertex the kd tracer
// may not test the fan triangle whose t rounds lowest); such cases are counted and printed, and
// must stay rare (rays aimed at vertices: up to 10%).
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/kd/kd_traversal.h"
#include "geometry/brute_force.h"
#include "kd_hand_trees.h"
#include "kd_test_util.h"
#include "kd_tracer_fixture.h"
#include "scene/camera.h"

namespace vkray::accel::kd {
namespace {

using test::Fixture;
using test::kInf;
using test::tracerFor;

struct Agreement {
    size_t rays = 0, hits = 0, ties = 0, capped = 0;
};

void expectSameClosest(const Fixture& f, const geometry::Ray& ray, double tmax, Agreement& a) {
    geometry::TraversalCounters c;
    const geometry::Hit want = f.brute->closest(ray, tmax);
    const geometry::Hit got = f.kd->closest(ray, tmax, &c);
    ++a.rays;
    a.capped += c.capped;
    if (want.found()) ++a.hits;
    if (got.triangle == want.triangle) {
        if (want.found()) {
            EXPECT_NEAR(got.t, want.t, 1e-5 * want.t);
        }
        return;
    }
    // Different triangle: only a tie explains it.
    ASSERT_TRUE(got.found() && want.found())
        << "origin (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") dir (" << ray.dir.x
        << ", " << ray.dir.y << ", " << ray.dir.z << "): kd " << got.triangle << " brute " << want.triangle;
    const auto again = geometry::intersectTriangle(ray, geometry::triangleVertices(f.scene)[size_t(got.triangle)], 0.0, tmax);
    ASSERT_TRUE(again.has_value());
    ASSERT_NEAR(again->t, want.t, 1e-12 * want.t) << "kd " << got.triangle << " brute " << want.triangle;
    ++a.ties;
}

void expectSameOccluded(const Fixture& f, const geometry::Ray& ray, double tmax) {
    EXPECT_EQ(f.kd->occluded(ray, tmax), f.brute->occluded(ray, tmax));
}

void report(const char* what, const Agreement& a, size_t tiesPerHundred = 1) {
    std::printf("%s: %zu rays, %zu hits, %zu ties, %zu capped\n", what, a.rays, a.hits, a.ties, a.capped);
    EXPECT_EQ(a.capped, 0u);
    EXPECT_LE(a.ties, a.rays * tiesPerHundred / 100 + 1) << "ties should be rare";
    EXPECT_GT(a.hits, a.rays / 10) << "a test whose rays miss everything proves nothing";
}

class KdTraversalTest : public ::testing::TestWithParam<kd::Traversal> {};

TEST_P(KdTraversalTest, RandomRaysMatchBruteForce) {
    const Fixture f(test::randomSoup(42, 2500), GetParam());
    std::mt19937 rng(1);
    Agreement a;
    for (int k = 0; k < 4000; ++k) {
        // Origins inside and outside the scene; every fourth ray has a finite tmax.
        const geometry::Ray ray{test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 1.6), test::randomDirection(rng)};
        const double tmax = k % 4 == 0 ? 0.05 + 2.0 * std::uniform_real_distribution<double>(0, 1)(rng) : kInf;
        expectSameClosest(f, ray, tmax, a);
        expectSameOccluded(f, ray, tmax);
    }
    report("random", a);
}

TEST_P(KdTraversalTest, AxisParallelRaysMatchBruteForce) {
    const Fixture f(test::meshScene(), GetParam());
    std::mt19937 rng(2);
    Agreement a;
    for (int k = 0; k < 3000; ++k) {
        const int axis = k % 3;
        glm::dvec3 dir(0.0);
        dir[axis] = (k / 3) % 2 ? 1.0 : -1.0;
        // The other components are +0 or -0: both must work (1 / -0 is -inf).
        if ((k / 6) % 2) dir[(axis + 1) % 3] = -0.0;
        if ((k / 12) % 2) dir[(axis + 2) % 3] = -0.0;
        glm::dvec3 o = test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 1.2);
        if (k % 5 == 0) o = glm::round(o * 4.0) / 4.0;  // on a grid: some coordinates hit vertices and planes
        expectSameClosest(f, {o, dir}, kInf, a);
        expectSameOccluded(f, {o, dir}, 1.0);
    }
    report("axis-parallel", a);
}

// Rays lying in a split plane of the tree: direction component 0 along the split axis, origin on
// the plane. They may hit triangles that merely touch the plane, which the builder puts on one side
// only: the traversals' side-mask passes must find them on either.
TEST_P(KdTraversalTest, RaysInSplitPlanesMatchBruteForce) {
    for (const Scene& s : {test::meshScene(), test::randomSoup(9, 1500)}) {
        const Fixture f(s, GetParam());
        std::mt19937 rng(3);
        Agreement a;
        for (uint32_t i = 0; i < f.tree.nodes.size() && a.rays < 6000; ++i) {
            const gpu::KdNode& n = f.tree.nodes[i];
            if (n.isLeaf()) continue;
            const gpu::KdNodeExtra& box = f.tree.extra[i];
            for (int r = 0; r < 6; ++r) {
                glm::dvec3 o = test::randomPointIn(rng, box.lo, box.hi, 1.0);
                o[n.axis()] = n.split();
                glm::dvec3 d = test::randomDirection(rng);
                d[n.axis()] = r % 2 ? 0.0 : -0.0;
                if (r == 4) d[(n.axis() + 1) % 3] = 0.0;  // also axis-parallel within the plane
                expectSameClosest(f, {o, d}, kInf, a);
                expectSameOccluded(f, {o, d}, kInf);
            }
        }
        report("in split planes", a);
    }
}

// Rays aimed exactly at mesh vertices and edge midpoints, where several triangles share the hit.
TEST_P(KdTraversalTest, RaysThroughEdgesAndVerticesMatchBruteForce) {
    const Fixture f(test::meshScene(), GetParam());
    std::mt19937 rng(4);
    Agreement a;
    for (size_t k = 0; k < f.scene.triangles.size(); k += 3) {
        const Triangle& t = f.scene.triangles[k];
        const glm::dvec3 targets[] = {glm::dvec3(t.p0), (glm::dvec3(t.p1) + glm::dvec3(t.p2)) * 0.5};
        for (const glm::dvec3& target : targets) {
            const glm::dvec3 o = test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 2.0);
            expectSameClosest(f, {o, glm::normalize(target - o)}, kInf, a);
        }
    }
    // A ray aimed at a mesh vertex hits every triangle of its fan at t equal up to the last bits;
    // brute force takes the smallest t of all, the tree tests only the fan triangles in the leaves
    // the ray passes (each triangle touching a split plane is on one side only). A different triangle
    // at the same t (1e-12) is the expected answer there, not a miss: allow up to 10% of the rays.
    report("edges and vertices", a, 10);
}

// Rays through the exact corners of leaves, where two or three split planes are crossed at the same
// t: kd-restart and kd-backtrack must step past each leaf exactly once (with `thit < tmin` instead
// of `thit <= tmin` the restart would enter the leaf it just left, forever). The three traversals
// visit the same leaves in the same order, so their leaf counts agree exactly.
TEST_P(KdTraversalTest, RaysThroughLeafCornersVisitEachLeafOnce) {
    const Fixture f(test::randomSoup(21, 2000), GetParam());
    const auto stack = makeKdTracer(kd::Traversal::Stack, f.tree, geometry::triangleVertices(f.scene));
    std::mt19937 rng(5);
    Agreement a;
    for (uint32_t i = 0; i < f.tree.nodes.size(); i += 7) {
        if (!f.tree.nodes[i].isLeaf()) continue;
        const gpu::KdNodeExtra& box = f.tree.extra[i];
        const glm::dvec3 corner(i % 2 ? box.lo.x : box.hi.x, i % 3 ? box.lo.y : box.hi.y, box.lo.z);
        // Directions of +-1 per axis, and an origin 3 steps back: the ray crosses x, y and z of the
        // corner at t = 3 exactly, with exactly equal plane hits.
        const glm::dvec3 d(rng() % 2 ? 1.0 : -1.0, rng() % 2 ? 1.0 : -1.0, rng() % 2 ? 1.0 : -1.0);
        const geometry::Ray ray{corner - 3.0 * d, d};
        geometry::TraversalCounters mine, base;
        f.kd->closest(ray, kInf, &mine);
        stack->closest(ray, kInf, &base);
        ASSERT_EQ(mine.capped, 0u);
        // kd-ropes compares fewer planes beyond the hit (only its ropes' nodes' own), so it may see
        // no tie there and walk fewer passes; KdRopes.SameLeavesAsRestart checks its leaves.
        if (GetParam() != kd::Traversal::Ropes) {
            ASSERT_EQ(mine.leaves, base.leaves) << "leaf " << i;
        }
        const geometry::TraversalCounters before = mine;
        f.kd->occluded(ray, kInf, &mine);
        ASSERT_EQ(mine.capped, before.capped);
        expectSameClosest(f, ray, kInf, a);
    }
    report("leaf corners", a);
}

TEST_P(KdTraversalTest, CornellBoxCameraAndInteriorRaysMatchBruteForce) {
    const Fixture f(test::sceneFile("cornell.scene"), GetParam());
    const CameraFrame cam = makeCameraFrame(f.scene.camera, 48, 48);
    Agreement a;
    for (int j = 0; j < cam.height; ++j)
        for (int i = 0; i < cam.width; ++i) expectSameClosest(f, {cam.eye, primaryDirection(cam, i, j)}, kInf, a);
    // From inside the box: every ray hits a wall, many along the walls' planes and edges.
    std::mt19937 rng(6);
    for (int k = 0; k < 3000; ++k) {
        glm::dvec3 o = test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 0.98);
        glm::dvec3 d = test::randomDirection(rng);
        if (k % 3 == 0) d[k % 2] = 0.0;
        if (k % 7 == 0) o.x = -1.0;  // in the red wall's plane (a root box face)
        expectSameClosest(f, {o, d}, kInf, a);
        expectSameOccluded(f, {o, d}, 0.5);
    }
    report("cornell", a);
}

// A malformed tree whose node 0 names itself as its above child: any ray crossing the plane loops
// for ever. The cap must end it, count it, and report a miss.
TEST_P(KdTraversalTest, IterationCapEndsAndCountsARunawayRay) {
    KdTree t;
    t.header = gpu::KdTreeHeader{{-1, -1, -1}, 2, {1, 1, 1}, 0};
    t.nodes = {gpu::KdNode::inner(0, 0.0f, 0), gpu::KdNode::leaf(0, 0)};
    t.extra = {gpu::KdNodeExtra{{-1, -1, -1}, VKRAY_KD_NO_PARENT, {1, 1, 1}, 0},
               gpu::KdNodeExtra{{-1, -1, -1}, 0, {0, 1, 1}, 0}};
    const auto tracer = tracerFor(GetParam(), t, {}, 500);
    const geometry::Ray ray{{-2.0, 0.1, 0.2}, {1.0, 0.0, 0.0}};
    geometry::TraversalCounters c;
    EXPECT_FALSE(tracer->closest(ray, kInf, &c).found());
    EXPECT_EQ(c.capped, 1u);
    EXPECT_LE(c.nodes, 500u);
    EXPECT_FALSE(tracer->occluded(ray, kInf, &c));
    EXPECT_EQ(c.capped, 2u);
    // A ray that never crosses the plane ends normally.
    geometry::TraversalCounters ok;
    tracer->closest({{-0.5, 0.0, 0.0}, {0.0, 1.0, 0.0}}, kInf, &ok);
    EXPECT_EQ(ok.capped, 0u);
}

// Counters: the stack traversal never restarts; the stackless ones restart once per leaf left; the
// short stack only when it ran dry (KdShortStack tests below).
TEST_P(KdTraversalTest, CountersAddUp) {
    const Fixture f(test::meshScene(), GetParam());
    std::mt19937 rng(8);
    geometry::TraversalCounters c;
    for (int k = 0; k < 500; ++k)
        f.kd->closest({test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 1.0), test::randomDirection(rng)},
                      kInf, &c);
    EXPECT_GE(c.nodes, c.leaves);
    EXPECT_GT(c.leaves, 500u);
    EXPECT_GT(c.triangles, 0u);
    if (GetParam() == kd::Traversal::Stack || GetParam() == kd::Traversal::Ropes) {
        EXPECT_EQ(c.restarts, 0u);
    } else if (GetParam() != kd::Traversal::ShortStack) {
        EXPECT_GT(c.restarts, 0u);
    }
}

// A near child flagged as an empty leaf is passed, not visited: the walk goes on from the plane in
// the far child (no leaf step, restart, climb or pop for it). Unflagged, the same tree visits it.
TEST_P(KdTraversalTest, EmptyNearChildIsPassed) {
    Scene scene;
    scene.triangles = {{{0.5f, -1, -1}, {0.5f, 1, -1}, {0.5f, 0, 1}, 0}};  // in the above leaf, x = 0.5
    for (const bool flagged : {true, false}) {
        KdTree t;
        t.header = gpu::KdTreeHeader{{-1, -1, -1}, 3, {1, 1, 1}, 1};
        t.nodes = {gpu::KdNode::inner(0, 0.0f, 2, flagged, false), gpu::KdNode::leaf(0, 0), gpu::KdNode::leaf(0, 1)};
        t.indices = {0};
        t.extra = {gpu::KdNodeExtra{{-1, -1, -1}, VKRAY_KD_NO_PARENT, {1, 1, 1}, 0},
                   gpu::KdNodeExtra{{-1, -1, -1}, 0, {0, 1, 1}, 0}, gpu::KdNodeExtra{{0, -1, -1}, 0, {1, 1, 1}, 0}};
        const auto kd = tracerFor(GetParam(), t, geometry::triangleVertices(scene));
        geometry::TraversalCounters c;
        const geometry::Hit hit = kd->closest({{-2.0, 0.1, 0.0}, {1.0, 0.0, 0.0}}, kInf, &c);
        EXPECT_EQ(hit.triangle, 0);
        EXPECT_DOUBLE_EQ(hit.t, 2.5);
        EXPECT_EQ(c.leaves, flagged ? 1u : 2u) << (flagged ? "flagged" : "unflagged");
        // Unflagged: root, empty leaf, then the pop (stack), the rope straight to the far leaf (ropes),
        // a restart at the root (restart), or a climbing step at the root and the root again
        // (backtrack), and the far leaf. (push-down: the root reached both children, so the restart
        // begins at the root too)
        const bool stack = GetParam() == kd::Traversal::Stack || GetParam() == kd::Traversal::ShortStack;
        const bool ropes = GetParam() == kd::Traversal::Ropes;
        const uint32_t unflagged = stack || ropes ? 3u : GetParam() == kd::Traversal::Backtrack ? 5u : 4u;
        EXPECT_EQ(c.nodes, flagged ? 2u : unflagged);
        EXPECT_EQ(c.restarts, flagged || stack || ropes ? 0u : 1u);
        // Going the other way the empty leaf lies beyond the triangle: never reached.
        geometry::TraversalCounters back;
        EXPECT_EQ(kd->closest({{2.0, 0.1, 0.0}, {-1.0, 0.0, 0.0}}, kInf, &back).triangle, 0);
        EXPECT_EQ(back.leaves, 1u);
    }
}

// Push-down restarts below the root, never above what a restart from the root would reach: the same
// hits, leaves and restarts as kd-restart on every ray, fewer node steps in all.
TEST(KdPushDown, SameWalkAsRestartInFewerSteps) {
    const Fixture f(test::meshScene(), kd::Traversal::PushDown);
    const auto restart = makeKdTracer(kd::Traversal::Restart, f.tree, geometry::triangleVertices(f.scene));
    std::mt19937 rng(13);
    geometry::TraversalCounters pushed, rooted;
    for (int k = 0; k < 2000; ++k) {
        const geometry::Ray ray{test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 1.0), test::randomDirection(rng)};
        geometry::TraversalCounters a, b;
        const geometry::Hit got = f.kd->closest(ray, kInf, &a), want = restart->closest(ray, kInf, &b);
        ASSERT_EQ(got.triangle, want.triangle) << "ray " << k;
        ASSERT_EQ(got.t, want.t) << "ray " << k;
        ASSERT_EQ(a.leaves, b.leaves) << "ray " << k;
        ASSERT_EQ(a.restarts, b.restarts) << "ray " << k;
        ASSERT_LE(a.nodes, b.nodes) << "ray " << k;
        pushed.nodes += a.nodes;
        rooted.nodes += b.nodes;
        rooted.restarts += b.restarts;
    }
    ASSERT_GT(rooted.restarts, 0u);
    std::printf("node steps: push-down %llu, restart %llu\n", (unsigned long long)pushed.nodes,
                (unsigned long long)rooted.nodes);
    EXPECT_LT(pushed.nodes, rooted.nodes);
}

// The short stack between the two ends: with room for the whole depth it is the full stack (the
// same walk, no restart); with one entry it runs dry and restarts, and still finds the same hits;
// its node steps lie between the full stack's and push-down's.
TEST(KdShortStack, BetweenTheFullStackAndPushDown) {
    const Fixture f(test::meshScene(), kd::Traversal::ShortStack);
    const auto vertices = geometry::triangleVertices(f.scene);
    const auto full = makeKdTracer(kd::Traversal::Stack, f.tree, vertices);
    const auto deep = makeKdTracer(kd::Traversal::ShortStack, f.tree, vertices, VKRAY_KD_MAX_STEPS, VKRAY_KD_STACK_SIZE);
    const auto one = makeKdTracer(kd::Traversal::ShortStack, f.tree, vertices, VKRAY_KD_MAX_STEPS, 1);
    const auto pushDown = makeKdTracer(kd::Traversal::PushDown, f.tree, vertices);
    std::mt19937 rng(17);
    geometry::TraversalCounters cFull, cDeep, cOne, cDefault, cPush;
    for (int k = 0; k < 2000; ++k) {
        const geometry::Ray ray{test::randomPointIn(rng, f.tree.header.lo, f.tree.header.hi, 1.0), test::randomDirection(rng)};
        const geometry::Hit want = full->closest(ray, kInf, &cFull);
        for (const auto& [tracer, counters] : {std::pair{deep.get(), &cDeep}, std::pair{one.get(), &cOne},
                                               std::pair{f.kd.get(), &cDefault}, std::pair{pushDown.get(), &cPush}}) {
            const geometry::Hit got = tracer->closest(ray, kInf, counters);
            ASSERT_EQ(got.triangle, want.triangle) << "ray " << k;
            ASSERT_EQ(got.t, want.t) << "ray " << k;
        }
    }
    std::printf("node steps: stack %llu, short stack 4 %llu (%llu restarts), 1 %llu (%llu), push-down %llu\n",
                (unsigned long long)cFull.nodes, (unsigned long long)cDefault.nodes,
                (unsigned long long)cDefault.restarts, (unsigned long long)cOne.nodes,
                (unsigned long long)cOne.restarts, (unsigned long long)cPush.nodes);
    EXPECT_EQ(cDeep.nodes, cFull.nodes);
    EXPECT_EQ(cDeep.leaves, cFull.leaves);
    EXPECT_EQ(cDeep.restarts, 0u);
    EXPECT_GT(cOne.restarts, 0u);
    EXPECT_GE(cDefault.nodes, cFull.nodes);
    EXPECT_LE(cDefault.nodes, cOne.nodes);
    EXPECT_LT(cOne.nodes, cPush.nodes);
}

// The hand-made trees of kd_hand_trees.h: rays lying in split planes, a decoy on the other side.
TEST_P(KdTraversalTest, RayInSplitPlaneFindsTriangleTouchingItFromAbove) {
    test::HandTree h = test::triangleTouchingThePlaneFromAbove();
    const auto kd = tracerFor(GetParam(), h.tree, geometry::triangleVertices(h.scene));
    const geometry::BruteForceTracer brute(h.scene);
    for (const double dx : {0.0, -0.0}) {
        const geometry::Ray ray{h.ray.origin, {dx, h.ray.dir.y, h.ray.dir.z}};
        const geometry::Hit want = brute.closest(ray, kInf);
        ASSERT_EQ(want.triangle, 0);
        const geometry::Hit got = kd->closest(ray, kInf);
        EXPECT_EQ(got.triangle, 0);
        EXPECT_EQ(got.t, want.t);
        EXPECT_TRUE(kd->occluded(ray, h.clearOf));  // only triangle 0 lies before it
    }
}

TEST_P(KdTraversalTest, RayAlongTwoSplitPlanesNeedsFourPasses) {
    test::HandTree h = test::rayAlongTwoSplitPlanes();
    const auto kd = tracerFor(GetParam(), h.tree, geometry::triangleVertices(h.scene));
    const geometry::BruteForceTracer brute(h.scene);
    const geometry::Hit want = brute.closest(h.ray, kInf);
    ASSERT_EQ(want.triangle, 0);
    geometry::TraversalCounters c;
    const geometry::Hit got = kd->closest(h.ray, kInf, &c);
    EXPECT_EQ(got.triangle, 0);
    EXPECT_EQ(got.t, want.t);
    EXPECT_EQ(c.leaves, 4u) << "one leaf per side mask";
    EXPECT_EQ(c.capped, 0u);
    EXPECT_TRUE(kd->occluded(h.ray, h.clearOf));  // only triangle 0 lies before it
    EXPECT_FALSE(kd->occluded(h.ray, 1.5));
}

TEST(KdClip, ZeroDirectionComponentsNeverMakeNaN) {
    const glm::vec3 lo(0, 0, 0), hi(1, 1, 1);
    // Origin on the box's face, moving along it: inside (closed box), no 0 * inf.
    const auto s = clipToBox({{0.0, 0.5, 0.5}, {0.0, 1.0, -0.0}}, lo, hi, {0.0, kInf});
    ASSERT_TRUE(s.has_value());
    EXPECT_EQ(s->tmin, 0.0);
    EXPECT_EQ(s->tmax, 0.5);
    EXPECT_FALSE(clipToBox({{-0.001, 0.5, 0.5}, {-0.0, 1.0, 0.0}}, lo, hi, {0.0, kInf}).has_value());
}

INSTANTIATE_TEST_SUITE_P(Traversals, KdTraversalTest,
                         ::testing::Values(kd::Traversal::Stack, kd::Traversal::Restart, kd::Traversal::Backtrack,
                                           kd::Traversal::PushDown, kd::Traversal::ShortStack, kd::Traversal::Ropes),
                         [](const auto& info) {
                             switch (info.param) {
                             case kd::Traversal::Stack: return std::string("Stack");
                             case kd::Traversal::Restart: return std::string("Restart");
                             case kd::Traversal::Backtrack: return std::string("Backtrack");
                             case kd::Traversal::PushDown: return std::string("PushDown");
                             case kd::Traversal::ShortStack: return std::string("ShortStack");
                             case kd::Traversal::Ropes: return std::string("Ropes");
                             case kd::Traversal::Packet: return std::string("Packet");  // the GPU's; on the CPU, Stack's walk
                             }
                             return std::string("Unknown");
                         });

}  // namespace
}  // namespace vkray::accel::kd
