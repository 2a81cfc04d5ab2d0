// Appends world-space triangles and materials to a Scene while keeping its invariants: materials
// deduplicated (equal Material -> one index), Scene::normals either empty or one entry per triangle
// (filled lazily: the first smooth triangle backfills geometric normals for the flat ones before it).
// Used by the .scene parser, the sphere tessellation and the OBJ loader alike.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkray {

using TriPoints = std::array<glm::dvec3, 3>;

class SceneBuilder {
public:
    // At most `maxTriangles` triangles in the scene (kMaxSceneTriangles; tests and the fuzzer set less).
    explicit SceneBuilder(Scene& scene, int64_t maxTriangles = kMaxSceneTriangles);

    Scene& scene() { return scene_; }

    // Index of `m` in scene.materials, appending it when no equal material is there yet.
    uint32_t material(const Material& m);

    // Room for `triangles` more (and their normals when the scene has smooth ones): for callers
    // that know their count up front.
    void reserve(size_t triangles);

    // Why `more` triangles do not fit under the scene's triangle limit, or nothing when they do.
    // Callers ask before they make the triangles and report the answer with their file:line; an
    // append past the limit throws a vkray::Error without a location (a caller that did not ask).
    std::optional<std::string> roomProblem(uint64_t more) const;
    int64_t maxTriangles() const { return maxTriangles_; }

    // Append one triangle; `p` and `n` are world space, `n` unit length. Returns false (and
    // appends nothing) when a coordinate does not fit a 32-bit float, so the caller can report
    // it with its own file:line.
    [[nodiscard]] bool addFlat(const TriPoints& p, uint32_t material);
    [[nodiscard]] bool addSmooth(const TriPoints& p, const TriPoints& n, uint32_t material);

private:
    bool append(const TriPoints& p, uint32_t material);

    // Ordered by a lexicographic comparison of the material's numbers: consistent with
    // Material::operator== for the finite values the parsers let through.
    struct MaterialLess {
        bool operator()(const Material& a, const Material& b) const;
    };

    Scene& scene_;
    int64_t maxTriangles_;
    std::map<Material, uint32_t, MaterialLess> index_;
};

// Unit normal of the triangle's plane, cross(p1 - p0, p2 - p0) normalized; (0, 0, 1) for a
// degenerate triangle, which no ray can hit, so its normal is never used but stays finite.
glm::vec3 geometricNormal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);

}  // namespace vkray
