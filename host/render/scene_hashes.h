// The hashes of one scene, each computed the first time it is asked for and kept: its geometry's
// (a structure file checks and records it, an EXR output records it) and its file's bytes (an EXR
// output records them), so that no step hashes the scene again.
#pragma once

#include <optional>
#include <string>

#include "accel/accel_file.h"
#include "scene/scene.h"

namespace vkray::render {

class SceneHashes {
public:
    SceneHashes(const std::string& file, const Scene& scene) : file_(file), scene_(scene) {}

    const accel::SceneGeometry& geometry();
    // XXH64 of the scene file's bytes, as 16 hex digits.
    const std::string& fileHash();

private:
    const std::string& file_;
    const Scene& scene_;
    std::optional<accel::SceneGeometry> geometry_;
    std::optional<std::string> fileHash_;
};

}  // namespace vkray::render
