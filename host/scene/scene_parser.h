// The .scene format of docs/scene-format.md: the UCSD CSE167 ray tracer format (whose *.test files load
// unchanged), plus `refract`, `reflect`, `spheresteps`, `geo`/`obj` for Wavefront OBJ, OFF, PLY and glTF meshes and
// `generate` for procedural ones (generators.h). Transforms, spheres and meshes are resolved here,
// materials are deduplicated, and triangle order is load order (docs/scene-format.md, "Triangle
// identity"). Geometry is transformed in double and stored relative to Scene::origin, rounded to float
// once (SceneBuilder). Camera, point-light, vertex and transform numbers are read in double; a scene
// whose origin stays 0 is stored from them rounded to float first, as always (bit for bit), a far one
// from the double values. A `sphere` line's numbers and mesh files' vertices are floats.
//
// Conventions where the format leaves room:
//  - Transforms apply to geometry only (tri, trinormal, sphere, geo); `camera`, `point` and
//    `directional` are world space, as in the CSE167 ray tracer's test scenes.
//  - `tri`/`trinormal` transform their vertices by the transform current at the `tri` line.
//  - `reflect` defaults to the current specular colour until a `reflect` line sets it; from then
//    on the explicit value stays (it is material state like every other).
//  - `attenuation` is one global setting (the last line wins), for point lights only.
//  - Sphere: `spheresteps` stacks x 2*steps slices, default 16 (960 triangles), smooth normals.
//
// Every bad line throws vkray::Error(FileLoc{file, line, col}, "what was expected"); nothing but
// comments (# to the end of the line) and blank lines is skipped. A scene without a camera or
// without triangles is not an error here (the render command decides): see Scene::hasCamera.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <istream>
#include <string>
#include <string_view>

#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "scene/text_input.h"

namespace vkray {

// Limits of `size` and `maxdepth` (kMaxImageSide, kMaxImagePixels, kMaxDepthLimit) and of the
// triangle count (kMaxSceneTriangles) live in scene/scene.h, shared with the command line.

// No command needs a long line (camera, the longest, has 10 numbers); a longer one is refused
// before it is tokenized, so a 10 MB line costs neither time nor memory nor a 10 MB message.
inline constexpr size_t kMaxSceneLineBytes = 64 * 1024;
// pushTransform nesting: each level keeps a matrix, and a hand-written or generated scene needs a
// few dozen; past this a push without its pop is a bug in the file (or a file of pushes).
inline constexpr size_t kMaxTransformDepth = 1024;

struct ParseOptions {
    int64_t maxTriangles = kMaxSceneTriangles;
    // Where geo/obj meshes and their MTL files are read from; empty: the file system.
    FileReader readFile;
    // Told before each step that may take seconds (a mesh file read, a mesh generated), for a
    // progress line: "mesh dragon.obj", "generate soup 16000000". May be empty.
    std::function<void(const std::string& step)> progress;
    // Told what a mesh reader skips of a file that still loads (MeshRequest::warn). May be empty.
    std::function<void(const std::string& message)> warn;
    // Asked before a line or a mesh file makes its triangles, with the scene's count after them (a
    // generator line's, a mesh file's from its header): why they would not fit in memory, refused at
    // that line before they are made. May be empty.
    MemoryCheck memoryProblem;
};

// Reads `file`; relative paths in it (geo/obj) are resolved against its directory. A mesh file
// (.obj, .off, .ply, .gltf, .glb: isMeshFile) is read as the scene loadMeshScene makes of it (scene/mesh_scene.h).
Scene loadScene(const std::filesystem::path& file, const ParseOptions& options = {});

// Parses a scene from a stream; errors name `displayName`, `geo` paths are relative to `baseDir`.
Scene parseScene(std::istream& in, const std::string& displayName, const std::filesystem::path& baseDir,
                 const ParseOptions& options = {});

// Parses scene text held in memory (what the other two call; the fuzzer's entry point).
Scene parseSceneText(std::string_view text, const std::string& displayName, const std::filesystem::path& baseDir,
                     const ParseOptions& options = {});

}  // namespace vkray
