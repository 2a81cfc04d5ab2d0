// bvh-sphere's containers: a triangle's sphere holds its vertices and is the smallest one (checked
// against the radius computed independently: half the longest edge for a right or obtuse triangle,
// abc / 4A for an acute one), a merged sphere holds both, and in a built tree every node's sphere
// holds its children's spheres and its leaf's vertices, in exact arithmetic of the stored floats.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/sphere_bounds.h"
#include "bvh_test_meshes.h"

namespace vkray::bvh {
namespace {

// |p - centre| <= radius, in double from the stored floats (long double for the margin of the check
// itself).
bool holds(const Sphere& s, const glm::vec3& p) {
    const long double dx = (long double)p.x - s.centre.x, dy = (long double)p.y - s.centre.y,
                      dz = (long double)p.z - s.centre.z;
    return dx * dx + dy * dy + dz * dz <= (long double)s.radius * s.radius;
}

bool holds(const Sphere& outer, const Sphere& inner) {
    const double d = glm::length(glm::dvec3(inner.centre) - glm::dvec3(outer.centre));
    return d + double(inner.radius) <= double(outer.radius) * (1.0 + 1e-12);
}

// The smallest enclosing radius, computed another way.
double smallestRadius(const Triangle& t) {
    const glm::dvec3 a(t.p0), b(t.p1), c(t.p2);
    const double ab = glm::length(b - a), bc = glm::length(c - b), ca = glm::length(a - c);
    const double longest = std::max({ab, bc, ca});
    const double sumSquares = ab * ab + bc * bc + ca * ca;
    if (2.0 * longest * longest >= sumSquares) return 0.5 * longest;  // right or obtuse (or flat)
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    return ab * bc * ca / (4.0 * area);
}

std::vector<Triangle> awkwardTriangles(uint32_t seed, int count) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-10.0f, 10.0f), small(-1e-3f, 1e-3f);
    std::vector<Triangle> tris;
    for (int k = 0; k < count; ++k) {
        const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        glm::vec3 c(u(rng), u(rng), u(rng));
        switch (k % 5) {
        case 1: c = 0.5f * (a + b); break;                                          // collinear
        case 2: c = a; break;                                                       // two equal vertices
        case 3: c = 0.5f * (a + b) + glm::vec3(small(rng), small(rng), small(rng)); break;  // a sliver
        case 4: c = glm::vec3(1e4f) + 0.01f * c; break;                             // far and small
        default: break;
        }
        tris.push_back({a, b, c, 0});
    }
    return tris;
}

TEST(SphereBounds, TriangleSphereIsTheSmallestThatHoldsIt) {
    for (const Triangle& t : awkwardTriangles(5, 5000)) {
        const Sphere s = triangleSphere(t);
        ASSERT_TRUE(holds(s, t.p0) && holds(s, t.p1) && holds(s, t.p2));
        const double want = smallestRadius(t);
        const double scale = std::max({glm::length(glm::dvec3(t.p0)), glm::length(glm::dvec3(t.p1)),
                                       glm::length(glm::dvec3(t.p2))});
        // Rounding the centre to float may cost a few ulps of the coordinates' magnitude.
        EXPECT_LE(double(s.radius), want * (1.0 + 1e-6) + 1e-6 * scale);
    }
}

TEST(SphereBounds, MergedSphereHoldsBothAndIsTight) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-5.0f, 5.0f), r(0.0f, 3.0f);
    for (int k = 0; k < 5000; ++k) {
        const Sphere a{{u(rng), u(rng), u(rng)}, r(rng)};
        const Sphere b = k % 7 == 0 ? Sphere{a.centre + 0.1f * glm::vec3(u(rng), 0, 0), 0.1f * a.radius}  // nested
                                    : Sphere{{u(rng), u(rng), u(rng)}, r(rng)};
        const Sphere m = mergeSpheres(a, b);
        ASSERT_TRUE(holds(m, a) && holds(m, b));
        const double d = glm::length(glm::dvec3(a.centre) - glm::dvec3(b.centre));
        const double want = std::max({double(a.radius), double(b.radius), 0.5 * (d + a.radius + b.radius)});
        EXPECT_LE(double(m.radius), want * (1.0 + 1e-6) + 1e-6);
        EXPECT_NEAR(mergedRadius(a.centre.x, a.centre.y, a.centre.z, a.radius, b.centre.x, b.centre.y, b.centre.z,
                                 b.radius),
                    want, 1e-5 * (want + 1.0));
    }
}

TEST(SphereBounds, EveryNodeOfABuiltTreeHoldsWhatIsBelowIt) {
    for (const test::NamedMesh& mesh : test::testMeshes()) {
        SCOPED_TRACE(mesh.name);
        const FlatBvh flat = buildFlatBvh(mesh.scene.triangles, Config::aacHqSpheres()).flat;
        ASSERT_EQ(flat.spheres.size(), flat.nodes.size());
        int leaves = 0;
        for (uint32_t i = 0; i < flat.nodes.size(); ++i) {
            const FlatNode& n = flat.nodes[i];
            if (n.count == 0) {
                ASSERT_TRUE(holds(flat.spheres[i], flat.spheres[i + 1])) << "node " << i;
                ASSERT_TRUE(holds(flat.spheres[i], flat.spheres[n.rightOrFirst])) << "node " << i;
                continue;
            }
            ++leaves;
            for (uint32_t k = n.rightOrFirst; k < n.rightOrFirst + n.count; ++k) {
                const Triangle& t = mesh.scene.triangles[flat.triangleOrder[k]];
                ASSERT_TRUE(holds(flat.spheres[i], t.p0) && holds(flat.spheres[i], t.p1) && holds(flat.spheres[i], t.p2))
                    << "leaf " << i;
            }
        }
        EXPECT_EQ(uint32_t(leaves), flat.leaves);
    }
}

}  // namespace
}  // namespace vkray::bvh
