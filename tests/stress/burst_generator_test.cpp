// `generate burst N` (scene/generators.h), the stress case for the BVH builders: every
// triangle has exactly the same centroid as the builders compute it, so every Morton code is equal,
// and no triangle is degenerate. The AAC builder must still make a valid tree that traces like
// brute force (stress_cases_test.cpp renders burst-100k.scene with every accelerator).
#include <gtest/gtest.h>

#include "accel/bvh/morton.h"
#include "accel/bvh/primitives.h"
#include "geometry/ray_triangle.h"
#include "scene/generators.h"
#include "scene/scene_builder.h"

namespace vkray {
namespace {

Scene burst(int64_t n, uint64_t seed) {
    Scene s;
    SceneBuilder out(s);
    EXPECT_TRUE(generateMesh({GeneratorKind::Burst, n, seed}, Transform(), out.material(Material{}), out));
    return s;
}

TEST(BurstGenerator, EveryCentroidAndMortonCodeIsTheSame) {
    const Scene s = burst(20000, 3);
    ASSERT_EQ(s.triangles.size(), 20000u);
    const bvh::PrimitiveSet prims = bvh::primitivesOf(s.triangles);
    // The builders' own centroid, (p0 + p1 + p2) / 3 in float, is the centre for every triangle.
    for (const glm::vec3& c : prims.centroids) ASSERT_EQ(c, glm::vec3(0.0f, 0.5f, 0.0f));
    EXPECT_EQ(prims.centroidBounds.lo, prims.centroidBounds.hi);
    const BuildArray<bvh::MortonKey> keys = bvh::mortonKeys(prims.centroids, prims.centroidBounds);
    for (bvh::MortonKey key : keys) ASSERT_EQ(bvh::keyCode(key), bvh::keyCode(keys.front()));
}

// (tests/scene/generators_test.cpp checks the other kinds the same way.)
TEST(BurstGenerator, ExactlyNTrianglesSameSeedSameTriangles) {
    for (int64_t n : {int64_t(1), int64_t(7), int64_t(1000)}) {
        EXPECT_EQ(generatedTriangleCount({GeneratorKind::Burst, n, 1}), n);
        EXPECT_EQ(int64_t(burst(n, 1).triangles.size()), n);
    }
    const Scene a = burst(500, 9), b = burst(500, 9), c = burst(500, 10);
    bool allSame = true, anyDifferent = false;
    for (size_t i = 0; i < a.triangles.size(); ++i) {
        allSame = allSame && a.triangles[i].p0 == b.triangles[i].p0 && a.triangles[i].p1 == b.triangles[i].p1;
        anyDifferent = anyDifferent || a.triangles[i].p0 != c.triangles[i].p0;
    }
    EXPECT_TRUE(allSame);
    EXPECT_TRUE(anyDifferent);
}

TEST(BurstGenerator, NoDegenerateTrianglesAndSizesSpanEightOctaves) {
    const Scene s = burst(5000, 1);
    float smallest = 1e30f, largest = 0.0f;
    for (const Triangle& t : s.triangles) {
        ASSERT_FALSE(geometry::isDegenerate({glm::dvec3(t.p0), glm::dvec3(t.p1), glm::dvec3(t.p2)}));
        const float extent = glm::length(t.p1 - t.p0) + glm::length(t.p2 - t.p0);
        smallest = std::min(smallest, extent);
        largest = std::max(largest, extent);
        // Within the generators' volume: x, z in [-1, 1], y in [0, 1].
        for (const glm::vec3& p : {t.p0, t.p1, t.p2}) {
            ASSERT_LE(std::abs(p.x), 1.0f);
            ASSERT_LE(std::abs(p.z), 1.0f);
            ASSERT_GE(p.y, 0.0f);
            ASSERT_LE(p.y, 1.0f);
        }
    }
    EXPECT_GT(largest / smallest, 64.0f);  // sizes 2^-k for k in 0..7, random shapes
}

}  // namespace
}  // namespace vkray
