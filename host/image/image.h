// A float image as read from or written to disk: PNG/BMP (values in [0, 1]) or PFM (raw floats,
// any value including +-inf). Pixels are interleaved and stored top row first, like Frame.
#pragma once

#include <cstddef>
#include <vector>

namespace vkray {

struct Image {
    int width = 0, height = 0, channels = 0;  // channels: 1 (grey / PFM "Pf") or 3 (RGB / "PF")
    std::vector<float> data;                   // width * height * channels floats, top row first

    Image() = default;
    Image(int w, int h, int c) : width(w), height(h), channels(c), data(size_t(w) * size_t(h) * size_t(c), 0.0f) {}

    size_t pixelCount() const { return size_t(width) * size_t(height); }
    // Offset of channel c of pixel column x, row y (0 = top).
    size_t offset(int x, int y, int c = 0) const {
        return (size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c);
    }
    float& at(int x, int y, int c = 0) { return data[offset(x, y, c)]; }
    float at(int x, int y, int c = 0) const { return data[offset(x, y, c)]; }
};

}  // namespace vkray
