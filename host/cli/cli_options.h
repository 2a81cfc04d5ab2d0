// Option values several subcommands parse the same way.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

namespace vkray::cli {

// "640x480" -> (640, 480), within the image limits of scene.h; `option` names the flag in errors.
std::pair<int, int> parseSize(const std::string& text, const std::string& option = "--size");

// "1,2,4" -> {1, 2, 4}, each in [lo, hi]; "none" -> {} when allowNone.
std::vector<int> parseIntList(const std::string& text, const std::string& option, int lo, int hi, bool allowNone);

// --view, as render and bench take it (scene/camera.h, viewCamera, checks the value).
void addViewOption(CLI::App& cmd, std::string& view);

// "0.2,0.3,0.5" -> an RGB colour of three finite, non-negative numbers; `option` names the flag.
glm::vec3 parseColour(const std::string& text, const std::string& option);

// "a,b,c" -> {"a", "b", "c"}; empty items are an error.
std::vector<std::string> parseNameList(const std::string& text, const std::string& option);

}  // namespace vkray::cli
