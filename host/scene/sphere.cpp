#include "scene/sphere.h"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace vkray {

std::vector<TriPoints> unitSphereTriangles(int steps) {
    const int stacks = steps, slices = 2 * steps;
    // Vertex of stack boundary i (0 = north pole +y, stacks = south pole) and slice boundary j.
    const auto at = [&](int i, int j) {
        if (i == 0) return glm::dvec3(0.0, 1.0, 0.0);
        if (i == stacks) return glm::dvec3(0.0, -1.0, 0.0);
        const double theta = glm::pi<double>() * i / stacks;
        const double phi = 2.0 * glm::pi<double>() * (j % slices) / slices;
        return glm::dvec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    std::vector<TriPoints> tris;
    tris.reserve(size_t(sphereTriangleCount(steps)));
    for (int i = 0; i < stacks; ++i) {
        for (int j = 0; j < slices; ++j) {
            const glm::dvec3 a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            // Quad a-b-c-d; at the poles one of its edges collapses and one triangle remains.
            if (i + 1 < stacks) tris.push_back({a, c, b});
            if (i > 0) tris.push_back({a, d, c});
        }
    }
    return tris;
}

bool appendSphere(SceneBuilder& out, const Transform& toWorld, const glm::dvec3& centre, double radius,
                  int steps, uint32_t material) {
    for (const TriPoints& u : unitSphereTriangles(steps)) {
        TriPoints p, n;
        for (int k = 0; k < 3; ++k) {
            p[k] = toWorld.point(centre + radius * u[k]);
            n[k] = toWorld.normal(u[k]);
        }
        if (!out.addSmooth(p, n, material)) return false;
    }
    return true;
}

}  // namespace vkray
