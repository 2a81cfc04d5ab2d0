#include "scene/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "scene/gltf_loader.h"
#include "scene/obj_loader.h"
#include "scene/off_loader.h"
#include "scene/ply_loader.h"

namespace vkray {
namespace {

using MeshReader = void (*)(const MeshRequest&, SceneBuilder&);

struct MeshFormat {
    std::string_view extension;  // lower case, with the dot
    MeshReader read;
};

// One row per format; extensions compare case-insensitively.
constexpr MeshFormat kMeshFormats[] = {
    {".obj", &loadObj},
    {".off", &loadOff},
    {".ply", &loadPly},
    {".gltf", &loadGltf},
    {".glb", &loadGltf},
};

std::string lowerCase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

const MeshFormat* formatOf(const std::filesystem::path& file) {
    const std::string ext = lowerCase(file.extension().string());
    for (const MeshFormat& format : kMeshFormats)
        if (ext == format.extension) return &format;
    return nullptr;
}

// Whether `file` lies in a folder meshes/ of a folder scenes/ (the fetched meshes' place).
bool inScenesMeshes(const std::filesystem::path& file) {
    std::string previous;
    for (const std::filesystem::path& part : file.lexically_normal().parent_path()) {
        if (part == "meshes" && previous == "scenes") return true;
        previous = part.string();
    }
    return false;
}

}  // namespace

bool isMeshFile(const std::filesystem::path& file) { return formatOf(file) != nullptr; }

Error meshOpenError(const MeshRequest& request, std::string_view format, const std::string& whyNot) {
    std::error_code ec;
    const std::string hint = inScenesMeshes(request.file) && !std::filesystem::exists(request.file, ec)
                                 ? " (the meshes of scenes/ are not in the repository: scripts/fetch-scenes.sh fetches them)"
                                 : "";
    return Error(request.requestedAt,
                 "cannot open " + std::string(format) + " file '" + request.displayName + "': " + whyNot + hint);
}

void loadMeshFile(const MeshRequest& request, SceneBuilder& out) {
    if (const MeshFormat* format = formatOf(request.file)) {
        format->read(request, out);
        return;
    }
    const std::string ext = lowerCase(request.file.extension().string());
    std::string supported;
    for (const MeshFormat& format : kMeshFormats)
        supported += (supported.empty() ? "" : ", ") + std::string(format.extension);
    throw Error(request.requestedAt, "cannot load '" + request.displayName + "': unsupported mesh format '" +
                                         (ext.empty() ? std::string("(no extension)") : ext) +
                                         "' (supported: " + supported + ")");
}

}  // namespace vkray
