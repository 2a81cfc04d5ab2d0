// Option values several subcommands parse the same way.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>
#include <glm/glm.hpp>

#include "frame/render_options.h"
#include "scene/text_input.h"

namespace vkray::cli {

// "640x480" -> (640, 480), within the image limits of scene.h; `option` names the flag in errors.
std::pair<int, int> parseSize(const std::string& text, const std::string& option = "--size");

// "1,2,4" -> {1, 2, 4}, each in [lo, hi]; "none" -> {} when allowNone.
std::vector<int> parseIntList(const std::string& text, const std::string& option, int lo, int hi, bool allowNone);

// --view, as render and bench take it (scene/camera.h, viewCamera, checks the value).
void addViewOption(CLI::App& cmd, std::string& view);

// --accel, as render (one accelerator) and bench (a comma-separated list) take it: `help` as its value
// prints accel::accelHelp() and ends the command successfully, before any other check.
CLI::Option* addAccelOption(CLI::App& cmd, std::string& accel, const std::string& description);

// A flag of four numbers, --NAME X0,X1,Y0,Y1 or pbrt-v3's --NAME X0 X1 Y0 Y1 (four arguments): `text`
// gets them joined by commas, for the parse* functions below to check.
CLI::Option* addFourNumberOption(CLI::App& cmd, const std::string& name, std::string& text,
                                 const std::string& description);

// "0.2,0.3,0.5" -> an RGB colour of three finite, non-negative numbers; `option` names the flag.
glm::vec3 parseColour(const std::string& text, const std::string& option);

// "a,b,c" -> {"a", "b", "c"}; empty items are an error.
std::vector<std::string> parseNameList(const std::string& text, const std::string& option);

// The pixels of a width x height image that one of render's window flags names (pbrt-v4's order,
// x before y, ends exclusive), each refused with its flag and value when it is malformed or not a
// non-empty part of the image:
//   --crop X0,X1,Y0,Y1          fractions of the image in [0, 1]; pixel columns ceil(X0 W) to
//                               ceil(X1 W), rows likewise, as pbrt-v4's crop window;
//   --pixel-bounds X0,X1,Y0,Y1  pixel columns [X0, X1) and rows [Y0, Y1);
//   --pixel X,Y                 the one pixel (X, Y);
//   --tile I/N                  band I of N (0 <= I < N <= H) of whole rows: rows floor(I H / N) to
//                               floor((I + 1) H / N), so N tasks cover the image exactly once.
PixelWindow parseCrop(const std::string& text, int width, int height);
PixelWindow parsePixelBounds(const std::string& text, int width, int height);
PixelWindow parsePixel(const std::string& text, int width, int height);
using TileIndex = IndexOfCount;
TileIndex parseTile(const std::string& text);
PixelWindow tileWindow(const TileIndex& tile, int width, int height);

}  // namespace vkray::cli
