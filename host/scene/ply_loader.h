// Stanford PLY meshes (.ply, Turk's polygon file format: the Stanford 3D Scanning Repository, most
// scanners and mesh tools) for `geo FILE` / `obj FILE` in a .scene.
#pragma once

#include "scene/mesh_file.h"

namespace vkray {

// Reads `format ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`, with the scalar
// types char/int8 ... double/float64 and list properties of any integer count type:
//  - element `vertex`: x y z (required), nx ny nz (optional, all three: smooth shading), red green
//    blue or diffuse_red diffuse_green diffuse_blue (optional: an integer type is scaled by its
//    maximum, 255 for uchar; a float is taken as it is);
//  - element `face`: the list vertex_indices (or vertex_index), 0-based, n >= 3, fanned in file
//    order (i0 i1 i2, i0 i2 i3, ...); optional red green blue of the face;
//  - every other element and property (alpha, texture coordinates, edges, ...) is read past.
// A face's diffuse colour is its own colour, else the colour of its first vertex; the rest of its
// material is request.defaultMaterial. The `vertex` element must come before `face`.
// Throws vkray::Error naming the file and, in the header and ASCII data, line:col, in binary data
// the byte offset, for: a file that is not PLY, a bad header (unknown keyword, type or format, a
// property outside an element, a vertex element without x y z, a face element without its index
// list), counts the file is too small to hold (refused before anything is reserved), a truncated
// file, a value that is not a number of its type, a face index out of range, a face of fewer than 3
// vertices, and bytes after the last element.
void loadPly(const MeshRequest& request, SceneBuilder& out);

}  // namespace vkray
