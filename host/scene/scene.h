// In-memory scene: what the .scene parser (and the OBJ/MTL loader) produce, in the scene's local frame
// (world space minus Scene::origin), and what every renderer and acceleration structure consumes. See
// docs/scene-format.md for the file format; triangle order here *is* its triangle identity
// (docs/scene-format.md, "Triangle identity").
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace vkray {

// Limits on what a scene or the command line may ask for: past them an image is an input error,
// not an allocation failure (each side; the total bounds host and GPU memory for the AOVs).
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 1LL << 26;  // 8192 x 8192
inline constexpr int kMaxDepthLimit = 64;
// Most camera rays per pixel (`spp`, --spp): far beyond what Whitted shading of a pixel's edges
// needs, and a typo's bound.
inline constexpr int kMaxSamplesPerPixel = 4096;
// Triangles a scene may hold: 2^26 is 2.5 GiB of Scene::triangles on the host, and at the GPU's 48
// bytes a triangle 3 GiB, about what the largest storage buffers of real GPUs hold (4 GiB). Loaders
// check it before they tessellate, generate or read, so `generate` and `sphere` lines cannot run
// a machine out of memory or time.
inline constexpr int64_t kMaxSceneTriangles = int64_t(1) << 26;

// Why w x h is not an image vkray renders, or nothing when it is (the `size` command and --size).
inline std::optional<std::string> imageSizeProblem(long long w, long long h) {
    if (w >= 1 && h >= 1 && w <= kMaxImageSide && h <= kMaxImageSide && w * h <= kMaxImagePixels)
        return std::nullopt;
    return "image size " + std::to_string(w) + "x" + std::to_string(h) +
           " is invalid: each side must be 1.." + std::to_string(kMaxImageSide) +
           " and the total at most " + std::to_string(kMaxImagePixels) + " pixels (2^26)";
}

// Material state of the .scene format (CSE167 conventions), resolved at the time a
// primitive is created: `reflect` already holds the specular colour when the scene never set it.
struct Material {
    glm::vec3 ambient{0.2f};
    glm::vec3 diffuse{0.0f};
    glm::vec3 specular{0.0f};
    glm::vec3 emission{0.0f};
    glm::vec3 reflect{0.0f};   // mirror weight per channel
    glm::vec3 transmit{0.0f};  // refraction (transmission) weight per channel; 0 = opaque
    float shininess = 1.0f;
    float ior = 1.0f;          // index of refraction of the material's inside

    bool reflects() const { return glm::any(glm::greaterThan(reflect, glm::vec3(0.0f))); }
    bool refracts() const { return glm::any(glm::greaterThan(transmit, glm::vec3(0.0f))); }
    bool operator==(const Material&) const = default;
};

struct Light {
    enum class Type : uint32_t { Point = 0, Directional = 1 };
    Type type = Type::Point;
    glm::vec3 vector{0.0f};  // Point: position (local frame). Directional: direction *towards* the light.
    glm::vec3 color{1.0f};
};

struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 5.0f};
    glm::vec3 center{0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovyDegrees = 45.0f;
};

// One triangle in the local frame (world minus Scene::origin). `material` indexes Scene::materials.
struct Triangle {
    glm::vec3 p0, p1, p2;
    uint32_t material = 0;
};

// Per-vertex shading normals of one triangle (unit length, world space).
struct TriangleNormals {
    glm::vec3 n0, n1, n2;
};

struct Scene {
    std::filesystem::path sourceFile;  // the .scene file it came from (empty when built in code)

    // Settings of the file; the CLI may override width/height/maxDepth.
    int width = 640;
    int height = 480;
    int maxDepth = 5;            // primary rays count as depth 1
    int spp = 1;                 // camera rays per pixel (scene/camera.h, pixelSampleOffset)
    std::string output;          // `output NAME` as written in the file; empty if absent

    // World position of the local frame's (0, 0, 0): triangles, the camera's eye and centre and point
    // lights are stored relative to it, each rounded to float once from its double world position,
    // so a scene far from the world's origin keeps the float precision it has near it. Chosen by
    // localOrigin (scene_builder.h) from the geometry's bounds: exactly (0, 0, 0) for any scene whose
    // bounds hold the world's origin, and always a multiple of a power of two no smaller than the
    // geometry's extent, so translating a scene by a multiple of that power leaves its local floats
    // bit for bit the same. Distances (depth, t) and directions are the same in both frames.
    glm::dvec3 origin{0.0};

    Camera camera;
    bool hasCamera = false;      // a scene without a `camera` line is an error at render time
    glm::vec3 attenuation{1.0f, 0.0f, 0.0f};  // constant, linear, quadratic (point lights only)
    glm::vec3 background{0.0f};               // the radiance of a ray that hits nothing
    std::vector<Light> lights;

    std::vector<Material> materials;   // deduplicated: equal material states share one entry
    std::vector<Triangle> triangles;   // in load order = triangle identity
    // Either empty (every triangle flat-shaded with its geometric normal) or one entry per triangle;
    // flat triangles then carry their geometric normal three times.
    std::vector<TriangleNormals> normals;

    bool hasSmoothNormals() const { return !normals.empty(); }
};

}  // namespace vkray
