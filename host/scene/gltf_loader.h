// glTF 2.0 scenes (.gltf with external or embedded base64 buffers, and binary .glb) for
// `geo FILE` / `obj FILE` in a .scene, read through tinygltf and flattened into triangles.
#pragma once

#include "scene/mesh_file.h"

namespace vkray {

// Loads the default scene (else the first; else every node that is no node's child) with its node
// hierarchy: each node's matrix or translation * rotation * scale, applied under request.toWorld.
// Mesh primitives of mode TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN, indexed or not, with smooth
// shading from NORMAL when present, become triangles in node order (depth first, children in file
// order) and primitive order; strips and fans follow the glTF 2.0 specification's vertex order.
// Materials map to the Whitted model by materialFromGltf (gltf_material.h); a primitive without one
// gets request.defaultMaterial. A mesh drawn by several nodes is copied per node.
// Skipped, each with one request.warn line per file: primitives of points or lines, textures (the
// factors alone colour the surface), skins and morph targets (the rest pose is drawn), and meshes
// drawn by several nodes (the count of copies). Cameras, lights, animations are ignored; a node
// whose transform is singular (a zero scale) draws nothing.
// Throws vkray::Error naming the file for: JSON or GLB structure tinygltf refuses, a missing buffer
// file, an extension in extensionsRequired other than those materialFromGltf reads, a node graph
// that is not a forest (a cycle, a node with two parents), an index (node, mesh, accessor, buffer
// view, buffer, material, vertex) out of range, an accessor of the wrong type or reaching past its
// buffer view or buffer, a sparse accessor, a non-finite position or transform.
void loadGltf(const MeshRequest& request, SceneBuilder& out);

}  // namespace vkray
