#include "cli/cli_options.h"

#include <charconv>
#include <cmath>
#include <regex>
#include <sstream>

#include "core/error.h"
#include "scene/scene.h"

namespace vkray::cli {

std::pair<int, int> parseSize(const std::string& text, const std::string& option) {
    std::smatch m;
    static const std::regex pattern(R"((\d{1,9})[xX](\d{1,9}))");
    if (!std::regex_match(text, m, pattern))
        throw Error(option + " " + text + ": expected WIDTHxHEIGHT, for example 640x480");
    const long long w = std::stoll(m[1]), h = std::stoll(m[2]);
    if (const auto problem = imageSizeProblem(w, h)) throw Error(option + " " + text + ": " + *problem);
    return {int(w), int(h)};
}

void addViewOption(CLI::App& cmd, std::string& view) {
    cmd.add_option("--view", view,
                   "Camera: scene (its own), close (a close-up of its triangles, where most camera rays hit) or "
                   "EX,EY,EZ,CX,CY,CZ[,FOVY] (eye, look-at centre, fovy; up from the scene)")
        ->default_str("scene");
}

glm::vec3 parseColour(const std::string& text, const std::string& option) {
    const std::vector<std::string> items = parseNameList(text, option);
    glm::vec3 c(0.0f);
    bool ok = items.size() == 3;
    for (size_t i = 0; ok && i < 3; ++i) {
        const char* begin = items[i].data();
        const char* end = begin + items[i].size();
        const auto [ptr, ec] = std::from_chars(begin, end, c[int(i)]);
        ok = ec == std::errc() && ptr == end && std::isfinite(c[int(i)]) && c[int(i)] >= 0.0f;
    }
    if (!ok) throw Error(option + " " + text + ": expected R,G,B, three non-negative numbers, for example 0.2,0.3,0.5");
    return c;
}

std::vector<std::string> parseNameList(const std::string& text, const std::string& option) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');) {
        if (item.empty()) throw Error(option + " " + text + ": empty item in the comma-separated list");
        out.push_back(item);
    }
    if (out.empty()) throw Error(option + ": expected a comma-separated list");
    return out;
}

std::vector<int> parseIntList(const std::string& text, const std::string& option, int lo, int hi, bool allowNone) {
    if (allowNone && text == "none") return {};
    std::vector<int> out;
    for (const std::string& item : parseNameList(text, option)) {
        int v = 0;
        const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
        if (ec != std::errc() || end != item.data() + item.size() || v < lo || v > hi)
            throw Error(option + " " + text + ": '" + item + "' is not an integer in " + std::to_string(lo) +
                        ".." + std::to_string(hi) + (allowNone ? " (or the whole list 'none')" : ""));
        out.push_back(v);
    }
    return out;
}

}  // namespace vkray::cli
