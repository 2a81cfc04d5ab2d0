#include "render/scene_hashes.h"

#include <cstdio>
#include <fstream>
#include <iterator>

#include "core/hash64.h"

namespace vkray::render {

const accel::SceneGeometry& SceneHashes::geometry() {
    if (!geometry_) geometry_.emplace(scene_);
    return *geometry_;
}

const std::string& SceneHashes::fileHash() {
    if (!fileHash_) {
        std::ifstream in(file_, std::ios::binary);
        const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        char text[24];
        std::snprintf(text, sizeof text, "%016llx", (unsigned long long)hash64(bytes.data(), bytes.size()));
        fileHash_ = text;
    }
    return *fileHash_;
}

}  // namespace vkray::render
