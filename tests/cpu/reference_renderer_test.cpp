// Whole images of scenes built in code, each with a pixel value computed by hand from
// docs/shading.md. Images are 5x5 (odd): the centre pixel's ray runs exactly down -z from (0, 0, 5)
// and meets the plane z = 0 at the origin, t = 5.
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "cpu/shading.h"
#include "scene/camera.h"
#include "support/scene_builder.h"
#include "support/window_check.h"

namespace vkray {
namespace {

using test::addDirectionalLight;
using test::addMaterial;
using test::addPointLight;
using test::addSquare;
using test::blackMaterial;

RenderOptions fiveByFive(int maxDepth = 5) {
    RenderOptions o;
    o.width = o.height = 5;
    o.maxDepth = maxDepth;
    return o;
}

glm::vec3 centre(const Frame& f) { return f.color[f.index(2, 2)]; }

void expectColor(const glm::vec3& got, const glm::dvec3& want, double tol = 1e-6) {
    EXPECT_NEAR(got.r, want.r, tol);
    EXPECT_NEAR(got.g, want.g, tol);
    EXPECT_NEAR(got.b, want.b, tol);
}

// A large square at z = 0 facing the camera, in the given material, filling the view.
Scene floorScene(const Material& m) {
    Scene s = test::sceneLookingDownZ();
    addSquare(s, 0.0f, 100.0f, true, addMaterial(s, m));
    return s;
}

TEST(ReferenceRenderer, AmbientOnlyIsExact) {
    Material m = blackMaterial();
    m.ambient = {0.3f, 0.6f, 0.9f};
    const Frame f = renderReference(floorScene(m), fiveByFive());
    ASSERT_EQ(f.width, 5);
    ASSERT_EQ(f.height, 5);
    const CameraFrame cam = makeCameraFrame(test::sceneLookingDownZ().camera, 5, 5);
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const size_t k = f.index(i, j);
            EXPECT_EQ(f.color[k], m.ambient) << i << "," << j;
            EXPECT_EQ(f.normal[k], glm::vec3(0, 0, 1));
            EXPECT_GE(f.primId[k], 0);
            // depth is t along the unit camera direction: 5 / cos(angle to -z).
            EXPECT_NEAR(f.depth[k], 5.0 / -primaryDirection(cam, i, j).z, 1e-5);
        }
    EXPECT_EQ(f.depth[f.index(2, 2)], 5.0f);
    // The centre ray meets the square on its diagonal, shared by both triangles: the lower index.
    EXPECT_EQ(f.primId[f.index(2, 2)], 0);
    EXPECT_EQ(f.primId[f.index(0, 4)], 0);  // bottom left: below the diagonal
    EXPECT_EQ(f.primId[f.index(0, 0)], 1);  // top left: above it
}

TEST(ReferenceRenderer, MissIsBlackWithEmptyAovs) {
    Scene s = test::sceneLookingDownZ();
    addMaterial(s, Material{});
    s.triangles.push_back({{10, 10, 0}, {11, 10, 0}, {10, 11, 0}, 0});  // out of view
    const Frame f = renderReference(s, fiveByFive());
    for (size_t k = 0; k < f.color.size(); ++k) {
        EXPECT_EQ(f.color[k], glm::vec3(0.0f));
        EXPECT_EQ(f.depth[k], std::numeric_limits<float>::infinity());
        EXPECT_EQ(f.primId[k], -1);
        EXPECT_EQ(f.normal[k], glm::vec3(0.0f));
    }
}

// Without primaryAovs the frame holds the colour alone, the same colour.
TEST(ReferenceRenderer, WithoutPrimaryAovsOnlyTheColour) {
    Material m = blackMaterial();
    m.ambient = {0.3f, 0.6f, 0.9f};
    const Scene s = floorScene(m);
    RenderOptions without = fiveByFive();
    without.primaryAovs = false;
    const Frame f = renderReference(s, fiveByFive()), g = renderReference(s, without);
    EXPECT_TRUE(f.hasAovs());
    EXPECT_FALSE(g.hasAovs());
    EXPECT_TRUE(g.depth.empty() && g.primId.empty() && g.normal.empty());
    EXPECT_EQ(f.color, g.color);
}

// Directional light 45 degrees off the normal, diffuse only: kd * C * cos(45).
TEST(ReferenceRenderer, DirectionalDiffuseIsLambert) {
    Material m = blackMaterial();
    m.diffuse = {0.5f, 0.25f, 1.0f};
    Scene s = floorScene(m);
    addDirectionalLight(s, {0, 1, 1}, {1.0f, 0.5f, 0.25f});
    const Frame f = renderReference(s, fiveByFive());
    const glm::dvec3 expected = glm::dvec3(0.5, 0.125, 0.25) * std::sqrt(0.5);
    for (const glm::vec3& c : f.color) expectColor(c, expected);  // the same everywhere on a plane
}

// Blinn-Phong highlight seen along the normal with the light at 45 degrees: ks C cos(22.5)^s.
TEST(ReferenceRenderer, SpecularHighlight) {
    Material m = blackMaterial();
    m.specular = glm::vec3(1.0f);
    m.reflect = glm::vec3(0.0f);  // highlight only, no mirror
    m.shininess = 10.0f;
    Scene s = floorScene(m);
    addDirectionalLight(s, {0, 1, 1}, {1.0f, 1.0f, 1.0f});
    const Frame f = renderReference(s, fiveByFive());
    expectColor(centre(f), glm::dvec3(std::pow(std::cos(std::numbers::pi / 8), 10.0)));
}

// Point light at (3, 0, 4): r = 5 from the origin, cos = 0.8, att = 1/(0.5 + 0.25 r + 0.125 r^2).
TEST(ReferenceRenderer, PointLightWithAttenuation) {
    Material m = blackMaterial();
    m.diffuse = {1.0f, 0.5f, 0.25f};
    Scene s = floorScene(m);
    s.attenuation = {0.5f, 0.25f, 0.125f};
    addPointLight(s, {3, 0, 4}, {1, 1, 1});
    const Frame f = renderReference(s, fiveByFive());
    expectColor(centre(f), glm::dvec3(1.0, 0.5, 0.25) * 0.8 / (0.5 + 0.25 * 5 + 0.125 * 25));
}

// A triangle halfway between the origin and the light leaves only ambient at the centre pixel
// (it is off to the side of the camera ray); one beyond the light does not shadow.
TEST(ReferenceRenderer, ShadowRayBlocksTheLight) {
    Material m = blackMaterial();
    m.ambient = glm::vec3(0.125f);
    m.diffuse = glm::vec3(0.5f);
    Scene lit = floorScene(m);
    addPointLight(lit, {3, 0, 4}, {1, 1, 1});
    // Beyond the light on the same line (1.5 x the way): must not block (shadow t < r).
    lit.triangles.push_back({{4.0f, -0.5f, 6.0f}, {5.0f, -0.5f, 6.0f}, {4.5f, 0.5f, 6.0f}, 0});
    expectColor(centre(renderReference(lit, fiveByFive())), glm::dvec3(0.125 + 0.5 * 0.8));

    Scene shadowed = lit;
    Material glass = blackMaterial();  // transparent occluders block too (no caustics)
    glass.transmit = glm::vec3(1.0f);
    glass.ior = 1.5f;
    const uint32_t g = addMaterial(shadowed, glass);
    shadowed.triangles.push_back({{1.0f, -0.5f, 2.0f}, {2.0f, -0.5f, 2.0f}, {1.5f, 0.5f, 2.0f}, g});
    const Frame f = renderReference(shadowed, fiveByFive(1));
    expectColor(centre(f), glm::dvec3(0.125));
    EXPECT_EQ(f.primId[f.index(2, 2)], 0);  // the occluder is not what the camera sees there
}

TEST(ReferenceRenderer, LightBelowTheSurfaceDoesNotLightIt) {
    Material m = blackMaterial();
    m.ambient = glm::vec3(0.25f);
    m.diffuse = glm::vec3(1.0f);
    Scene s = floorScene(m);
    addDirectionalLight(s, {0, 0, -1}, {1, 1, 1});
    addPointLight(s, {0, 1, -3}, {1, 1, 1});
    for (const glm::vec3& c : renderReference(s, fiveByFive()).color) EXPECT_EQ(c, glm::vec3(0.25f));
}

// Seen from behind (Ng pointing away from the camera) a triangle is shaded with its facing side,
// and the normal AOV faces the camera.
TEST(ReferenceRenderer, BackFacesAreShadedTwoSided) {
    Material m = blackMaterial();
    m.diffuse = glm::vec3(1.0f);
    Scene s = test::sceneLookingDownZ();
    addSquare(s, 0.0f, 100.0f, false, addMaterial(s, m));
    addDirectionalLight(s, {0, 0, 1}, {0.5f, 0.5f, 0.5f});
    const Frame f = renderReference(s, fiveByFive());
    expectColor(centre(f), glm::dvec3(0.5));
    EXPECT_EQ(f.normal[f.index(2, 2)], glm::vec3(0, 0, 1));
}

// Partial transparency T scales ambient and diffuse by (1 - T), per channel; with a light
// straight above: (1 - T) (ambient + diffuse).
TEST(ReferenceRenderer, TransparencyReplacesTheDiffuseBody) {
    Material m = blackMaterial();
    m.ambient = glm::vec3(0.5f);
    m.diffuse = glm::vec3(1.0f);
    m.transmit = {0.25f, 0.5f, 1.0f};
    m.ior = 1.5f;
    Scene s = floorScene(m);
    addDirectionalLight(s, {0, 0, 1}, {1, 1, 1});
    EXPECT_EQ(centre(renderReference(s, fiveByFive(1))), glm::vec3(1.125f, 0.75f, 0.0f));
}

// Smooth normals tilted to (0, 0.6, 0.8) under a light straight above: kd C 0.8.
TEST(ReferenceRenderer, SmoothNormalsShade) {
    Material m = blackMaterial();
    m.diffuse = glm::vec3(1.0f);
    Scene s = floorScene(m);
    const glm::vec3 n{0.0f, 0.6f, 0.8f};
    s.normals.assign(s.triangles.size(), TriangleNormals{n, n, n});
    addDirectionalLight(s, {0, 0, 1}, {1, 1, 1});
    const Frame f = renderReference(s, fiveByFive());
    expectColor(centre(f), glm::dvec3(0.8));
    EXPECT_NEAR(f.normal[f.index(2, 2)].y, 0.6f, 1e-6);
}

// A mirror at z = 0 and an emissive square at z = 10 facing it (behind the camera): every pixel
// sees the emission by reflection. With maxdepth 1 there is no reflection: black.
Scene mirrorScene(glm::vec3 reflect, glm::vec3 emission) {
    Material mirror = blackMaterial();
    mirror.reflect = reflect;
    Scene s = floorScene(mirror);
    Material lamp = blackMaterial();
    lamp.emission = emission;
    addSquare(s, 10.0f, 100.0f, false, addMaterial(s, lamp));
    return s;
}

TEST(ReferenceRenderer, MirrorShowsEmissionByReflection) {
    const glm::vec3 emission{0.2f, 0.6f, 0.9f};
    const Scene s = mirrorScene(glm::vec3(1.0f), emission);
    const Frame f = renderReference(s, fiveByFive(2));
    for (const glm::vec3& c : f.color) EXPECT_EQ(c, emission);
    EXPECT_EQ(f.primId[f.index(2, 2)], 0);  // AOVs describe the mirror, not what it reflects
    const Frame local = renderReference(s, fiveByFive(1));
    for (const glm::vec3& c : local.color) EXPECT_EQ(c, glm::vec3(0.0f));
}

// Weights below 1/1024 in every channel are not traced; at 1/1024 they are.
TEST(ReferenceRenderer, WeightCutoff) {
    const glm::vec3 white(1.0f);
    const float cutoff = 1.0f / 1024.0f, below = 1.0f / 2048.0f;
    EXPECT_EQ(centre(renderReference(mirrorScene(glm::vec3(below), white), fiveByFive())),
              glm::vec3(0.0f));
    EXPECT_EQ(centre(renderReference(mirrorScene(glm::vec3(cutoff), white), fiveByFive())),
              glm::vec3(cutoff));
    // One channel at the cutoff carries the others along.
    EXPECT_EQ(centre(renderReference(mirrorScene({below, cutoff, 0.0f}, white), fiveByFive())),
              glm::vec3(below, cutoff, 0.0f));
}

// A clear glass slab (T = 1, n = 1.5) between z = -1 and z = 0, lit from above by a red emitter and
// from below by a green one, seen at normal incidence: F = ((n - 1)/(n + 1))^2 = 0.04 at each face.
// maxdepth 3: F red (reflected at the top) + (1 - F)^2 green (through both faces); the ray reflected
// inside at the bottom face reaches the top at depth 3 and stops.
// maxdepth 4 adds that ray leaving through the top: F (1 - F)^2 red.
TEST(ReferenceRenderer, GlassSlabAtNormalIncidence) {
    Scene s = test::sceneLookingDownZ();
    Material glass = blackMaterial();
    glass.transmit = glm::vec3(1.0f);
    glass.ior = 1.5f;
    const uint32_t g = addMaterial(s, glass);
    addSquare(s, 0.0f, 100.0f, true, g);    // top face, outward normal +z
    addSquare(s, -1.0f, 100.0f, false, g);  // bottom face, outward normal -z
    Material red = blackMaterial(), green = blackMaterial();
    red.emission = {1, 0, 0};
    green.emission = {0, 1, 0};
    addSquare(s, 10.0f, 100.0f, false, addMaterial(s, red));
    addSquare(s, -5.0f, 100.0f, true, addMaterial(s, green));
    const double F = 0.04;
    expectColor(centre(renderReference(s, fiveByFive(3))), {F, (1 - F) * (1 - F), 0.0}, 1e-7);
    expectColor(centre(renderReference(s, fiveByFive(4))),
                {F + F * (1 - F) * (1 - F), (1 - F) * (1 - F), 0.0}, 1e-7);
    // Local shading alone: clear glass shows no ambient and no diffuse.
    EXPECT_EQ(centre(renderReference(s, fiveByFive(1))), glm::vec3(0.0f));
}

// A scene with every feature at once, rendered on 1 and on 2 threads: bit-identical frames.
TEST(ReferenceRenderer, ThreadCountDoesNotChangeTheImage) {
    Scene s = test::sceneLookingDownZ();
    s.camera.eye = {1.0f, 2.0f, 6.0f};
    Material floor = blackMaterial();
    floor.diffuse = {0.6f, 0.5f, 0.4f};
    floor.specular = glm::vec3(0.3f);
    floor.reflect = glm::vec3(0.3f);
    floor.shininess = 20.0f;
    addSquare(s, -1.0f, 5.0f, true, addMaterial(s, floor));
    Material glass = blackMaterial();
    glass.transmit = {0.9f, 0.95f, 1.0f};
    glass.ior = 1.5f;
    glass.specular = glm::vec3(0.5f);
    const uint32_t g = addMaterial(s, glass);
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    for (int k = 0; k < 40; ++k) {
        const glm::vec3 c(u(rng), u(rng), u(rng) * 0.5f);
        s.triangles.push_back({c, c + glm::vec3(u(rng), u(rng), u(rng)) * 0.5f,
                               c + glm::vec3(u(rng), u(rng), u(rng)) * 0.5f, g});
    }
    addPointLight(s, {2, 3, 4}, {0.8f, 0.8f, 0.8f});
    addDirectionalLight(s, {-1, 1, 2}, {0.3f, 0.3f, 0.4f});
    RenderOptions o;
    o.width = 40;
    o.height = 30;
    o.maxDepth = 5;
    o.threads = 1;
    const Frame one = renderReference(s, o);
    o.threads = 2;
    const Frame two = renderReference(s, o);
    auto sameBytes = [](const auto& a, const auto& b) {
        return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(a[0]) * a.size()) == 0;
    };
    EXPECT_TRUE(sameBytes(one.color, two.color));
    EXPECT_TRUE(sameBytes(one.depth, two.depth));
    EXPECT_TRUE(sameBytes(one.primId, two.primId));
    EXPECT_TRUE(sameBytes(one.normal, two.normal));
    // The scene is not trivially black: glass, floor and misses all occur.
    int hits = 0;
    for (int32_t id : one.primId) hits += id >= 0;
    EXPECT_GT(hits, 300);
    EXPECT_LT(hits, 1200);
}

TEST(ReferenceRenderer, ProgressCountsRows) {
    RenderOptions o = fiveByFive();
    o.height = 7;
    std::vector<int> seen;
    renderReference(floorScene(blackMaterial()), o, [&](int done, int rows) {
        EXPECT_EQ(rows, 7);
        seen.push_back(done);
    });
    EXPECT_EQ(seen, (std::vector<int>{1, 2, 3, 4, 5, 6, 7}));
}

TEST(ReferenceRenderer, UnrenderableScenesAreErrors) {
    Scene noCamera = floorScene(blackMaterial());
    noCamera.hasCamera = false;
    EXPECT_THROW(renderReference(noCamera, fiveByFive()), Error);
    EXPECT_THROW(renderReference(floorScene(blackMaterial()), fiveByFive(0)), Error);
    Scene badMaterial = floorScene(blackMaterial());
    badMaterial.triangles[0].material = 7;
    EXPECT_THROW(renderReference(badMaterial, fiveByFive()), Error);
    Scene badNormals = floorScene(blackMaterial());
    badNormals.normals.resize(1);
    EXPECT_THROW(renderReference(badNormals, fiveByFive()), Error);
    RenderOptions empty = fiveByFive();
    empty.width = 0;
    EXPECT_THROW(renderReference(floorScene(blackMaterial()), empty), Error);
}

TEST(ReferenceRenderer, WindowPixelsAreBitIdenticalToTheWholeImages) {
    Material m = blackMaterial();
    m.diffuse = glm::vec3(0.7f, 0.5f, 0.3f);
    m.specular = glm::vec3(0.2f);
    m.shininess = 10.0f;
    Scene s = floorScene(m);
    addPointLight(s, {1.0f, 0.5f, 2.0f}, glm::vec3(1.0f));
    RenderOptions o;
    o.width = 41;
    o.height = 23;
    o.spp = 3;
    const Frame whole = renderReference(s, o);
    for (const PixelWindow w : {PixelWindow{3, 4, 40, 11}, PixelWindow{40, 22, 41, 23}, PixelWindow{0, 0, 41, 1}}) {
        RenderOptions part = o;
        part.window = w;
        test::expectSamePixels(whole, renderReference(s, part), w);
    }
    o.window = PixelWindow{0, 0, 42, 1};  // past the right edge
    EXPECT_THROW(renderReference(s, o), Error);
}

TEST(ReferenceRenderer, TracePixelLogsEveryRayAndEndsWithThePixelsRadiance) {
    Material m = blackMaterial();
    m.diffuse = glm::vec3(0.5f);
    m.ambient = glm::vec3(0.1f);
    m.reflect = glm::vec3(0.5f);  // a mirror: one reflected ray, which misses
    Scene s = floorScene(m);
    addPointLight(s, {0.0f, 0.0f, 2.0f}, glm::vec3(1.0f));
    addPointLight(s, {0.0f, 0.0f, -2.0f}, glm::vec3(1.0f));  // below the floor
    RenderOptions o = fiveByFive(2);
    const Frame f = renderReference(s, o);
    const std::vector<std::string> log = tracePixel(s, o, 2, 2);
    const auto has = [&](const std::string& start) {
        for (const std::string& line : log)
            if (line.find(start) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(has("camera ray, depth 1: origin"));
    EXPECT_TRUE(has("hit triangle"));
    EXPECT_TRUE(has("light 0 (point): visible, adds"));
    EXPECT_TRUE(has("light 1 (point): behind the surface"));
    EXPECT_TRUE(has("reflected ray, depth 2"));
    EXPECT_TRUE(has("miss: background"));
    ASSERT_FALSE(log.empty());
    // The logged radiance is the rendered pixel's (to the 6 digits printed).
    double r = 0.0, g = 0.0, b = 0.0;
    ASSERT_EQ(std::sscanf(log.back().c_str(), "radiance %lf %lf %lf", &r, &g, &b), 3);
    expectColor(centre(f), {r, g, b}, 1e-5);
    EXPECT_THROW(tracePixel(s, o, 5, 0), Error);
}

}  // namespace
}  // namespace vkray
