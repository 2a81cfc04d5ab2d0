// Sphere tessellation: triangle count, vertices on the sphere, outward winding, smooth normals.
#include <gtest/gtest.h>

#include "scene/scene_builder.h"
#include "scene/sphere.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

TEST(Sphere, TriangleCountIsFourStepsTimesStepsMinusOne) {
    for (int steps : {3, 4, 12, 16, 40}) {
        EXPECT_EQ(int64_t(unitSphereTriangles(steps).size()), sphereTriangleCount(steps)) << steps;
    }
    EXPECT_EQ(sphereTriangleCount(kDefaultSphereSteps), 960);
}

TEST(Sphere, UnitTrianglesAreOnTheSphereAndWoundOutward) {
    for (const TriPoints& t : unitSphereTriangles(7)) {
        for (const glm::dvec3& p : t) EXPECT_NEAR(glm::length(p), 1.0, 1e-12);
        const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
        EXPECT_GT(glm::length(n), 1e-6) << "degenerate triangle";
        EXPECT_GT(glm::dot(n, t[0] + t[1] + t[2]), 0.0) << "inward-facing triangle";
    }
}

TEST(Sphere, AllVerticesLieAtTheRadiusFromTheCentre) {
    const glm::vec3 centre(1.5f, -2.0f, 4.0f);
    const float radius = 0.75f;
    const Scene s = test::inWorld(test::parseText("sphere 1.5 -2 4 0.75\n"));
    ASSERT_EQ(s.triangles.size(), 960u);
    for (size_t i = 0; i < s.triangles.size(); ++i) {
        const Triangle& t = s.triangles[i];
        const TriangleNormals& n = s.normals[i];
        for (const auto& [p, normal] :
             {std::pair{t.p0, n.n0}, std::pair{t.p1, n.n1}, std::pair{t.p2, n.n2}}) {
            EXPECT_NEAR(glm::length(p - centre), radius, 1e-6f);
            EXPECT_VEC3_NEAR(normal, (p - centre) / radius, 1e-5f);
        }
        EXPECT_GT(glm::dot(geometricNormal(t.p0, t.p1, t.p2), (t.p0 + t.p1 + t.p2) / 3.0f - centre), 0.0f);
        EXPECT_EQ(t.material, s.triangles[0].material);
    }
}

TEST(Sphere, TheSphereCoversTheWholeSolidAngle) {
    // The triangles' projected solid angles around the centre add up to 4 pi (no gaps, no overlaps):
    // the signed solid angle of each triangle by Van Oosterom & Strackee.
    double total = 0.0;
    for (const TriPoints& t : unitSphereTriangles(9)) {
        const double num = glm::dot(t[0], glm::cross(t[1], t[2]));
        const double den = 1.0 + glm::dot(t[0], t[1]) + glm::dot(t[1], t[2]) + glm::dot(t[2], t[0]);
        total += 2.0 * std::atan2(num, den);
    }
    EXPECT_NEAR(total, 4.0 * 3.14159265358979323846, 1e-9);
}

}  // namespace
}  // namespace vkray
