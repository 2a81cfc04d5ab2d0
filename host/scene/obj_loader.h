// Wavefront OBJ (+ MTL) through tinyobjloader, for `geo FILE` / `obj FILE` in a .scene.
#pragma once

#include "scene/mesh_file.h"

namespace vkray {

// Appends the OBJ's faces in file order (polygons triangulated by tinyobjloader, triangulate=true:
// docs/scene-format.md, "Triangle identity"), transformed by request.toWorld. Faces with a material of the MTL
// get its mapping (mtl_material.h); faces without one get request.defaultMaterial. A face whose
// three corners all name a normal (vn) is smooth-shaded with them; a zero vn leaves it flat.
// The MTL files are looked up next to the OBJ. Throws vkray::Error for an unreadable OBJ or MTL,
// what checkObjText/checkMtlText reject, tinyobjloader errors, and its warnings except two
// harmless ones (both `d` and `Tr` given; a `g` without a name). An OBJ without faces adds nothing.
void loadObj(const MeshRequest& request, SceneBuilder& out);

}  // namespace vkray
