// Procedural scenes for the build and traversal scaling curves: from thousands to tens of millions
// of triangles without a file to fetch. Used by the `generate KIND N [SEED]` scene command and by
// `vkray gen`. Deterministic: the same kind, count and seed give the same triangles on every
// machine (an own random generator; std:: distributions differ between standard libraries).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "scene/scene_builder.h"
#include "scene/transform.h"

namespace vkray {

enum class GeneratorKind {
    Spheres,  // a grid of tessellated spheres of random radius and height (flat-shaded)
    Soup,     // random triangles scattered through the volume (many overlaps: worst case for a BVH)
    Terrain,  // a heightfield by diamond-square (midpoint displacement), two triangles per cell
    // N random triangles that all share one centroid, exactly (in float), so every Morton code of
    // an AAC build is equal and every triangle overlaps every other: a stress case for the
    // builders (docs/stability.md).
    Burst,
};

// "spheres", "soup", "terrain", "burst" and back.
std::optional<GeneratorKind> generatorKindFromName(std::string_view name);
std::string_view generatorName(GeneratorKind kind);
// "spheres, soup, terrain, burst": for messages.
std::string generatorNames();

// Past this a request is an input error, not an allocation failure (40 bytes a triangle: 1.3 GB).
inline constexpr int64_t kMaxGeneratedTriangles = int64_t(1) << 25;

struct GeneratorSpec {
    GeneratorKind kind = GeneratorKind::Spheres;
    int64_t triangles = 0;  // requested, 1..kMaxGeneratedTriangles
    uint64_t seed = 1;
};

// What `spec` really makes: the smallest count of the kind's structure that reaches the request.
// Soup and burst: exactly N. Terrain: g x h cells, g = ceil(sqrt(N/2)), h = ceil(N/2g), 2gh triangles (less
// than N + 2 sqrt(N/2) + 2). Spheres: tessellation steps s = clamp(round(N^(1/4)/2), 3, 64), each
// sphere 4s(s-1) triangles, ceil(N / 4s(s-1)) spheres (less than one sphere over N).
int64_t generatedTriangleCount(const GeneratorSpec& spec);

// The volume every kind stays in before the transform: x and z in [-1, 1], y in [0, 1] (the
// object stands on y = 0, so a scene puts its floor there).
inline constexpr double kGeneratedHalfWidth = 1.0;
inline constexpr double kGeneratedHeight = 1.0;

// Appends generatedTriangleCount(spec) flat triangles with `material`, transformed by `toWorld`.
// Returns false when a transformed vertex does not fit a float (SceneBuilder's rule); the caller
// reports it with its file:line. Throws nothing for a valid spec (1..kMaxGeneratedTriangles).
[[nodiscard]] bool generateMesh(const GeneratorSpec& spec, const Transform& toWorld, uint32_t material,
                                SceneBuilder& out);

}  // namespace vkray
