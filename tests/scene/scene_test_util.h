// Helpers of the scene tests: parse scene text in memory, with `geo` paths relative to data/.
#pragma once

#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray::test {

inline std::filesystem::path sceneDataDir() {
    return std::filesystem::path(VKRAY_SOURCE_DIR) / "tests" / "scene" / "data";
}

inline Scene parseText(const std::string& text) {
    std::istringstream in(text);
    return parseScene(in, "test.scene", sceneDataDir());
}

// `s` with its positions back in world space (float(local + origin), origin 0): for tests that
// check where the loader put geometry in the world, whatever local origin it chose.
inline Scene inWorld(Scene s) {
    const auto world = [&](glm::vec3& p) { p = glm::vec3(glm::dvec3(p) + s.origin); };
    for (Triangle& t : s.triangles) {
        world(t.p0);
        world(t.p1);
        world(t.p2);
    }
    world(s.camera.eye);
    world(s.camera.center);
    for (Light& l : s.lights)
        if (l.type == Light::Type::Point) world(l.vector);
    s.origin = glm::dvec3(0.0);
    return s;
}

// An axis-aligned box grown by points.
struct Box {
    glm::dvec3 lo{1e300}, hi{-1e300};
    void add(const glm::vec3& p) { lo = glm::min(lo, glm::dvec3(p)), hi = glm::max(hi, glm::dvec3(p)); }
};

inline Box triangleBox(const Scene& s) {
    Box box;
    for (const Triangle& t : s.triangles)
        for (const glm::vec3& p : {t.p0, t.p1, t.p2}) box.add(p);
    return box;
}

// Every corner of `box` projects inside the scene camera's image of scene.width x scene.height
// pixels (or width x height when given): the whole object is in view.
inline void expectFramed(const Scene& s, const Box& box, int width = 0, int height = 0) {
    const CameraFrame f = makeCameraFrame(s.camera, width ? width : s.width, height ? height : s.height);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 p((corner & 1) ? box.hi.x : box.lo.x, (corner & 2) ? box.hi.y : box.lo.y,
                           (corner & 4) ? box.hi.z : box.lo.z);
        const glm::dvec3 d = p - f.eye;
        const double depth = -glm::dot(d, f.w);
        ASSERT_GT(depth, 0.0) << "corner " << corner << " is behind the camera";
        EXPECT_LT(std::abs(glm::dot(d, f.u) / depth), f.tanX) << "corner " << corner << " outside horizontally";
        EXPECT_LT(std::abs(glm::dot(d, f.v) / depth), f.tanY) << "corner " << corner << " outside vertically";
    }
}

// The message of the vkray::Error that parsing `text` throws, or "(no error)".
inline std::string parseError(const std::string& text) {
    try {
        parseText(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace vkray::test

// Component-wise EXPECT_NEAR of two glm vectors, reported at the caller's line.
#define EXPECT_VEC3_NEAR(actual, expected, tolerance)            \
    do {                                                         \
        const glm::vec3 a_ = (actual), e_ = (expected);          \
        EXPECT_NEAR(a_.x, e_.x, (tolerance)) << #actual << ".x"; \
        EXPECT_NEAR(a_.y, e_.y, (tolerance)) << #actual << ".y"; \
        EXPECT_NEAR(a_.z, e_.z, (tolerance)) << #actual << ".z"; \
    } while (0)
