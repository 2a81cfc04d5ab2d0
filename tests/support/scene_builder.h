// Scenes built in code for the CPU tests: small, with every value chosen so the expected pixel can
// be computed by hand.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkray::test {

// A material that is black unless a test says otherwise (the .scene default ambient is 0.2).
inline Material blackMaterial() {
    Material m;
    m.ambient = glm::vec3(0.0f);
    return m;
}

// Camera at (0, 0, 5) looking at the origin, +y up, fovy 45: the centre pixel of an odd-sized
// image looks exactly down -z and meets the plane z = 0 at the origin, t = 5.
inline Scene sceneLookingDownZ() {
    Scene s;
    s.camera.eye = {0.0f, 0.0f, 5.0f};
    s.camera.center = {0.0f, 0.0f, 0.0f};
    s.camera.up = {0.0f, 1.0f, 0.0f};
    s.camera.fovyDegrees = 45.0f;
    s.hasCamera = true;
    return s;
}

inline uint32_t addMaterial(Scene& s, const Material& m) {
    s.materials.push_back(m);
    return uint32_t(s.materials.size() - 1);
}

// The square [-h, h]^2 in the plane z = z0 as two triangles split along the diagonal from
// (-h, -h) to (h, h). Geometric normal +z when facingUp, else -z.
inline void addSquare(Scene& s, float z0, float h, bool facingUp, uint32_t material) {
    const glm::vec3 a{-h, -h, z0}, b{h, -h, z0}, c{h, h, z0}, d{-h, h, z0};
    if (facingUp) {
        s.triangles.push_back({a, b, c, material});
        s.triangles.push_back({a, c, d, material});
    } else {
        s.triangles.push_back({a, c, b, material});
        s.triangles.push_back({a, d, c, material});
    }
}

inline void addDirectionalLight(Scene& s, glm::vec3 towardsLight, glm::vec3 color) {
    s.lights.push_back({Light::Type::Directional, towardsLight, color});
}

inline void addPointLight(Scene& s, glm::vec3 position, glm::vec3 color) {
    s.lights.push_back({Light::Type::Point, position, color});
}

}  // namespace vkray::test
