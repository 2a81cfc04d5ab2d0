// Appends world-space triangles and materials to a Scene while keeping its invariants: materials
// deduplicated (equal Material -> one index), Scene::normals either empty or one entry per triangle
// (filled lazily: the first smooth triangle backfills geometric normals for the flat ones before it).
// Used by the .scene parser, the sphere tessellation and the OBJ loader alike.
//
// Positions arrive in double world space. Each is stored at once as a float, as if Scene::origin
// were (0, 0, 0); finish() then picks the scene's local origin (localOrigin) and, when it is not 0,
// stores every position again as float(world - origin). Until then the builder keeps the double
// world positions, but only while the origin may still move: once the geometry's bounds hold the
// world's origin on every axis (most scenes, after a few triangles), it is 0 and the copy goes.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkray {

using TriPoints = std::array<glm::dvec3, 3>;

// Why a scene of `triangles` triangles would not fit in memory (render/memory_budget.h), or nothing.
using MemoryCheck = std::function<std::optional<std::string>(uint64_t triangles)>;

class SceneBuilder {
public:
    // At most `maxTriangles` triangles in the scene (kMaxSceneTriangles; tests and the fuzzer set less),
    // and, with `memory`, no more than it lets fit.
    explicit SceneBuilder(Scene& scene, int64_t maxTriangles = kMaxSceneTriangles, MemoryCheck memory = {});

    Scene& scene() { return scene_; }

    // Index of `m` in scene.materials, appending it when no equal material is there yet.
    uint32_t material(const Material& m);

    // Room for `triangles` more (and their normals when the scene has smooth ones): for callers
    // that know their count up front.
    void reserve(size_t triangles);

    // Why `more` triangles do not fit under the scene's triangle limit or in memory (the MemoryCheck),
    // or nothing when they do.
    // Callers ask before they make the triangles and report the answer with their file:line; an
    // append past the limit throws a vkray::Error without a location (a caller that did not ask).
    std::optional<std::string> roomProblem(uint64_t more) const;
    int64_t maxTriangles() const { return maxTriangles_; }

    // Append one triangle; `p` and `n` are world space, `n` unit length. Returns false (and
    // appends nothing) when a coordinate does not fit a 32-bit float, so the caller can report
    // it with its own file:line.
    [[nodiscard]] bool addFlat(const TriPoints& p, uint32_t material);
    [[nodiscard]] bool addSmooth(const TriPoints& p, const TriPoints& n, uint32_t material);
    // Smooth with the vertex normals `n` where the file gives them all and each has a direction (a
    // zero normal has none), flat otherwise: how every mesh loader shades its triangles.
    [[nodiscard]] bool addShaded(const TriPoints& p, const std::optional<TriPoints>& n, uint32_t material);
    // The same, with `exact`: the corners computed from the file's decimal numbers read in double,
    // where `p` comes from them read as float (how every scene near the world's origin has always
    // been stored, kept bit for bit). A scene that moves to a local origin is stored from `exact`,
    // so a vertex written as 1000000.02 keeps its .02.
    [[nodiscard]] bool addFlat(const TriPoints& p, const TriPoints& exact, uint32_t material);
    [[nodiscard]] bool addSmooth(const TriPoints& p, const TriPoints& exact, const TriPoints& n, uint32_t material);

    // The camera and a light, with their world positions in double (a directional light's vector
    // is a direction and stays as it is): stored like triangles, moved by finish().
    void setCamera(const Camera& camera, const glm::dvec3& eye, const glm::dvec3& centre);
    void addLight(const Light& light, const glm::dvec3& vector);

    // Chooses Scene::origin from the triangles appended through this builder and stores them, the
    // camera and the point lights relative to it. Call once, after the last append; a builder made
    // over a scene that already had triangles leaves the origin as it is.
    void finish();

private:
    bool append(const TriPoints& p, const TriPoints& exact, uint32_t material);
    void rebase(const glm::dvec3& origin);

    // Ordered by a lexicographic comparison of the material's numbers: consistent with
    // Material::operator== for the finite values the parsers let through.
    struct MaterialLess {
        bool operator()(const Material& a, const Material& b) const;
    };

    Scene& scene_;
    int64_t maxTriangles_;
    MemoryCheck memory_;
    std::map<Material, uint32_t, MaterialLess> index_;

    // What finish() needs when the origin moves, kept while it still may (see the top).
    bool mayMove_ = true;
    glm::dvec3 lo_, hi_;                  // bounds of the world positions appended so far
    struct WorldTriangle {
        TriPoints corners;   // double world positions
        bool flat = true;    // its normals are the geometric one (recomputed after the move)
    };
    std::vector<WorldTriangle> world_;    // per triangle, while mayMove_
    std::optional<std::pair<glm::dvec3, glm::dvec3>> camera_;  // eye, centre
    std::vector<std::pair<size_t, glm::dvec3>> pointLights_;   // index in Scene::lights, position
};

// The local origin of geometry whose world bounds are [lo, hi] (double): on each axis the bounds'
// centre rounded to the nearest multiple of g, the smallest power of two at least twice the bounds'
// largest side (the extent), ties towards 0. So:
//  - an axis whose bounds' centre lies within one extent of 0 (|centre| < g / 2) gets exactly 0, in
//    particular one whose bounds hold 0: scenes built around the world's origin keep their floats;
//  - every local coordinate lies within 3 g / 4 < 3 extent of 0, whatever the offset;
//  - bounds translated by a multiple of g give an origin translated by exactly that, so a far copy
//    of a scene (translated by a round number) has the local coordinates of the scene near 0.
// Bounds of zero extent (one point) give the point itself; empty bounds (lo > hi) give 0.
glm::dvec3 localOrigin(const glm::dvec3& lo, const glm::dvec3& hi);

// Unit normal of the triangle's plane, cross(p1 - p0, p2 - p0) normalized; (0, 0, 1) for a
// degenerate triangle, which no ray can hit, so its normal is never used but stays finite.
glm::vec3 geometricNormal(const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2);

}  // namespace vkray
