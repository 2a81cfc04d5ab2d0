// The JSON types of the glTF 2.0 members vkray reads, checked before tinygltf sees the file:
// tinygltf skips a member of the wrong type without a word ("mesh": "0" reads as no mesh) and
// converts numbers to its integer fields unchecked, so a file that breaks the schema there would
// load as something else than it says.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace vkray {

// The JSON text of a glTF file: the file itself, or a GLB's JSON chunk; nothing when `bytes` is a
// GLB whose header or first chunk is not well formed (tinygltf then says what is wrong).
std::optional<std::string_view> gltfJsonText(std::string_view bytes);

struct GltfJsonCheck {
    // Why the JSON does not follow the glTF 2.0 schema in the members vkray reads ("nodes[2].mesh
    // is a string, expected a non-negative integer"); nothing when it does, or when it is no JSON
    // at all (tinygltf names the place of a syntax error).
    std::optional<std::string> typeProblem;
    // The file's extensionsRequired, known before tinygltf reads it (which fails on the accessors
    // of a compressed mesh before it can be asked for them).
    std::vector<std::string> extensionsRequired;
};
GltfJsonCheck checkGltfJson(std::string_view json);

}  // namespace vkray
