// The watertight ray-triangle test: exact values where the arithmetic is exact, and the edge-case
// rules of geometry/ray_triangle.h.
#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "geometry/ray_triangle.h"

namespace vkray::geometry {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

const TriangleVertices kUnitRight{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)};

// Dyadic coordinates keep every intermediate exact, so t and the barycentrics are exact too.
TEST(RayTriangle, HitGivesExactTAndBarycentrics) {
    const auto hit = intersectTriangle({{0.25, 0.5, 1.0}, {0, 0, -1}}, kUnitRight, 0.0, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, 1.0);
    EXPECT_EQ(hit->b0, 0.25);
    EXPECT_EQ(hit->b1, 0.25);
    EXPECT_EQ(hit->b2, 0.5);
}

// t is measured in units of the direction's length; either winding is hit (two-sided).
TEST(RayTriangle, NonUnitDirectionAndBothWindings) {
    const auto hit = intersectTriangle({{0.25, 0.5, 1.0}, {0, 0, -2}}, kUnitRight, 0.0, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, 0.5);
    const TriangleVertices flipped{kUnitRight[0], kUnitRight[2], kUnitRight[1]};
    const auto back = intersectTriangle({{0.25, 0.5, 1.0}, {0, 0, -1}}, flipped, 0.0, kInf);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->t, 1.0);
    EXPECT_EQ(back->b0, 0.25);
    EXPECT_EQ(back->b1, 0.5);  // p1 and p2 swapped places
    EXPECT_EQ(back->b2, 0.25);
}

// A tilted triangle (plane z = y) and an oblique ray, still with exact arithmetic: the ray from
// (1.5, 1.5, 4.5) along (-1, -1, -4) reaches (0.5, 0.5, 0.5) = 0.5 p0 + 0.25 p1 + 0.25 p2 at t = 1.
TEST(RayTriangle, ObliqueRayOnTiltedTriangle) {
    const TriangleVertices tri{glm::dvec3(0, 0, 0), glm::dvec3(2, 0, 0), glm::dvec3(0, 2, 2)};
    const auto hit = intersectTriangle({{1.5, 1.5, 4.5}, {-1, -1, -4}}, tri, 0.0, kInf);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->t, 1.0);
    EXPECT_EQ(hit->b0, 0.5);
    EXPECT_EQ(hit->b1, 0.25);
    EXPECT_EQ(hit->b2, 0.25);
}

TEST(RayTriangle, Misses) {
    // Beside the hypotenuse.
    EXPECT_FALSE(intersectTriangle({{0.75, 0.75, 1.0}, {0, 0, -1}}, kUnitRight, 0.0, kInf));
    // Behind the origin (t = -1).
    EXPECT_FALSE(intersectTriangle({{0.25, 0.25, -1.0}, {0, 0, -1}}, kUnitRight, 0.0, kInf));
    // Pointing away.
    EXPECT_FALSE(intersectTriangle({{0.25, 0.25, 1.0}, {0, 0, 1}}, kUnitRight, 0.0, kInf));
}

// The square [0,1]^2 split along its diagonal: a ray through the diagonal or through a corner of
// the diagonal hits both halves (points on edges and vertices count as inside).
TEST(RayTriangle, SharedEdgeAndVertexHitBothTriangles) {
    const TriangleVertices lower{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(1, 1, 0)};
    const TriangleVertices upper{glm::dvec3(0, 0, 0), glm::dvec3(1, 1, 0), glm::dvec3(0, 1, 0)};
    const Ray throughEdge{{0.5, 0.5, 1.0}, {0, 0, -1}};
    const auto a = intersectTriangle(throughEdge, lower, 0.0, kInf);
    const auto b = intersectTriangle(throughEdge, upper, 0.0, kInf);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->t, 1.0);
    EXPECT_EQ(b->t, 1.0);
    EXPECT_EQ(a->b1, 0.0);  // on the edge opposite p1 of `lower`
    EXPECT_EQ(b->b2, 0.0);  // on the edge opposite p2 of `upper`
    const Ray throughVertex{{2.0, 2.0, 1.0}, {-1, -1, -1}};  // reaches (1, 1, 0) at t = 1
    const auto c = intersectTriangle(throughVertex, lower, 0.0, kInf);
    const auto d = intersectTriangle(throughVertex, upper, 0.0, kInf);
    ASSERT_TRUE(c && d);
    EXPECT_EQ(c->b2, 1.0);
    EXPECT_EQ(d->b1, 1.0);
}

// A ray passing 2^-60-ish beside a shared edge, where the plain edge function rounds to zero: the
// exactly signed recomputation puts the hit in the one triangle that really contains it (without
// it, both would report a hit). Coordinates as seen along -z: the edge runs from
// B = (-(1 + e), -1) to C = (1 + 2e, 1 + e), e = 2^-30; the origin lies e^2-close on A2's side.
TEST(RayTriangle, NearEdgeRayHitsOnlyTheTriangleThatContainsIt) {
    const double e = 0x1p-30;
    const glm::dvec3 B(-(1 + e), -1, 0), C(1 + 2 * e, 1 + e, 0);
    const TriangleVertices side1{glm::dvec3(-1, 1, 0), B, C}, side2{glm::dvec3(1, -1, 0), C, B};
    const Ray ray{{0, 0, 1}, {0, 0, -1}};
    EXPECT_FALSE(intersectTriangle(ray, side1, 0.0, kInf));
    EXPECT_TRUE(intersectTriangle(ray, side2, 0.0, kInf));
}

// The point of watertightness: a closed mesh around the origin (an octahedron with randomly
// stretched vertices) leaks no ray aimed exactly at a vertex or at points on its edges (which
// round to either side of the edge, or onto it); every such ray hits at least one triangle.
TEST(RayTriangle, ClosedMeshIsWatertight) {
    std::mt19937 rng(20130613);
    std::uniform_real_distribution<double> stretch(0.3, 3.0), unit(0.0, 1.0), shift(-0.1, 0.1);
    for (int mesh = 0; mesh < 20; ++mesh) {
        const glm::dvec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        glm::dvec3 v[6];
        for (int k = 0; k < 6; ++k) v[k] = axes[k] * stretch(rng);
        std::vector<TriangleVertices> faces;
        for (int sx : {0, 1})
            for (int sy : {2, 3})
                for (int sz : {4, 5}) faces.push_back({v[sx], v[sy], v[sz]});
        // Origins off the centre so no ray is symmetric about the mesh.
        const glm::dvec3 origin(shift(rng), shift(rng), shift(rng));
        auto hits = [&](const glm::dvec3& target) {
            int n = 0;
            for (const TriangleVertices& f : faces)
                if (intersectTriangle({origin, target - origin}, f, 0.0, kInf)) ++n;
            return n;
        };
        for (const glm::dvec3& vertex : v) EXPECT_GE(hits(vertex), 1) << "mesh " << mesh;
        for (const TriangleVertices& f : faces)
            for (int e = 0; e < 3; ++e)
                for (int sample = 0; sample < 200; ++sample) {
                    const double s = unit(rng);
                    const glm::dvec3 onEdge = f[e] + s * (f[(e + 1) % 3] - f[e]);
                    ASSERT_GE(hits(onEdge), 1) << "mesh " << mesh << " edge " << e << " s " << s;
                }
    }
}

TEST(RayTriangle, ParallelRaysMiss) {
    // Above the plane z = 0, along x and along a diagonal.
    EXPECT_FALSE(intersectTriangle({{-1.0, 0.25, 1.0}, {1, 0, 0}}, kUnitRight, 0.0, kInf));
    EXPECT_FALSE(intersectTriangle({{-1.0, -1.0, 0.5}, {1, 1, 0}}, kUnitRight, 0.0, kInf));
    // Above the tilted plane z = x, parallel to it.
    const TriangleVertices tilted{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 1), glm::dvec3(0, 1, 0)};
    EXPECT_FALSE(intersectTriangle({{-1.0, 0.25, 0.0}, {1, 0, 1}}, tilted, 0.0, kInf));
}

TEST(RayTriangle, RaysInThePlaneMiss) {
    EXPECT_FALSE(intersectTriangle({{-1.0, 0.25, 0.0}, {1, 0, 0}}, kUnitRight, 0.0, kInf));
    EXPECT_FALSE(intersectTriangle({{-1.0, -1.0, 0.0}, {1, 1, 0}}, kUnitRight, 0.0, kInf));
    const TriangleVertices tilted{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 1), glm::dvec3(0, 1, 0)};
    EXPECT_FALSE(intersectTriangle({{-1.0, 0.25, -1.0}, {1, 0, 1}}, tilted, 0.0, kInf));
}

TEST(RayTriangle, DegenerateTrianglesNeverHit) {
    const TriangleVertices line{glm::dvec3(0, 0, 0), glm::dvec3(1, 1, 0), glm::dvec3(2, 2, 0)};
    const TriangleVertices point{glm::dvec3(1, 1, 0), glm::dvec3(1, 1, 0), glm::dvec3(1, 1, 0)};
    const TriangleVertices twoEqual{glm::dvec3(0, 0, 0), glm::dvec3(0, 0, 0), glm::dvec3(1, 2, 3)};
    EXPECT_TRUE(isDegenerate(line) && isDegenerate(point) && isDegenerate(twoEqual));
    EXPECT_FALSE(isDegenerate(kUnitRight));
    EXPECT_FALSE(intersectTriangle({{1.0, 1.0, 1.0}, {0, 0, -1}}, line, 0.0, kInf));
    EXPECT_FALSE(intersectTriangle({{1.0, 1.0, 1.0}, {0, 0, -1}}, point, 0.0, kInf));
    // Oblique rays through a collinear triangle in general position, where the sheared 2D
    // triangle need not round to exactly zero area.
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Multiples of 2^-20 below 1: p0 + e and p0 + 2e are exact, so the vertices are collinear.
    auto coarse = [&] { return std::ldexp(std::round(std::ldexp(u(rng), 20)), -20); };
    for (int k = 0; k < 1000; ++k) {
        const glm::dvec3 p0(coarse(), coarse(), coarse()), e(coarse(), coarse(), coarse());
        const TriangleVertices collinear{p0, p0 + e, p0 + 2.0 * e};
        const glm::dvec3 origin(u(rng) * 4.0, u(rng) * 4.0, u(rng) * 4.0);
        const glm::dvec3 target = p0 + 0.7 * e;
        ASSERT_FALSE(intersectTriangle({origin, target - origin}, collinear, 0.0, kInf)) << k;
    }
}

// Hits must lie strictly inside (tmin, tmax).
TEST(RayTriangle, TRangeIsOpen) {
    const Ray ray{{0.25, 0.25, 1.0}, {0, 0, -1}};  // t = 1
    EXPECT_FALSE(intersectTriangle(ray, kUnitRight, 0.0, 1.0));
    EXPECT_TRUE(intersectTriangle(ray, kUnitRight, 0.0, std::nextafter(1.0, 2.0)));
    EXPECT_FALSE(intersectTriangle(ray, kUnitRight, 1.0, kInf));
    EXPECT_TRUE(intersectTriangle(ray, kUnitRight, std::nextafter(1.0, 0.0), kInf));
    // A ray starting on the triangle (t = 0) does not hit it.
    EXPECT_FALSE(intersectTriangle({{0.25, 0.25, 0.0}, {0, 0, -1}}, kUnitRight, 0.0, kInf));
}

TEST(RayTriangle, DifferenceOfProductsHasExactSign) {
    // a*b and c*d round to the same double, but differ by 2^-60.
    const double a = 1.0 + 0x1p-30, b = 1.0 + 0x1p-30;  // a*b = 1 + 2^-29 + 2^-60
    const double c = 1.0 + 0x1p-29, d = 1.0;            // c*d = 1 + 2^-29
    EXPECT_EQ(a * b - c * d, 0.0);
    EXPECT_EQ(differenceOfProducts(a, b, c, d), 0x1p-60);
    EXPECT_EQ(differenceOfProducts(c, d, a, b), -0x1p-60);
    EXPECT_EQ(differenceOfProducts(3.0, 5.0, 5.0, 3.0), 0.0);
}

}  // namespace
}  // namespace vkray::geometry
