// Checks of OBJ and MTL text before tinyobjloader reads it. tinyobjloader turns what it cannot
// parse into 0 without a word ("v nan 0 0", "Kd 1e999 0 0") and reports bad face indices, if at
// all, without a useful line number; these checks name file:line:col instead. They cover only what
// vkray uses: positions, normals, face indices, and the MTL numbers of DESIGN.md's mapping.
#pragma once

#include <string>
#include <string_view>

namespace vkray {

// `context` is appended to every message, e.g. " (OBJ loaded by 'geo' at a.scene:3)".
// Throws vkray::Error(FileLoc{displayName, line, col}, ...) on:
//  - binary data (NUL bytes) or UTF-16;
//  - `v` without 3..7 numbers, `vn` without exactly 3, any of them not a finite float;
//  - `f` with fewer than 3 vertices, or an index (position, texcoord or normal) that is 0,
//    not an integer, or outside the elements the file defines (negative = relative, OBJ rules).
void checkObjText(std::string_view text, const std::string& displayName, const std::string& context);

// Ka Kd Ks Ke Tf Kt need 3 finite numbers; Ns Ni d Tr need 1 (texture maps are not checked).
void checkMtlText(std::string_view text, const std::string& displayName, const std::string& context);

}  // namespace vkray
