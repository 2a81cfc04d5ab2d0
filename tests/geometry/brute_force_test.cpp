// The brute-force tracer against a naive loop written independently here: the closest hit is the
// smallest t over all triangles, ties to the lowest index; occluded() is "some hit in (0, tmax)".
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/brute_force.h"
#include "support/scene_builder.h"

namespace vkray::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Moeller and Trumbore (JGT 1997), a different algorithm than the watertight one under test: used
// to confirm t values away from edges, where both must agree.
std::optional<double> mollerTrumbore(const Ray& r, const TriangleVertices& tri, double* margin) {
    const glm::dvec3 e1 = tri[1] - tri[0], e2 = tri[2] - tri[0];
    const glm::dvec3 p = glm::cross(r.dir, e2);
    const double det = glm::dot(e1, p);
    if (det == 0.0) return std::nullopt;
    const glm::dvec3 s = r.origin - tri[0];
    const double u = glm::dot(s, p) / det;
    const glm::dvec3 q = glm::cross(s, e1);
    const double v = glm::dot(r.dir, q) / det;
    *margin = std::min({u, v, 1.0 - u - v});  // distance to the nearest edge, in barycentrics
    if (*margin < 0.0) return std::nullopt;
    const double t = glm::dot(e2, q) / det;
    return t > 0.0 ? std::optional<double>(t) : std::nullopt;
}

struct Soup {
    std::vector<TriangleVertices> triangles;
    std::vector<Ray> rays;
};

// Random triangles in [-1, 1]^3 with some exact duplicates (ties in t), random rays from [-2, 2]^3.
Soup randomSoup(uint32_t seed, int triangles, int rays) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> inBox(-1.0, 1.0), dir(-1.0, 1.0);
    Soup soup;
    for (int k = 0; k < triangles; ++k) {
        if (k % 10 == 9) {
            soup.triangles.push_back(soup.triangles[size_t(k) - 1]);
            continue;
        }
        const glm::dvec3 c(inBox(rng), inBox(rng), inBox(rng));
        TriangleVertices t;
        for (glm::dvec3& p : t) p = c + 0.3 * glm::dvec3(inBox(rng), inBox(rng), inBox(rng));
        soup.triangles.push_back(t);
    }
    for (int k = 0; k < rays; ++k) {
        glm::dvec3 d(dir(rng), dir(rng), dir(rng));
        while (glm::length(d) < 1e-3) d = glm::dvec3(dir(rng), dir(rng), dir(rng));
        soup.rays.push_back({2.0 * glm::dvec3(inBox(rng), inBox(rng), inBox(rng)), glm::normalize(d)});
    }
    return soup;
}

TEST(BruteForce, ClosestMatchesNaiveSearch) {
    const Soup soup = randomSoup(1234, 300, 3000);
    const BruteForceTracer tracer(soup.triangles);
    int hits = 0, ties = 0, confirmed = 0;
    for (const Ray& ray : soup.rays) {
        // Naive: every hit as a (t, index) pair; the closest is the smallest pair.
        std::vector<std::pair<double, int32_t>> all;
        for (size_t k = 0; k < soup.triangles.size(); ++k)
            if (const auto h = intersectTriangle(ray, soup.triangles[k], 0.0, kInf))
                all.emplace_back(h->t, int32_t(k));
        const auto smallest = std::min_element(all.begin(), all.end());
        const int32_t best = smallest == all.end() ? -1 : smallest->second;
        const double bestT = smallest == all.end() ? kInf : smallest->first;
        ties += std::count_if(all.begin(), all.end(), [&](auto& h) { return h.first == bestT; }) > 1;
        const Hit hit = tracer.closest(ray, kInf);
        ASSERT_EQ(hit.triangle, best);
        if (best < 0) {
            EXPECT_EQ(hit.t, kInf);
            continue;
        }
        ++hits;
        EXPECT_EQ(hit.t, bestT);
        const auto exact = intersectTriangle(ray, soup.triangles[size_t(best)], 0.0, kInf);
        EXPECT_EQ(hit.b0, exact->b0);
        EXPECT_EQ(hit.b1, exact->b1);
        EXPECT_EQ(hit.b2, exact->b2);
        // Away from edges, an independent algorithm finds the same t.
        double margin = 0.0;
        const auto mt = mollerTrumbore(ray, soup.triangles[size_t(best)], &margin);
        if (margin > 1e-6) {
            ASSERT_TRUE(mt);
            EXPECT_NEAR(*mt, hit.t, 1e-9 * std::max(1.0, hit.t));
            ++confirmed;
        }
    }
    EXPECT_GT(hits, 300);     // the test exercises hits, not only misses
    EXPECT_GT(ties, 10);      // and ties between the duplicated triangles
    EXPECT_GT(confirmed, 300);
}

TEST(BruteForce, TiesGoToLowestIndex) {
    const TriangleVertices tri{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
    const TriangleVertices farther{glm::dvec3(0, 0, -1), glm::dvec3(1, 0, -1), glm::dvec3(0, 1, -1)};
    const BruteForceTracer tracer({farther, tri, tri, farther});
    const Hit hit = tracer.closest({{0.25, 0.25, 1.0}, {0, 0, -1}}, kInf);
    EXPECT_EQ(hit.triangle, 1);
    EXPECT_EQ(hit.t, 1.0);
    // Two halves of a square meeting at the ray: the lower index wins.
    Scene scene = test::sceneLookingDownZ();
    test::addSquare(scene, 0.0f, 1.0f, true, 0);
    const Hit diagonal = BruteForceTracer(scene).closest({{0.0, 0.0, 1.0}, {0, 0, -1}}, kInf);
    EXPECT_EQ(diagonal.triangle, 0);
}

TEST(BruteForce, TmaxLimitsClosestHit) {
    const TriangleVertices tri{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};
    const BruteForceTracer tracer({tri});
    EXPECT_FALSE(tracer.closest({{0.25, 0.25, 1.0}, {0, 0, -1}}, 1.0).found());
    EXPECT_TRUE(tracer.closest({{0.25, 0.25, 1.0}, {0, 0, -1}}, 1.5).found());
    EXPECT_FALSE(BruteForceTracer(std::vector<TriangleVertices>{}).closest({{0, 0, 0}, {0, 0, -1}}, kInf).found());
}

TEST(BruteForce, OccludedMatchesNaiveSearch) {
    const Soup soup = randomSoup(99, 200, 3000);
    const BruteForceTracer tracer(soup.triangles);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> length(0.0, 4.0);
    int blocked = 0, clear = 0;
    for (const Ray& ray : soup.rays) {
        const double tmax = length(rng);
        bool naive = false;
        for (const TriangleVertices& tri : soup.triangles) {
            const auto h = intersectTriangle(ray, tri, 0.0, kInf);
            naive = naive || (h && h->t < tmax);
        }
        ASSERT_EQ(tracer.occluded(ray, tmax), naive);
        (naive ? blocked : clear)++;
    }
    EXPECT_GT(blocked, 100);
    EXPECT_GT(clear, 100);
}

TEST(BruteForce, SceneTrianglesAreWidenedInOrder) {
    Scene scene = test::sceneLookingDownZ();
    scene.triangles.push_back({{0.1f, 0.2f, 0.3f}, {1, 0, 0}, {0, 1, 0}, 0});
    scene.triangles.push_back({{5, 6, 7}, {8, 9, 10}, {11, 12, 14}, 0});
    const std::vector<TriangleVertices> v = triangleVertices(scene);
    ASSERT_EQ(v.size(), 2u);
    EXPECT_EQ(v[0][0].x, double(0.1f));  // the float value, not 0.1
    EXPECT_EQ(v[1][2], glm::dvec3(11, 12, 14));
}

}  // namespace
}  // namespace vkray::geometry
