// Viridis from a small table of control points, linearly interpolated (see colormap.h).
#include "bench/colormap.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/error.h"

namespace vkray::bench {
namespace {

// Viridis at t = 0, 1/8, ..., 1 (matplotlib's values, sRGB bytes). The curve is smooth, so nine
// points linearly interpolated follow it closely; a heatmap needs no 256-entry table.
constexpr std::array<std::array<int, 3>, 9> kViridis = {{
    {68, 1, 84},  // #440154
    {71, 45, 123},  // #472d7b
    {59, 82, 139},  // #3b528b
    {44, 114, 142},  // #2c728e
    {33, 145, 140},  // #21918c
    {40, 174, 128},  // #28ae80
    {94, 201, 98},  // #5ec962
    {173, 220, 48},  // #addc30
    {253, 231, 37},  // #fde725
}};

}  // namespace

DisplayColor viridis(double t) {
    t = std::isnan(t) ? 0.0 : std::clamp(t, 0.0, 1.0);
    const double scaled = t * double(kViridis.size() - 1);
    const size_t i = std::min(size_t(scaled), kViridis.size() - 2);
    const double f = scaled - double(i);
    auto channel = [&](int c) { return float(((1.0 - f) * kViridis[i][c] + f * kViridis[i + 1][c]) / 255.0); };
    return {channel(0), channel(1), channel(2)};
}

std::string cssColor(DisplayColor c) {
    auto byte = [](float v) { return int(std::lround(255.0 * std::clamp(double(v), 0.0, 1.0))); };
    char buf[8];
    std::snprintf(buf, sizeof buf, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
    return buf;
}

Image heatmapImage(const std::vector<uint32_t>& values, int w, int h, double maxValue) {
    if (w <= 0 || h <= 0 || values.size() != size_t(w) * size_t(h))
        throw Error("heatmap of " + std::to_string(values.size()) + " values cannot be a " + std::to_string(w) + "x" +
                    std::to_string(h) + " image");
    Image image(w, h, 3);
    for (size_t i = 0; i < values.size(); ++i) {
        const double t = maxValue > 0.0 ? double(values[i]) / maxValue : values[i] > 0 ? 1.0 : 0.0;
        const DisplayColor c = viridis(t);
        image.data[3 * i] = c.r;
        image.data[3 * i + 1] = c.g;
        image.data[3 * i + 2] = c.b;
    }
    return image;
}

}  // namespace vkray::bench
