// The rules of docs/shading.md one by one: Fresnel, directions, origin offsets, normals, the local
// Blinn-Phong term and the child weights.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "cpu/shading.h"
#include "cpu/whitted.h"
#include "support/scene_builder.h"

namespace vkray::cpu {
namespace {

constexpr double kTol = 1e-12;

void expectNear(const glm::dvec3& got, const glm::dvec3& want, double tol = kTol) {
    EXPECT_NEAR(got.x, want.x, tol);
    EXPECT_NEAR(got.y, want.y, tol);
    EXPECT_NEAR(got.z, want.z, tol);
}

// ---- Fresnel ("Secondary rays") ----------------------------------------------------------------

TEST(Fresnel, NormalIncidence) {
    const double n = 1.5, expected = std::pow((n - 1.0) / (n + 1.0), 2.0);  // 0.04
    EXPECT_NEAR(fresnelDielectric(1.0, 1.0 / n), expected, 1e-15);  // entering
    EXPECT_NEAR(fresnelDielectric(1.0, n), expected, 1e-15);        // leaving
    EXPECT_EQ(fresnelDielectric(1.0, 1.0), 0.0);                    // index matched: no interface
}

// Against the textbook angle form: Rs = sin^2(i - t) / sin^2(i + t), Rp = tan^2(i - t) / tan^2(i + t).
TEST(Fresnel, MatchesAngleFormOfFresnelEquations) {
    const double n = 1.5;
    for (double degrees : {10.0, 30.0, 45.0, 60.0, 80.0}) {
        const double i = degrees * std::numbers::pi / 180.0, t = std::asin(std::sin(i) / n);
        const double rs = std::pow(std::sin(i - t) / std::sin(i + t), 2.0);
        const double rp = std::pow(std::tan(i - t) / std::tan(i + t), 2.0);
        EXPECT_NEAR(fresnelDielectric(std::cos(i), 1.0 / n), (rs + rp) / 2.0, kTol) << degrees;
        // Reciprocity: the same interface seen from inside at the refracted angle reflects alike.
        EXPECT_NEAR(fresnelDielectric(std::cos(t), n), (rs + rp) / 2.0, kTol) << degrees;
    }
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
    const double n = 1.5, cosCritical = std::sqrt(1.0 - 1.0 / (n * n));
    const Interface beyond = dielectricInterface(cosCritical - 1e-6, n);
    EXPECT_TRUE(beyond.totalInternalReflection);
    EXPECT_EQ(beyond.reflectance, 1.0);
    const Interface before = dielectricInterface(cosCritical + 1e-6, n);
    EXPECT_FALSE(before.totalInternalReflection);
    EXPECT_LT(before.reflectance, 1.0);
    EXPECT_GT(before.reflectance, 0.9);  // F rises to 1 as the critical angle nears
    EXPECT_EQ(fresnelDielectric(0.3, n), 1.0);
}

TEST(Fresnel, GoesToOneAtGrazingIncidence) {
    EXPECT_EQ(fresnelDielectric(0.0, 1.0 / 1.5), 1.0);
    EXPECT_GT(fresnelDielectric(1e-4, 1.0 / 1.5), 0.999);
    double previous = fresnelDielectric(1.0, 1.0 / 1.5);
    for (double cosi = 0.95; cosi > 0.0; cosi -= 0.05) {  // increasing angle, rising F
        const double f = fresnelDielectric(cosi, 1.0 / 1.5);
        EXPECT_GT(f, previous) << cosi;
        previous = f;
    }
}

// ---- Directions and origins ---------------------------------------------------------------------

TEST(Directions, Reflection) {
    const glm::dvec3 d = glm::normalize(glm::dvec3(1, -1, 0));
    expectNear(reflectedDirection(d, {0, 1, 0}), glm::normalize(glm::dvec3(1, 1, 0)));
}

TEST(Directions, RefractionObeysSnell) {
    const double n = 1.5;
    const glm::dvec3 N(0, 1, 0), d = glm::normalize(glm::dvec3(1, -1, 0));  // 45 degrees
    const Interface at = dielectricInterface(glm::dot(-d, N), 1.0 / n);
    const glm::dvec3 t = refractedDirection(d, N, at);
    EXPECT_NEAR(glm::length(t), 1.0, kTol);
    EXPECT_NEAR(glm::length(glm::cross(t, N)), std::sin(std::numbers::pi / 4) / n, kTol);
    EXPECT_NEAR(-t.y, at.cost, kTol);
    EXPECT_GT(t.x, 0.0);  // onwards, bent towards the normal
    EXPECT_EQ(t.z, 0.0);  // in the plane of incidence
    // Normal incidence goes straight through.
    const Interface straight = dielectricInterface(1.0, 1.0 / n);
    expectNear(refractedDirection({0, -1, 0}, N, straight), {0, -1, 0});
}

TEST(Origins, OffsetScalesWithTheLargestCoordinate) {
    EXPECT_EQ(offsetRayOrigin({0, 0, 0}, {0, 0, 1}), glm::dvec3(0, 0, 1e-9));
    EXPECT_EQ(offsetRayOrigin({0.5, -0.25, 0}, {0, 0, -1}), glm::dvec3(0.5, -0.25, -1e-9));
    const glm::dvec3 far = offsetRayOrigin({1000, -2000, 3}, {0, 1, 0});
    EXPECT_EQ(far.x, 1000.0);
    EXPECT_NEAR(far.y - -2000.0, 2e-6, 1e-12);
    EXPECT_EQ(far.z, 3.0);
}

// ---- Surface points ("Notation") ---------------------------------------------------------------

Scene oneTriangle() {
    Scene s = test::sceneLookingDownZ();
    test::addMaterial(s, test::blackMaterial());
    s.triangles.push_back({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0});  // Ng = +z
    return s;
}

Hit hitAt(double b0, double b1, double b2) { return Hit{0, 1.0, b0, b1, b2}; }

TEST(SurfacePoints, FlatFromEitherSide) {
    const Scene s = oneTriangle();
    const SurfacePoint above = surfaceAt(s, hitAt(0.25, 0.25, 0.5), {0, 0, -1});
    EXPECT_EQ(above.position, glm::dvec3(0.25, 0.5, 0));
    EXPECT_TRUE(above.front);
    EXPECT_EQ(above.geometricNormal, glm::dvec3(0, 0, 1));
    EXPECT_EQ(above.facingNormal, glm::dvec3(0, 0, 1));
    EXPECT_EQ(above.normal, glm::dvec3(0, 0, 1));
    const SurfacePoint below = surfaceAt(s, hitAt(0.25, 0.25, 0.5), {0, 0, 1});
    EXPECT_FALSE(below.front);
    EXPECT_EQ(below.geometricNormal, glm::dvec3(0, 0, 1));
    EXPECT_EQ(below.facingNormal, glm::dvec3(0, 0, -1));
    EXPECT_EQ(below.normal, glm::dvec3(0, 0, -1));
}

TEST(SurfacePoints, SmoothNormalsAreInterpolatedAndTurnedToTheRay) {
    Scene s = oneTriangle();
    s.normals.push_back({{0, 0, 1}, {0, 1, 0}, {0, 1, 0}});
    // b0 = 0.5: (0, 0.5, 0.5) normalised.
    const SurfacePoint above = surfaceAt(s, hitAt(0.5, 0.25, 0.25), {0, 0, -1});
    expectNear(above.normal, glm::normalize(glm::dvec3(0, 1, 1)));
    const SurfacePoint below = surfaceAt(s, hitAt(0.5, 0.25, 0.25), {0, 0, 1});
    expectNear(below.normal, -glm::normalize(glm::dvec3(0, 1, 1)));
    // A vertex normal pointing below the surface is flipped with the whole interpolation.
    s.normals[0] = {{0, 0.6f, -0.8f}, {0, 0.6f, -0.8f}, {0, 0.6f, -0.8f}};
    const SurfacePoint flipped = surfaceAt(s, hitAt(0.25, 0.25, 0.5), {0, 0, -1});
    expectNear(flipped.normal, {0, -0.6, 0.8}, 1e-7);
    // Opposed vertex normals that cancel: fall back to the geometric normal.
    s.normals[0] = {{0, 0, 1}, {0, 0, -1}, {0, 0, 1}};
    EXPECT_EQ(surfaceAt(s, hitAt(0.25, 0.5, 0.25), {0, 0, -1}).normal, glm::dvec3(0, 0, 1));
}

// ---- Local shading ------------------------------------------------------------------------------

SurfacePoint flatUp() {
    SurfacePoint s;
    s.position = {0, 0, 0};
    s.geometricNormal = s.facingNormal = s.normal = {0, 0, 1};
    s.front = true;
    return s;
}

TEST(BlinnPhong, DiffuseAndSpecularTerms) {
    Material m = test::blackMaterial();
    m.diffuse = {0.5f, 0.25f, 1.0f};
    const glm::dvec3 L = glm::normalize(glm::dvec3(0, 1, 1)), V(0, 0, 1), C(1, 2, 4);
    expectNear(blinnPhong(flatUp(), m, V, L, C), glm::dvec3(0.5, 0.5, 4.0) * std::sqrt(0.5));
    // (1 - T) scales the diffuse body.
    m.transmit = glm::vec3(0.75f);
    expectNear(blinnPhong(flatUp(), m, V, L, C), glm::dvec3(0.5, 0.5, 4.0) * 0.25 * std::sqrt(0.5));
    // Specular: H halves the 45 degrees between L and V; T does not scale it.
    m.diffuse = glm::vec3(0.0f);
    m.specular = glm::vec3(1.0f);
    m.shininess = 10.0f;
    expectNear(blinnPhong(flatUp(), m, V, L, C), C * std::pow(std::cos(std::numbers::pi / 8), 10.0));
}

TEST(BlinnPhong, LightBehindTheSurfaceContributesNothing) {
    Material m = test::blackMaterial();
    m.diffuse = glm::vec3(1.0f);
    m.specular = glm::vec3(1.0f);
    const glm::dvec3 V(0, 0, 1), C(1.0);
    EXPECT_EQ(blinnPhong(flatUp(), m, V, {0, 0, -1}, C), glm::dvec3(0.0));
    EXPECT_EQ(blinnPhong(flatUp(), m, V, {1, 0, 0}, C), glm::dvec3(0.0));  // dot(N, L) = 0
    // In front of a tilted shading normal but behind the geometric surface.
    SurfacePoint tilted = flatUp();
    tilted.normal = glm::normalize(glm::dvec3(1, 0, 1));
    EXPECT_EQ(blinnPhong(tilted, m, V, glm::normalize(glm::dvec3(1, 0, -0.1)), C), glm::dvec3(0.0));
}

TEST(BlinnPhong, PointLightAttenuation) {
    EXPECT_EQ(pointLightAttenuation({1, 0, 0}, 7.0), 1.0);
    EXPECT_EQ(pointLightAttenuation({0.5, 0.25, 0.125}, 2.0), 1.0 / 1.5);
}

// ---- Children and weights ("Secondary rays", "Depth and weights") -------------------------------

TEST(SecondaryRays, OpaqueMaterialReflectsWithR) {
    Material m = test::blackMaterial();
    m.reflect = {0.5f, 0.25f, 0.0f};
    const glm::dvec3 d = glm::normalize(glm::dvec3(1, 0, -1));
    const SecondaryRays c = secondaryRays(flatUp(), m, d);
    EXPECT_EQ(c.reflected.factor, glm::dvec3(0.5, 0.25, 0.0));
    EXPECT_EQ(c.refracted.factor, glm::dvec3(0.0));
    EXPECT_EQ(c.reflected.ray.origin, glm::dvec3(0, 0, 1e-9));
    expectNear(c.reflected.ray.dir, glm::normalize(glm::dvec3(1, 0, 1)));
}

TEST(SecondaryRays, GlassSplitsByFresnel) {
    Material m = test::blackMaterial();
    m.reflect = {0.125f, 0.0f, 0.0f};
    m.transmit = {1.0f, 0.5f, 0.0f};
    m.ior = 1.5f;
    const SecondaryRays c = secondaryRays(flatUp(), m, {0, 0, -1});  // entering, normal incidence
    const double F = 0.04;
    expectNear(c.reflected.factor, {0.125 + F, 0.5 * F, 0.0});
    expectNear(c.refracted.factor, {1.0 - F, 0.5 * (1.0 - F), 0.0});
    EXPECT_EQ(c.refracted.ray.origin, glm::dvec3(0, 0, -1e-9));  // below the surface
    expectNear(c.refracted.ray.dir, {0, 0, -1});
}

// Entering at 80 degrees bends towards the normal (eta = 1/n, no total internal reflection);
// leaving at the same angle reflects totally.
TEST(SecondaryRays, ObliqueIncidenceDependsOnTheSide) {
    Material m = test::blackMaterial();
    m.transmit = glm::vec3(1.0f);
    m.ior = 1.5f;
    const double angle = 80.0 * std::numbers::pi / 180.0;
    const glm::dvec3 d(std::sin(angle), 0.0, -std::cos(angle));
    const SecondaryRays in = secondaryRays(flatUp(), m, d);
    const double F = fresnelDielectric(std::cos(angle), 1.0 / 1.5);
    expectNear(in.refracted.factor, glm::dvec3(1.0 - F));
    expectNear(in.reflected.factor, glm::dvec3(F));
    EXPECT_NEAR(in.refracted.ray.dir.x, std::sin(angle) / 1.5, kTol);  // Snell
    SurfacePoint inside = flatUp();
    inside.front = false;
    const SecondaryRays out = secondaryRays(inside, m, d);
    EXPECT_EQ(out.refracted.factor, glm::dvec3(0.0));
    EXPECT_EQ(out.reflected.factor, glm::dvec3(1.0));
}

TEST(SecondaryRays, TotalInternalReflectionSendsEverythingBack) {
    Material m = test::blackMaterial();
    m.transmit = glm::vec3(1.0f);
    m.ior = 1.5f;
    SurfacePoint inside = flatUp();  // leaving the material: the ray travels along +Ng
    inside.front = false;
    inside.facingNormal = inside.normal = {0, 0, -1};
    const glm::dvec3 d = glm::normalize(glm::dvec3(1, 0, 0.5));  // 63 degrees > critical 41.8
    const SecondaryRays c = secondaryRays(inside, m, d);
    EXPECT_EQ(c.reflected.factor, glm::dvec3(1.0));
    EXPECT_EQ(c.refracted.factor, glm::dvec3(0.0));
    expectNear(c.reflected.ray.dir, glm::normalize(glm::dvec3(1, 0, -0.5)));
}

TEST(Weights, CutoffAtOneOver1024InEveryChannel) {
    EXPECT_TRUE(worthTracing({1.0 / 1024.0, 0.0, 0.0}));
    EXPECT_TRUE(worthTracing({0.0, 0.0, 1.0 / 1024.0}));
    EXPECT_FALSE(worthTracing(glm::dvec3(std::nextafter(1.0 / 1024.0, 0.0))));
    EXPECT_FALSE(worthTracing(glm::dvec3(0.0)));
}

}  // namespace
}  // namespace vkray::cpu
