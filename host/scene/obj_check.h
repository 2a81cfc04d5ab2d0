// Checks of OBJ and MTL text before tinyobjloader reads it. tinyobjloader turns what it cannot
// parse into 0 without a word ("v nan 0 0", "Kd 1e999 0 0") and reports bad face indices, if at
// all, without a useful line number; these checks name file:line:col instead. They cover only what
// vkray uses: positions, normals, face indices, and the MTL numbers of the mapping in
// docs/scene-format.md ("OBJ/MTL materials").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

namespace vkray {

// Corners an OBJ face may have. tinyobjloader triangulates a polygon by ear clipping, quadratic to
// cubic in its corners, so a hostile file with one huge polygon would stall the load. Real models
// stay far below (a cylinder cap of 256 sides is a large polygon).
inline constexpr size_t kMaxObjFaceCorners = 1024;

struct ObjSummary {
    uint64_t triangles = 0;  // what the faces make once triangulated: corners - 2 each
};

// `context` is appended to every message, e.g. " (OBJ loaded by 'geo' at a.scene:3)".
// Throws vkray::Error(FileLoc{displayName, line, col}, ...) on:
//  - binary data (NUL bytes) or UTF-16;
//  - a statement that is not OBJ (a .scene file named .obj, say), or OBJ that tinyobjloader would
//    skip without a word although it holds geometry: free-form curves and surfaces, `call` and
//    `csh` (file inclusion and shell commands), the old `fo` spelling of `f`;
//  - `v` without 3..7 numbers, `vn` without exactly 3, any of them not a finite float;
//  - `f` with fewer than 3 or more than kMaxObjFaceCorners vertices, or an index (position,
//    texcoord or normal) that is 0, not an integer, or outside the elements the file defines
//    (negative = relative, OBJ rules).
ObjSummary checkObjText(std::string_view text, const std::string& displayName, const std::string& context);

// Ka Kd Ks Ke Tf Kt need 3 finite numbers; Ns Ni d Tr need 1 (texture maps are not checked).
void checkMtlText(std::string_view text, const std::string& displayName, const std::string& context);

}  // namespace vkray
