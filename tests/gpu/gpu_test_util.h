// Shared by the GPU tests: one Vulkan context per test binary (validation always on: a validation
// error fails the test that caused it), and Frame comparisons.
#pragma once

#include <cstdlib>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "gpu/vulkan_context.h"
#include "image/compare.h"
#include "image/image.h"
#include "render/frame.h"

namespace vkray::test {

// VKRAY_TEST_DEVICE picks the device (index or name substring); default: vkray's usual choice,
// which is lavapipe on a machine without a GPU.
inline const gpu::VulkanContext& gpuContext() {
    static std::unique_ptr<gpu::VulkanContext> ctx = [] {
        const char* dev = std::getenv("VKRAY_TEST_DEVICE");
        return std::make_unique<gpu::VulkanContext>(
            gpu::ContextOptions{.validation = true, .device = dev ? dev : ""});
    }();
    return *ctx;
}

// The colour of a Frame as it would be written to an 8-bit file (clamped, quantised).
inline Image quantisedColor(const Frame& f) {
    Image img(f.width, f.height, 3);
    for (size_t i = 0; i < f.color.size(); ++i)
        for (int c = 0; c < 3; ++c) {
            const float v = std::min(std::max(f.color[i][c], 0.0f), 1.0f);
            img.data[i * 3 + size_t(c)] = std::round(v * 255.0f) / 255.0f;
        }
    return img;
}

// Fraction of pixels whose primary-hit triangle is the same in both frames.
inline double primIdAgreement(const Frame& a, const Frame& b) {
    size_t same = 0;
    for (size_t i = 0; i < a.primId.size(); ++i) same += a.primId[i] == b.primId[i];
    return a.primId.empty() ? 1.0 : double(same) / double(a.primId.size());
}

}  // namespace vkray::test
