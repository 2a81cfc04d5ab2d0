// Helpers of the scene tests: parse scene text in memory, with `geo` paths relative to data/.
#pragma once

#include <filesystem>
#include <sstream>
#include <string>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "core/error.h"
#include "scene/scene_parser.h"

namespace vkray::test {

inline std::filesystem::path sceneDataDir() {
    return std::filesystem::path(VKRAY_SOURCE_DIR) / "tests" / "scene" / "data";
}

inline Scene parseText(const std::string& text) {
    std::istringstream in(text);
    return parseScene(in, "test.scene", sceneDataDir());
}

// The message of the vkray::Error that parsing `text` throws, or "(no error)".
inline std::string parseError(const std::string& text) {
    try {
        parseText(text);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace vkray::test

// Component-wise EXPECT_NEAR of two glm vectors, reported at the caller's line.
#define EXPECT_VEC3_NEAR(actual, expected, tolerance)            \
    do {                                                         \
        const glm::vec3 a_ = (actual), e_ = (expected);          \
        EXPECT_NEAR(a_.x, e_.x, (tolerance)) << #actual << ".x"; \
        EXPECT_NEAR(a_.y, e_.y, (tolerance)) << #actual << ".y"; \
        EXPECT_NEAR(a_.z, e_.z, (tolerance)) << #actual << ".z"; \
    } while (0)
