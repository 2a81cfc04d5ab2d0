// Mesh files named by `geo FILE` / `obj FILE` in a .scene: one entry point that picks the reader by
// the file extension, so a new format (a .off reader, say) is one function and one table row.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/scene.h"
#include "scene/scene_builder.h"
#include "scene/text_input.h"
#include "scene/transform.h"

namespace vkray {

// What the scene line asks a mesh reader to do.
struct MeshRequest {
    std::filesystem::path file;  // resolved against the including scene file's directory
    std::string displayName;     // how error messages name the file (the resolved path)
    FileLoc requestedAt;         // the scene line, for errors that concern the file as a whole
    Transform toWorld;           // the current transform at that line
    Material defaultMaterial;    // the scene's material state, for faces the file gives none
    FileReader readFile;         // reads the mesh and the files it names (never empty)
    // Told what a reader skips of a file that still loads (glTF textures, points and lines), one
    // line per cause and file; may be empty.
    std::function<void(const std::string& message)> warn;
};

// Appends the file's triangles in file order. Throws vkray::Error for an unsupported extension,
// an unreadable file or bad content.
void loadMeshFile(const MeshRequest& request, SceneBuilder& out);

// Whether loadMeshFile reads files with this path's extension (.obj, .off, .ply, any case).
bool isMeshFile(const std::filesystem::path& file);

// The error of a mesh reader that cannot read request.file (`format`: "OBJ", "OFF", "PLY"), at the scene
// line that asked for it. A missing file under a scenes/meshes/ folder, where the repository's scenes look
// for the meshes scripts/fetch-scenes.sh downloads (they are not committed), names that script.
Error meshOpenError(const MeshRequest& request, std::string_view format, const std::string& whyNot);

}  // namespace vkray
