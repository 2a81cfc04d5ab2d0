// The BVH's CPU traversal against brute force, the ground truth: the same triangle and exactly the
// same t (ties at equal t to the lowest original index) for closest hits, the same answer for any
// hit, on random rays, on axis-parallel rays (direction components exactly +-0, many of them in
// the planes of axis-aligned walls) and on rays aimed exactly at vertices and edge points.
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/bvh_tracer.h"
#include "bvh_test_meshes.h"
#include "geometry/brute_force.h"

namespace vkray::bvh {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Presets {
    std::string name;
    Config config;
    bool stackless = false;
};

Config reinserted(Config c) {
    c.reinsertIterations = 20;
    return c;
}

Config spheres(Config c) {
    c.container = Config::Container::Sphere;
    return c;
}

std::vector<Presets> presets() {
    return {{"bvh", Config::aacHqRestructured()},
            {"bvh-fast", Config::aacFast()},
            {"bvh-hq", Config::aacHq()},
            {"bvh-sah", Config::binnedSah()},
            {"bvh reinserted", reinserted(Config::aacHqRestructured())},
            {"bvh-fast reinserted stackless", reinserted(Config::aacFast()), true},
            {"bvh-stackless", Config::aacHqRestructured(), true},
            {"bvh-fast stackless", Config::aacFast(), true},
            {"bvh-sphere", Config::aacHqSpheres()},
            {"bvh-fast spheres", spheres(Config::aacFast())}};
}

std::vector<geometry::Ray> randomRays(uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<geometry::Ray> rays;
    for (int k = 0; k < count; ++k) {
        glm::dvec3 d(u(rng), u(rng), u(rng));
        while (glm::length(d) < 1e-3) d = glm::dvec3(u(rng), u(rng), u(rng));
        // Origins inside and outside the meshes.
        rays.push_back({1.6 * glm::dvec3(u(rng), u(rng), u(rng)), glm::normalize(d)});
    }
    return rays;
}

// Rays along +-x, +-y, +-z (other components exactly 0 or -0): from random points, and from points
// whose coordinates are vertex coordinates of the scene, so that many run inside the planes of
// flat walls and along the edges of the grid.
std::vector<geometry::Ray> axisParallelRays(const Scene& scene, uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.5, 1.5);
    std::uniform_int_distribution<size_t> pick(0, scene.triangles.size() - 1);
    std::vector<geometry::Ray> rays;
    for (int k = 0; k < count; ++k) {
        const int axis = k % 3;
        const double sign = (k / 3) % 2 ? -1.0 : 1.0;
        glm::dvec3 dir(0.0);
        dir[axis] = sign;
        if (k % 4 == 1) dir[(axis + 1) % 3] = -0.0;  // negative zero must behave like zero
        if (k % 8 == 2) dir[(axis + 2) % 3] = -0.0;
        glm::dvec3 origin(u(rng), u(rng), u(rng));
        if (k % 2 == 0) {  // snap the two other coordinates to vertex coordinates
            const Triangle& t = scene.triangles[pick(rng)];
            origin[(axis + 1) % 3] = t.p0[(axis + 1) % 3];
            origin[(axis + 2) % 3] = (k % 6 == 0 ? t.p1 : t.p2)[(axis + 2) % 3];
        }
        origin[axis] = -2.5 * sign;  // start outside, travel through the scene
        if (k % 10 == 5) origin[axis] = 0.0;
        rays.push_back({origin, dir});
    }
    return rays;
}

// Rays whose (unnormalised) direction points exactly at a vertex or at an edge point: the watertight
// test's hardest cases, where two triangles share the answer.
std::vector<geometry::Ray> raysAtVerticesAndEdges(const Scene& scene, uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-2.0, 2.0);
    std::uniform_int_distribution<size_t> pick(0, scene.triangles.size() - 1);
    std::vector<geometry::Ray> rays;
    for (int k = 0; k < count; ++k) {
        const Triangle& t = scene.triangles[pick(rng)];
        const glm::dvec3 p0(t.p0), p1(t.p1), p2(t.p2);
        const glm::dvec3 target = k % 3 == 0 ? p0 : k % 3 == 1 ? 0.5 * (p0 + p1) : 0.25 * p1 + 0.75 * p2;
        glm::dvec3 origin(u(rng), u(rng), u(rng));
        if (k % 5 == 0) origin = glm::dvec3(u(rng) > 0 ? 2.5 : -2.5, target.y, target.z);  // axis-parallel
        if (origin == target) continue;
        rays.push_back({origin, target - origin});
    }
    return rays;
}

struct Agreement {
    int rays = 0, hits = 0, ties = 0;
};

// Compares closest and any hit for every ray with tmax = inf and with a tmax that cuts some hits.
void expectSameAsBruteForce(const geometry::Tracer& bvh, const geometry::BruteForceTracer& brute,
                            const std::vector<geometry::Ray>& rays, const std::vector<geometry::TriangleVertices>& tris,
                            Agreement& a) {
    for (const geometry::Ray& ray : rays) {
        for (double tmax : {kInf, 1.5}) {
            const geometry::Hit want = brute.closest(ray, tmax);
            const geometry::Hit got = bvh.closest(ray, tmax);
            ++a.rays;
            ASSERT_EQ(got.triangle, want.triangle)
                << "origin (" << ray.origin.x << ", " << ray.origin.y << ", " << ray.origin.z << ") dir ("
                << ray.dir.x << ", " << ray.dir.y << ", " << ray.dir.z << ") tmax " << tmax;
            ASSERT_EQ(got.t, want.t);
            ASSERT_EQ(got.b0, want.b0);
            ASSERT_EQ(got.b1, want.b1);
            ASSERT_EQ(got.b2, want.b2);
            ASSERT_EQ(bvh.occluded(ray, tmax), brute.occluded(ray, tmax));
            if (want.found()) {
                ++a.hits;
                // A tie: another triangle hit at exactly the same t (the BVH had to pick the same one).
                const geometry::WatertightRay w(ray);
                for (size_t k = 0; k < tris.size(); ++k)
                    if (int32_t(k) != want.triangle)
                        if (const auto h = w.intersect(tris[k], 0.0, tmax); h && h->t == want.t) {
                            ++a.ties;
                            break;
                        }
            }
        }
    }
}

TEST(BvhTracer, SameHitsAsBruteForce) {
    for (const test::NamedMesh& mesh : test::testMeshes()) {
        const std::vector<geometry::TriangleVertices> tris = geometry::triangleVertices(mesh.scene);
        const geometry::BruteForceTracer brute(mesh.scene);
        const std::vector<geometry::Ray> random = randomRays(101, 1500);
        const std::vector<geometry::Ray> axis = axisParallelRays(mesh.scene, 202, 1500);
        const std::vector<geometry::Ray> edges = raysAtVerticesAndEdges(mesh.scene, 303, 1500);
        for (const Presets& p : presets()) {
            SCOPED_TRACE(mesh.name + " / " + p.name);
            const FlatBvh flat = buildFlatBvh(mesh.scene.triangles, p.config).flat;
            const BvhTracer bvh(flat, mesh.scene.triangles, p.stackless);
            Agreement random_, axis_, edges_;
            expectSameAsBruteForce(bvh, brute, random, tris, random_);
            expectSameAsBruteForce(bvh, brute, axis, tris, axis_);
            expectSameAsBruteForce(bvh, brute, edges, tris, edges_);
            if (HasFatalFailure()) return;
            // The ray sets must exercise what they are for, or the comparison proves little.
            EXPECT_GT(random_.hits, random_.rays / 10);
            EXPECT_GT(axis_.hits, axis_.rays / 10);
            EXPECT_GT(edges_.hits, edges_.rays / 2);
            if (mesh.name != "equal_centroids") {
                EXPECT_GT(edges_.ties + axis_.ties, 10) << "shared edges";
            }
            if (mesh.name == "soup") {
                EXPECT_GT(random_.ties, 10) << "duplicate triangles";
            }
        }
    }
}

// Hapala et al.'s automaton tests the boxes the stack walk tests, in another order (fixed per node,
// not nearest first), so it finds the same hits; it climbs back through every node it left, so it
// takes more steps (each climb is one). On random rays through a sphere: the same answers, and no
// more than 4x the steps.
TEST(BvhTracer, StacklessWalkFindsTheSameHits) {
    const Scene s = test::uvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 60, 120);
    const FlatBvh flat = buildFlatBvh(s.triangles, Config::aacHqRestructured()).flat;
    const BvhTracer stack(flat, s.triangles), stackless(flat, s.triangles, true);
    geometry::TraversalCounters a, b;
    int hits = 0;
    for (const geometry::Ray& ray : randomRays(9, 1000)) {
        const geometry::Hit want = stack.closest(ray, kInf, &a), got = stackless.closest(ray, kInf, &b);
        ASSERT_EQ(got.triangle, want.triangle);
        ASSERT_EQ(got.t, want.t);
        ASSERT_EQ(stackless.occluded(ray, 1.0), stack.occluded(ray, 1.0));
        hits += want.found();
    }
    std::printf("steps: stack %llu, stackless %llu; leaves %llu, %llu\n", (unsigned long long)a.nodes,
                (unsigned long long)b.nodes, (unsigned long long)a.leaves, (unsigned long long)b.leaves);
    EXPECT_GT(hits, 200);
    EXPECT_GT(b.nodes, a.nodes);
    EXPECT_LT(b.nodes, 4 * a.nodes);
}

TEST(BvhTracer, CountsLessWorkThanBruteForce) {
    const Scene s = test::uvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 60, 120);
    const FlatBvh flat = buildFlatBvh(s.triangles, Config::aacHq()).flat;
    const BvhTracer bvh(flat, s.triangles);
    geometry::TraversalCounters c;
    int hits = 0;
    for (const geometry::Ray& ray : randomRays(7, 500)) hits += bvh.closest(ray, kInf, &c).found();
    EXPECT_GT(hits, 100);
    EXPECT_GT(c.nodes, 0u);
    EXPECT_GT(c.leaves, 0u);
    EXPECT_LE(c.leaves, c.nodes);
    // Far fewer triangle tests than brute force's one per triangle per ray.
    EXPECT_LT(c.triangles, 500u * s.triangles.size() / 20);
}

TEST(BvhTracer, EmptySceneMissesEverything) {
    const Scene empty;
    const FlatBvh flat = buildFlatBvh(empty.triangles, Config::aacFast()).flat;
    const BvhTracer bvh(flat, empty.triangles);
    const geometry::Ray ray{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
    EXPECT_FALSE(bvh.closest(ray, kInf).found());
    EXPECT_FALSE(bvh.occluded(ray, kInf));
}

}  // namespace
}  // namespace vkray::bvh
