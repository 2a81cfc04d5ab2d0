#include "fuzz_common.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "core/error.h"
#include "scene/mesh_file.h"
#include "scene/scene_builder.h"

namespace vkray::fuzz {

namespace {
constexpr std::string_view kFileMarker = "#@ ";
}

FuzzFiles splitFiles(std::string_view data) {
    FuzzFiles in;
    std::string name;  // of the section being read; empty: the main file
    bool inMain = true;
    size_t start = 0, pos = 0;
    const auto close = [&](size_t end) {
        const std::string_view text = data.substr(start, end - start);
        if (inMain)
            in.main = text;
        else
            in.files[name] = std::string(text);
    };
    while (pos < data.size()) {
        const size_t eol = std::min(data.find('\n', pos), data.size());
        const std::string_view line = data.substr(pos, eol - pos);
        const size_t next = std::min(eol + 1, data.size());
        if (line.starts_with(kFileMarker) && line.size() > kFileMarker.size()) {
            close(pos);
            name = std::string(line.substr(kFileMarker.size()));
            inMain = false;
            start = next;
        }
        pos = next;
    }
    close(data.size());
    return in;
}

FileReader memoryReader(const FuzzFiles& files, const std::string& mainName) {
    return [&files, mainName](const std::filesystem::path& file, std::string& whyNot) -> std::optional<std::string> {
        const std::string name = file.filename().string();
        if (!mainName.empty() && name == mainName) return std::string(files.main);
        const auto it = files.files.find(name);
        if (it == files.files.end()) {
            whyNot = "not among the fuzz input's files";
            return std::nullopt;
        }
        return it->second;
    };
}

void checkScene(const Scene& scene) {
    for (const Triangle& t : scene.triangles)
        if (t.material >= scene.materials.size()) __builtin_trap();
    if (!scene.normals.empty() && scene.normals.size() != scene.triangles.size()) __builtin_trap();
    if (scene.triangles.size() > size_t(kMaxTriangles)) __builtin_trap();
}

void expectOnlyErrors(const std::function<void()>& load) {
    try {
        load();
    } catch (const Error& e) {
        if (std::string_view(e.what()).find('\n') != std::string_view::npos) {
            std::fprintf(stderr, "vkray::Error of more than one line: %s\n", e.what());
            __builtin_trap();
        }
    }
}

void fuzzMeshFile(std::string_view data, const std::string& fileName, bool multiFile) {
    FuzzFiles files = multiFile ? splitFiles(data) : FuzzFiles{data, {}};
    expectOnlyErrors([&] {
        Scene scene;
        SceneBuilder builder(scene, kMaxTriangles);
        MeshRequest request;
        request.file = fileName;
        request.displayName = fileName;
        request.requestedAt = FileLoc{"fuzz.scene", 1, 1};
        request.readFile = memoryReader(files, fileName);
        request.warn = [](const std::string&) {};
        loadMeshFile(request, builder);
        builder.finish();
        checkScene(scene);
    });
}

}  // namespace vkray::fuzz
