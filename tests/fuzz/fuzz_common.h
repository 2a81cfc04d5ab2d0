// What every libFuzzer target of tests/fuzz shares: the multi-file input format, files served from
// memory, the scene invariants checked after a load, and the rule that only a one-line vkray::Error
// is an acceptable failure. Each target (one per reader) is a few lines on top of this.
//
// Multi-file input: the first section is the main file; a line "#@ NAME" starts the file NAME, which
// runs to the next such line. To the .scene and OBJ/MTL parsers the "#@" lines are comments, so every
// such file is a seed as it is. Binary formats (PLY, GLB, images) take the input whole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <string_view>

#include "scene/scene.h"
#include "scene/text_input.h"

namespace vkray::fuzz {

// A scene may hold at most this many triangles under fuzzing, so one input costs milliseconds,
// not the minutes a `generate soup 33554432` would.
inline constexpr int64_t kMaxTriangles = int64_t(1) << 16;

struct FuzzFiles {
    std::string_view main;                                  // the first section
    std::map<std::string, std::string, std::less<>> files;  // the "#@ NAME" sections, by name
};

// `data` cut at its "#@ NAME" lines.
FuzzFiles splitFiles(std::string_view data);

// Serves `files` by file name (the directory a loader resolves against plays no part), and the
// file `mainName` (unless empty) as `main`; any other name is "not among the fuzz input's files".
FileReader memoryReader(const FuzzFiles& files, const std::string& mainName);

// Traps unless the scene keeps what every renderer relies on (scene_builder.h): a material per
// triangle that exists, normals absent or one per triangle, no more than kMaxTriangles.
void checkScene(const Scene& scene);

// Runs `load`; a vkray::Error whose message is one line (as main() prints it) is the reader doing
// its job. Anything else propagates (libFuzzer reports an uncaught exception as a crash).
void expectOnlyErrors(const std::function<void()>& load);

// The whole target for a mesh format: `data` as the file `fileName` (split into the file and the
// files it names when `multiFile`), loaded by loadMeshFile as a `geo` line would, then checked.
void fuzzMeshFile(std::string_view data, const std::string& fileName, bool multiFile);

inline std::string_view asText(const uint8_t* bytes, size_t size) {
    return {reinterpret_cast<const char*>(bytes), size};
}

}  // namespace vkray::fuzz
