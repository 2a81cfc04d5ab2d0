#include "scene/mesh_file.h"

#include <algorithm>
#include <cctype>
#include <string_view>

#include "scene/obj_loader.h"
#include "scene/off_loader.h"

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
};

std::string lowerCase(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

}  // namespace

void loadMeshFile(const MeshRequest& request, SceneBuilder& out) {
    const std::string ext = lowerCase(request.file.extension().string());
    for (const MeshFormat& format : kMeshFormats) {
        if (ext == format.extension) {
            format.read(request, out);
            return;
        }
    }
    std::string supported;
    for (const MeshFormat& format : kMeshFormats)
        supported += (supported.empty() ? "" : ", ") + std::string(format.extension);
    throw Error(request.requestedAt, "cannot load '" + request.displayName + "': unsupported mesh format '" +
                                         (ext.empty() ? std::string("(no extension)") : ext) +
                                         "' (supported: " + supported + ")");
}

}  // namespace vkray
