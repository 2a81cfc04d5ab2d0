// The .scene format of DESIGN.md ("Scene file"): seed 001's format, itself the UCSD CSE167 ray
// tracer format (whose *.test files load unchanged), plus `refract`, `reflect`, `spheresteps`,
// `geo`/`obj` for Wavefront OBJ and OFF meshes and `generate` for procedural ones (generators.h).
// The result is world space: transforms, spheres and meshes are resolved here, materials are
// deduplicated, and triangle order is load order (the triangle identity of DESIGN.md).
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

#include <filesystem>
#include <istream>
#include <string>

#include "scene/scene.h"

namespace vkray {

// Limits of `size` and `maxdepth` (kMaxImageSide, kMaxImagePixels, kMaxDepthLimit) live in
// scene/scene.h, shared with the command line.

// Reads `file`; relative paths in it (geo/obj) are resolved against its directory.
Scene loadScene(const std::filesystem::path& file);

// Parses a scene from a stream; errors name `displayName`, `geo` paths are relative to `baseDir`.
Scene parseScene(std::istream& in, const std::string& displayName, const std::filesystem::path& baseDir);

}  // namespace vkray
