#include "cli/cli_options.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <regex>
#include <sstream>

#include "accel/accel_spec.h"
#include "core/error.h"
#include "scene/scene.h"
#include "scene/text_input.h"

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
    cmd.add_option("--view,--camera", view,
                   "scene, fit (all in view), close, or EX,EY,EZ,CX,CY,CZ[,FOVY]")
        ->type_name("V")
        ->default_str("scene");
}

CLI::Option* addAccelOption(CLI::App& cmd, std::string& accel, const std::string& description) {
    // Checked as it is parsed, so that `vkray render --accel help` needs no scene.
    return cmd
        .add_option_function<std::string>(
            "--accel",
            [&accel](const std::string& value) {
                if (value == "help") {
                    std::fputs(accel::accelHelp().c_str(), stdout);
                    throw CLI::Success();
                }
                accel = value;
            },
            description)
        ->trigger_on_parse()
        ->type_name("NAME");
}

CLI::Option* addFourNumberOption(CLI::App& cmd, const std::string& name, std::string& text,
                                 const std::string& description) {
    return cmd
        .add_option_function<std::vector<std::string>>(
            name,
            [&text](const std::vector<std::string>& values) {
                text.clear();
                for (const std::string& v : values) text += (text.empty() ? "" : ",") + v;
            },
            description)
        ->expected(1, 4)
        ->allow_extra_args(false)
        ->delimiter(',')  // so that X0,X1,Y0,Y1 counts four and the scene after it stays a scene
        ->type_name("X0,X1,Y0,Y1");
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

namespace {

// "a,b,c,d" (or "a b c d") -> exactly `count` finite numbers, else the flag's usage.
std::vector<double> parseNumbers(const std::string& text, size_t count, const std::string& usage) {
    const std::optional<std::vector<double>> v = parseRealList(text);
    if (!v || v->size() != count) throw Error(usage);
    return *v;
}

std::vector<int> parsePixelNumbers(const std::string& text, size_t count, const std::string& usage) {
    std::vector<int> out;
    for (const double x : parseNumbers(text, count, usage)) {
        if (x != std::floor(x) || std::fabs(x) > 1e9) throw Error(usage);
        out.push_back(int(x));
    }
    return out;
}

PixelWindow checked(const PixelWindow& w, const std::string& option, const std::string& text, int width, int height) {
    if (const auto problem = windowProblem(w, width, height)) throw Error(option + " " + text + ": " + *problem);
    return w;
}

}  // namespace

PixelWindow parseCrop(const std::string& text, int width, int height) {
    const std::vector<double> f =
        parseNumbers(text, 4, "--crop " + text + ": expected X0,X1,Y0,Y1, fractions of the image in [0, 1]");
    for (const double x : f)
        if (x < 0.0 || x > 1.0) throw Error("--crop " + text + ": the fractions must lie in [0, 1]");
    const auto at = [](double fraction, int size) { return int(std::ceil(fraction * double(size))); };
    return checked({at(f[0], width), at(f[2], height), at(f[1], width), at(f[3], height)}, "--crop", text, width,
                   height);
}

PixelWindow parsePixelBounds(const std::string& text, int width, int height) {
    const std::vector<int> p =
        parsePixelNumbers(text, 4, "--pixel-bounds " + text + ": expected X0,X1,Y0,Y1, whole pixel numbers");
    return checked({p[0], p[2], p[1], p[3]}, "--pixel-bounds", text, width, height);
}

PixelWindow parsePixel(const std::string& text, int width, int height) {
    const std::vector<int> p = parsePixelNumbers(text, 2, "--pixel " + text + ": expected X,Y, a pixel's column and row");
    return checked({p[0], p[1], p[0] + 1, p[1] + 1}, "--pixel", text, width, height);
}

TileIndex parseTile(const std::string& text) {
    const std::optional<TileIndex> t = parseIndexOfCount(text);
    if (!t) throw Error("--tile " + text + ": expected I/N, tile I (counted from 0) of N, for example 0/4");
    if (t->count < 1 || t->index >= t->count)
        throw Error("--tile " + text + ": I must be 0.." + std::to_string(std::max(t->count - 1, 0)) +
                    " (tiles count from 0)");
    return *t;
}

PixelWindow tileWindow(const TileIndex& tile, int width, int height) {
    if (tile.count > height)
        throw Error("--tile " + std::to_string(tile.index) + "/" + std::to_string(tile.count) + ": more tiles than the " +
                    std::to_string(height) + " rows of the image");
    const auto row = [&](int i) { return int(int64_t(i) * height / tile.count); };
    return {0, row(tile.index), width, row(tile.index + 1)};
}

}  // namespace vkray::cli
