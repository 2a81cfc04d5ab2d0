// Object File Format (.off, Geomview/Princeton) meshes for `geo FILE` / `obj FILE` in a .scene:
// the format of the CGAL sample meshes (Armadillo, Chinese dragon, elephant, ...).
#pragma once

#include "scene/mesh_file.h"

namespace vkray {

// Reads the ASCII form, line by line:
//   OFF                    (or COFF: vertex colours; the counts may follow on the same line)
//   nv nf [ne]             (the edge count is ignored)
//   x y z                  nv vertex lines (COFF: x y z r g b [a], the colour ignored)
//   n i0 i1 ... i(n-1)     nf face lines, n >= 3, 0-based indices, an optional face colour ignored
// '#' starts a comment anywhere, blank lines are skipped. Faces are fan-triangulated in file order
// (i0 i1 i2, i0 i2 i3, ...: the triangle identity of docs/scene-format.md for OFF), flat-shaded,
// transformed by request.toWorld, with request.defaultMaterial (OFF has no materials).
// Throws vkray::Error naming file:line:col (with the scene line that loaded it) for: a missing or
// unsupported header (NOFF, 4OFF, binary OFF, ...), counts that are not integers or that the file is
// too small to hold (a lying header must not allocate gigabytes), a vertex value that is not a
// finite float, a face with fewer than 3 vertices or an index outside 0..nv-1, a truncated file
// (fewer vertex or face lines than counted) and anything after the last face.
void loadOff(const MeshRequest& request, SceneBuilder& out);

}  // namespace vkray
