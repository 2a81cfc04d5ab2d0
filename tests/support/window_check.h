// Shared by the CPU and GPU renderer tests: a render of a window (RenderOptions::window) against
// the same pixels of a render of the whole image.
#pragma once

#include <gtest/gtest.h>

#include "frame/frame.h"
#include "frame/render_options.h"

namespace vkray::test {

// Each pixel of `window` (image coordinates) is bit for bit the same pixel of `whole`: colour,
// depth, triangle and normal.
inline void expectSamePixels(const Frame& whole, const Frame& window, const PixelWindow& w) {
    ASSERT_EQ(window.width, w.width());
    ASSERT_EQ(window.height, w.height());
    EXPECT_EQ(window.x0, w.x0);
    EXPECT_EQ(window.y0, w.y0);
    for (int j = 0; j < window.height; ++j)
        for (int i = 0; i < window.width; ++i) {
            const size_t a = whole.index(w.x0 + i, w.y0 + j), b = window.index(i, j);
            ASSERT_EQ(whole.color[a], window.color[b]) << "pixel " << w.x0 + i << "," << w.y0 + j;
            ASSERT_EQ(whole.depth[a], window.depth[b]);
            ASSERT_EQ(whole.primId[a], window.primId[b]);
            ASSERT_EQ(whole.normal[a], window.normal[b]);
        }
}

}  // namespace vkray::test
