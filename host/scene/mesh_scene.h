// A mesh file rendered by itself (`vkray render bunny.obj`): the scene a .scene file would have to
// write around it, built from defaults.
#pragma once

#include <filesystem>

#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray {

// The mesh of `file` (any format loadMeshFile reads: scene/mesh_file.h) as a scene:
//  - its triangles as a `geo` line loads them, untransformed, and its MTL materials where an OBJ
//    names them; faces without one get kMeshDefaultMaterial, a light grey plastic;
//  - a camera fitted to the triangles' bounds (fitCamera, scene/camera.h) looking from the front
//    (+z), above and to the right: kMeshViewDirection, up +y, the convention of most OBJ files;
//  - two directional lights placed from that camera: a key light above and to its left and a
//    dimmer fill from its right, so that no side it sees is black;
//  - the defaults of scene.h otherwise (640x480, maxdepth 5, black background, no `output`: the
//    image is MESH.png).
// Errors are the mesh reader's, naming `file`; a mesh without faces gives a scene without triangles.
Scene loadMeshScene(const std::filesystem::path& file, const ParseOptions& options = {});

// From the mesh's centre towards the eye.
inline constexpr glm::vec3 kMeshViewDirection{0.5f, 0.45f, 1.0f};

inline const Material kMeshDefaultMaterial = [] {
    Material m;
    m.ambient = glm::vec3(0.08f);
    m.diffuse = glm::vec3(0.65f, 0.65f, 0.62f);
    m.specular = glm::vec3(0.15f);
    m.shininess = 40.0f;
    return m;
}();

}  // namespace vkray
