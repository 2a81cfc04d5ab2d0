// Meshes for the BVH tests, each chosen for a way a BVH can go wrong: flat axis-aligned walls (boxes
// of zero thickness, rays in their planes), a closed sphere (shared edges and vertices), a random
// soup with exact duplicates (ties in t), and triangles that all share one centroid (one Morton
// code: the downward phase can only split in the middle).
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkray::test {

struct NamedMesh {
    std::string name;
    Scene scene;
};

inline void addQuad(Scene& s, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    s.triangles.push_back({a, b, c, 0});
    s.triangles.push_back({a, c, d, 0});
}

// An axis-aligned box [lo, hi] whose six faces are n x n grids of quads.
inline void addGridBox(Scene& s, glm::vec3 lo, glm::vec3 hi, int n) {
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            const float w = side ? hi[axis] : lo[axis];
            for (int i = 0; i < n; ++i)
                for (int j = 0; j < n; ++j) {
                    const auto at = [&](int a, int b) {
                        glm::vec3 p;
                        p[axis] = w;
                        p[u] = lo[u] + (hi[u] - lo[u]) * float(a) / float(n);
                        p[v] = lo[v] + (hi[v] - lo[v]) * float(b) / float(n);
                        return p;
                    };
                    addQuad(s, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                }
        }
}

// A Cornell-like room: walls at +-1 split into grids, two axis-aligned blocks inside.
inline Scene cornellBox() {
    Scene s;
    s.materials.push_back(Material{});
    addGridBox(s, glm::vec3(-1.0f), glm::vec3(1.0f), 4);
    addGridBox(s, {-0.6f, -1.0f, -0.5f}, {-0.1f, 0.2f, 0.0f}, 1);
    addGridBox(s, {0.1f, -1.0f, 0.1f}, {0.6f, -0.4f, 0.6f}, 2);
    return s;
}

// A closed latitude-longitude sphere (poles as triangle fans).
inline Scene uvSphere(glm::vec3 centre, float radius, int rings, int segments) {
    Scene s;
    s.materials.push_back(Material{});
    const auto point = [&](int r, int g) {
        const double theta = M_PI * r / rings, phi = 2.0 * M_PI * (g % segments) / segments;
        return centre + radius * glm::vec3(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                           float(std::sin(theta) * std::sin(phi)));
    };
    for (int r = 0; r < rings; ++r)
        for (int g = 0; g < segments; ++g) {
            const glm::vec3 a = point(r, g), b = point(r + 1, g), c = point(r + 1, g + 1), d = point(r, g + 1);
            if (r > 0) s.triangles.push_back({a, b, d, 0});
            if (r < rings - 1) s.triangles.push_back({b, c, d, 0});
        }
    return s;
}

// Random triangles in [-1, 1]^3; every tenth repeats the one before exactly (ties in t).
inline Scene randomSoup(uint32_t seed, int count, float size = 0.3f) {
    Scene s;
    s.materials.push_back(Material{});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < count; ++k) {
        if (k % 10 == 9) {
            s.triangles.push_back(s.triangles.back());
            continue;
        }
        const glm::vec3 c(u(rng), u(rng), u(rng));
        Triangle t{};
        t.p0 = c + size * glm::vec3(u(rng), u(rng), u(rng));
        t.p1 = c + size * glm::vec3(u(rng), u(rng), u(rng));
        t.p2 = c + size * glm::vec3(u(rng), u(rng), u(rng));
        s.triangles.push_back(t);
    }
    return s;
}

// Triangles of many sizes and orientations whose centroids are all exactly the origin: a + b and
// -(a + b) round alike, so (p0 + p1) + p2 is exactly 0.
inline Scene equalCentroids(uint32_t seed, int count) {
    Scene s;
    s.materials.push_back(Material{});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < count; ++k) {
        const glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
        s.triangles.push_back({a, b, -(a + b), 0});
    }
    return s;
}

// All triangles in the plane z = 0, overlapping: random triangles in [-1, 1]^2 (every box flat on
// one axis; many Morton codes, but every box spans many cells).
inline Scene coplanarOverlapping(uint32_t seed, int count) {
    Scene s;
    s.materials.push_back(Material{});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (int k = 0; k < count; ++k)
        s.triangles.push_back({{u(rng), u(rng), 0.0f}, {u(rng), u(rng), 0.0f}, {u(rng), u(rng), 0.0f}, 0});
    return s;
}

// One triangle spanning [-100, 100]^2 among `count` - 1 tiny ones (size 0.01) in [-1, 1]^3: the
// huge box covers every other, and its centroid lies among theirs.
inline Scene hugeAmongTiny(uint32_t seed, int count) {
    Scene s = randomSoup(seed, count - 1, 0.01f);
    s.triangles.push_back({{-100.0f, -100.0f, 0.1f}, {100.0f, -100.0f, -0.1f}, {0.0f, 100.0f, 0.0f}, 0});
    return s;
}

// `copies` exact copies of each of `count` / `copies` random triangles, a triangle's copies in a row
// (equal boxes and Morton codes: no split separates them, ties in t everywhere).
inline Scene duplicated(uint32_t seed, int count, int copies) {
    Scene s = randomSoup(seed, count / copies, 0.2f);
    Scene out;
    out.materials = s.materials;
    for (const Triangle& t : s.triangles)
        for (int c = 0; c < copies; ++c) out.triangles.push_back(t);
    return out;
}

// The degenerate cases of a Morton-ordered build (ties in the codes, boxes covering boxes), for the
// AAC-against-binned-SAH quality bounds and the GPU hit checks.
inline std::vector<NamedMesh> degenerateMeshes(int count) {
    return {{"equal_centroids", equalCentroids(5, count)},
            {"coplanar", coplanarOverlapping(6, count)},
            {"huge_among_tiny", hugeAmongTiny(7, count)},
            {"duplicated", duplicated(8, count, 50)}};
}

inline std::vector<NamedMesh> testMeshes() {
    return {{"cornell", cornellBox()},
            {"sphere", uvSphere({0.1f, -0.2f, 0.3f}, 0.9f, 24, 48)},
            {"soup", randomSoup(7, 600)},
            {"equal_centroids", equalCentroids(11, 300)}};
}

}  // namespace vkray::test
