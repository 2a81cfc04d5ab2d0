// Scene::origin, the local frame the loader stores positions in (scene_builder.h, localOrigin): scenes
// built around the world's origin keep origin 0 and their floats; a copy translated by a round number
// gets exactly that origin and the same local floats; any other offset keeps the positions within one
// float rounding of their double world values.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scene/camera.h"
#include "scene/scene_builder.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

constexpr char kHeader[] = "camera 0.5 2.2 4.6  0.5 0.3 0  0 1 0  40\n"
                           "point 1.5 2.5 1.5  0.5 0.5 0.5\n"
                           "directional -1 0.35 0.4  0.6 0.6 0.6\n";
// Non-dyadic coordinates (0.02, 1.81, -0.3), a flat and a smooth triangle (the flat one's normals
// are its geometric normal, computed from the local floats).
constexpr char kGeometry[] = "vertex -3 0 3\nvertex 3 0 3\nvertex 1.81 0.02 -3\n"
                             "tri 0 1 2\n"
                             "vertexnormal -0.3 0.4 1.2  0 1 0\nvertexnormal 0.5 0.02 -0.5  0.6 0.8 0\n"
                             "vertexnormal 1.5 0.6 0.5  0 0 1\n"
                             "trinormal 0 1 2\n";

std::string translated(double x, double y, double z) {
    const auto num = [](double v) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.17g", v);
        return std::string(buf);
    };
    const std::string t = num(x) + " " + num(y) + " " + num(z);
    const auto p = [&](double a, double b, double c) { return num(x + a) + " " + num(y + b) + " " + num(z + c); };
    return "camera " + p(0.5, 2.2, 4.6) + "  " + p(0.5, 0.3, 0) + "  0 1 0  40\n" + "point " + p(1.5, 2.5, 1.5) +
           "  0.5 0.5 0.5\n" + "directional -1 0.35 0.4  0.6 0.6 0.6\n" + "translate " + t + "\n" + kGeometry;
}

bool sameBits(const void* a, const void* b, size_t n) { return std::memcmp(a, b, n) == 0; }

TEST(LocalOrigin, IsZeroForBoundsAroundTheWorldsOrigin) {
    EXPECT_EQ(localOrigin(glm::dvec3(-3, 0, -3), glm::dvec3(3, 1, 3)), glm::dvec3(0.0));
    // Bounds ending at 0 and spanning a power of two: the centre is half a grid step at most.
    EXPECT_EQ(localOrigin(glm::dvec3(0, 0, 0), glm::dvec3(4, 4, 4)), glm::dvec3(0.0));
    EXPECT_EQ(localOrigin(glm::dvec3(-4, -4, -4), glm::dvec3(0, 0, 0)), glm::dvec3(0.0));
    // Off the origin but within one extent of it: still 0.
    EXPECT_EQ(localOrigin(glm::dvec3(0.4, 0.5, 0.4), glm::dvec3(1.4, 1.5, 1.4)), glm::dvec3(0.0));
    // No bounds (no triangles): 0.
    EXPECT_EQ(localOrigin(glm::dvec3(1.0), glm::dvec3(-1.0)), glm::dvec3(0.0));
    EXPECT_FALSE(std::signbit(localOrigin(glm::dvec3(-0.3), glm::dvec3(0.1)).x));  // +0, not -0
}

TEST(LocalOrigin, FollowsARoundTranslationExactly) {
    const glm::dvec3 lo(-3, 0, -3), hi(3, 1, 3);  // extent 6: grid 16
    for (const double offset : {1e6, 1e7, -1e7, 16.0 * 12345.0, std::ldexp(1.0, 60)}) {
        EXPECT_EQ(localOrigin(lo + offset, hi + offset), glm::dvec3(offset)) << offset;
    }
    // Not a multiple of the grid: the nearest multiple, so the local bounds stay within 3 extents.
    EXPECT_EQ(localOrigin(lo + 1e6 + 7.0, hi + 1e6 + 7.0), glm::dvec3(1e6));  // centres 7 and 7.5 above
    EXPECT_EQ(localOrigin(lo + 1e6 + 9.0, hi + 1e6 + 9.0), glm::dvec3(1e6 + 16.0));  // 9 and 9.5 above
    // One point: the point itself.
    EXPECT_EQ(localOrigin(glm::dvec3(5e6, 1, 2), glm::dvec3(5e6, 1, 2)), glm::dvec3(5e6, 1, 2));
}

TEST(SceneOrigin, HandMadeScenesStayAtTheWorldsOrigin) {
    const std::filesystem::path root = std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes";
    for (const char* name : {"default.scene", "cornell.scene", "spheres.scene", "lights.scene", "objects.scene",
                             "stress/magnitude.scene", "stress/tiny-1e-4.scene", "stress/burst-100k.scene",
                             "stress/kd-zeno.scene", "stress/coplanar.scene", "stress/mirror-corridor.scene"}) {
        const Scene s = loadScene(root / name);
        EXPECT_EQ(s.origin, glm::dvec3(0.0)) << name;
    }
    const Scene s = test::parseText(std::string(kHeader) + kGeometry);
    EXPECT_EQ(s.origin, glm::dvec3(0.0));
    EXPECT_EQ(s.camera.eye, glm::vec3(0.5f, 2.2f, 4.6f));  // each number rounded to float once
    EXPECT_EQ(s.lights[0].vector, glm::vec3(1.5f, 2.5f, 1.5f));
}

TEST(SceneOrigin, RoundTranslationGivesTheSameLocalFloats) {
    const Scene base = test::parseText(std::string(kHeader) + kGeometry);
    for (const double offset : {1e6, 1e7, -3e6, 1048576.0}) {
        const Scene far = test::parseText(translated(offset, offset, offset));
        EXPECT_EQ(far.origin, glm::dvec3(offset)) << offset;
        ASSERT_EQ(far.triangles.size(), base.triangles.size());
        for (size_t i = 0; i < base.triangles.size(); ++i) {
            EXPECT_TRUE(sameBits(&far.triangles[i], &base.triangles[i], sizeof(Triangle))) << offset << " #" << i;
            EXPECT_TRUE(sameBits(&far.normals[i], &base.normals[i], sizeof(TriangleNormals))) << offset << " #" << i;
        }
        EXPECT_EQ(far.camera.eye, base.camera.eye) << offset;
        EXPECT_EQ(far.camera.center, base.camera.center) << offset;
        EXPECT_EQ(far.lights[0].vector, base.lights[0].vector) << offset;
        EXPECT_EQ(far.lights[1].vector, base.lights[1].vector) << offset;  // a direction: not moved
    }
}

TEST(SceneOrigin, AnyOffsetKeepsPositionsWithinOneFloatRounding) {
    // Straddling a grid line (x around 2^20), and off every round number in y and z.
    const glm::dvec3 offset(1048576.0 - 0.25, 2.5e6 + 1.0 / 3.0, -7654321.123);
    const Scene s = test::parseText(translated(offset.x, offset.y, offset.z));
    const Scene base = test::parseText(std::string(kHeader) + kGeometry);
    EXPECT_NE(s.origin, glm::dvec3(0.0));
    for (int k = 0; k < 3; ++k) EXPECT_LE(std::abs(s.origin[k] - offset[k]), 16.0) << k;  // grid 16 (extent 6)
    for (size_t i = 0; i < base.triangles.size(); ++i) {
        const Triangle &t = s.triangles[i], &b = base.triangles[i];
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) {
                // The world position (vertex and translate read in double, added in double), minus
                // the origin, rounded to float once: within half a float ulp of the local value. The
                // base scene's float vertex stands for the decimal one, within half its own ulp.
                const float vertex = (&b.p0)[v][k];
                const double world = double(vertex) + offset[k];
                const double local = double((&t.p0)[v][k]);
                const double ulp = std::nextafter(float(std::abs(local)), INFINITY) - float(std::abs(local));
                const double vertexUlp = std::nextafter(std::abs(vertex), INFINITY) - std::abs(vertex);
                EXPECT_LE(std::abs(local + s.origin[k] - world), 0.5 * ulp + 0.5 * vertexUlp)
                    << i << " " << v << " " << k;
            }
    }
    // The camera the same way, and a world-space --view camera lands on it.
    const glm::dvec3 eye = offset + glm::dvec3(0.5, 2.2, 4.6);
    EXPECT_NEAR(double(s.camera.eye.x) + s.origin.x, eye.x, 1e-6);
    EXPECT_NEAR(double(s.camera.eye.z) + s.origin.z, eye.z, 1e-6);
}

// Coordinates written out far from the origin (as CAD or geographic data are), not translated
// there: vertices and transforms are read in double, so 0.02 above a floor at 1e6 stays 0.02
// (read as float, both would be 1e6).
TEST(SceneOrigin, FarVerticesKeepTheirDecimals) {
    const Scene s = test::parseText(
        "camera 1000000 1000003 1000005  1000000 1000000 1000000  0 1 0  40\n"
        "vertex 999997 1000000 999997\nvertex 1000003 1000000 999997\nvertex 1000003 1000000 1000003\n"
        "vertex 999999.5 1000000.02 999999.5\nvertex 1000000.5 1000000.02 999999.5\n"
        "vertex 1000000.5 1000000.02 1000000.5\n"
        "tri 0 1 2\ntri 3 4 5\n"
        "pushTransform\ntranslate 0.001 0.01 0\ntri 3 4 5\npopTransform\n");
    ASSERT_EQ(s.triangles.size(), 3u);
    EXPECT_NE(s.origin, glm::dvec3(0.0));
    const double floor = double(s.triangles[0].p0.y), plate = double(s.triangles[1].p0.y);
    EXPECT_NEAR(plate - floor, 0.02, 1e-6);
    EXPECT_NEAR(double(s.triangles[2].p0.y) - plate, 0.01, 1e-6);
    EXPECT_NEAR(double(s.triangles[2].p0.x) - double(s.triangles[1].p0.x), 0.001, 1e-6);
    EXPECT_NEAR(double(s.triangles[1].p0.x) + s.origin.x, 999999.5, 1e-6);
}

TEST(SceneOrigin, ViewCameraIsWorldSpace) {
    const Scene far = test::parseText(translated(1e6, 1e6, 1e6));
    const Scene base = test::parseText(std::string(kHeader) + kGeometry);
    const Camera c = viewCamera(far, "1000000.5,1000002.2,1000004.6,1000000.5,1000000.3,1000000");
    EXPECT_EQ(c.eye, base.camera.eye);
    EXPECT_EQ(c.center, base.camera.center);
    const Camera close = viewCamera(far, "close"), closeBase = viewCamera(base, "close");
    EXPECT_EQ(close.eye, closeBase.eye);
}

}  // namespace
}  // namespace vkray
