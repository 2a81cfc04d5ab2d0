// libFuzzer target of the .scene parser and, through `geo`, of the OBJ/MTL, OFF, PLY and glTF loaders.
//
// The input is a scene, optionally followed by mesh files: a line "#@ NAME" starts the file NAME,
// which runs to the next such line. To the scene the "#@" lines are comments, so every .scene file
// is a seed as it is. Files are served from memory (ParseOptions::readFile): a fuzzed `geo` or
// `mtllib` reaches no real file, whatever path it names. A scene may hold at most 65536 triangles,
// so one input costs milliseconds, not the minutes a `generate soup 33554432` would.
//
// A vkray::Error is the parser doing its job. Anything else (a crash, a sanitizer report, another
// exception, a leak, a time-out) is a finding.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "scene/scene_parser.h"

namespace {

constexpr std::string_view kFileMarker = "#@ ";

struct FuzzInput {
    std::string_view scene;
    std::map<std::string, std::string, std::less<>> files;  // by file name
};

FuzzInput split(std::string_view data) {
    FuzzInput in;
    std::string name;  // of the section being read; empty: the scene
    size_t start = 0, pos = 0;
    const auto close = [&](size_t end) {
        const std::string_view text = data.substr(start, end - start);
        if (name.empty())
            in.scene = text;
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
            start = next;
        }
        pos = next;
    }
    close(data.size());
    return in;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, size_t size) {
    const FuzzInput in = split(std::string_view(reinterpret_cast<const char*>(bytes), size));
    vkray::ParseOptions options;
    options.maxTriangles = 1 << 16;
    options.readFile = [&in](const std::filesystem::path& file, std::string& whyNot) -> std::optional<std::string> {
        const auto it = in.files.find(file.filename().string());
        if (it == in.files.end()) {
            whyNot = "not among the fuzz input's files";
            return std::nullopt;
        }
        return it->second;
    };
    try {
        const vkray::Scene scene = vkray::parseSceneText(in.scene, "fuzz.scene", "fuzz", options);
        // The invariants every renderer relies on (scene_builder.h): a material per triangle
        // that exists, normals either absent or one entry per triangle.
        for (const vkray::Triangle& t : scene.triangles)
            if (t.material >= scene.materials.size()) __builtin_trap();
        if (!scene.normals.empty() && scene.normals.size() != scene.triangles.size()) __builtin_trap();
        if (scene.triangles.size() > size_t(options.maxTriangles)) __builtin_trap();
    } catch (const vkray::Error& e) {
        // One line, as main() prints it: a message with a newline would break that promise.
        if (std::string_view(e.what()).find('\n') != std::string_view::npos) __builtin_trap();
    }
    return 0;
}
