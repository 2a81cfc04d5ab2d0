// Texel arrays split over several views of a binding (gpu/buffer.h, bindings.glsl): on a context that
// pretends one view holds few texels, every accelerator renders a scene with smooth normals,
// several materials and lights through split arrays, pixel for pixel as through one view each.
#include <algorithm>
#include <bit>
#include <cstring>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "core/error.h"
#include "gpu/buffer.h"
#include "gpu/scene_buffers.h"
#include "gpu_test_util.h"
#include "scene/scene_parser.h"
#include "support/window_check.h"

namespace vkray {
namespace {

// A context like the test device, except that one view holds at most `texels` texels (and, for
// rayquery, with the driver's ray tracing).
gpu::VulkanContext contextWithViewsOf(uint64_t texels, bool rayQuery = false) {
    gpu::ContextOptions options = test::gpuContextOptions();
    options.maxTexelsPerView = texels;
    options.rayQuery = rayQuery;
    return gpu::VulkanContext(options);
}

uint64_t largestArray(const Scene& scene, const accel::GpuAccelData& data) {
    uint64_t largest = 0;
    for (const gpu::TexelArraySize& a : gpu::texelArraySizes(gpu::packScene(scene, data.triangleOrder), data))
        largest = std::max(largest, a.texels);
    return largest;
}

TEST(TexelViews, EveryAcceleratorRendersTheSamePixelsThroughSplitArrays) {
    const Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / "objects.scene");
    ASSERT_TRUE(scene.hasSmoothNormals());
    RenderOptions o{.width = 64, .height = 48, .maxDepth = 3};
    for (const std::string& name : accel::accelNames()) {
        SCOPED_TRACE(name);
        const accel::AccelSpec spec = accel::resolveAccel(name);
        const bool driver = spec.family == accel::Family::Driver;
        if (driver && test::rayQuerySkipped()) continue;
        const gpu::VulkanContext* ctx = driver ? test::rayQueryContext() : &test::gpuContext();
        ASSERT_NE(ctx, nullptr) << "the test device has no VK_KHR_ray_query (see `vkray devices`)";
        const auto built = accel::buildAccel(scene, spec);
        const accel::GpuAccelData data = built->gpuData();
        gpu::GpuRenderReport whole, split;
        const Frame reference = gpu::renderOnGpu(*ctx, scene, o, data, &whole);
        ASSERT_EQ(whole.features.texelViewBits, 0);
        // Views of a power of two of texels such that the largest array takes 5 to 8 of them.
        const uint64_t perView = std::bit_ceil((largestArray(scene, data) + VKRAY_TEXEL_VIEWS - 1) / VKRAY_TEXEL_VIEWS);
        const gpu::VulkanContext small = contextWithViewsOf(perView, driver);
        const Frame viaViews = gpu::renderOnGpu(small, scene, o, data, &split);
        EXPECT_EQ(split.features.texelViewBits, std::countr_zero(perView));
        test::expectSamePixels(reference, viaViews, PixelWindow{0, 0, o.width, o.height});
        EXPECT_EQ(split.raysTraced, whole.raysTraced);
        EXPECT_EQ(split.shadowRays, whole.shadowRays);
    }
}

TEST(TexelViews, ViewBitsOnlyWhenAnArrayOutgrowsOneView) {
    const gpu::VulkanContext ctx = contextWithViewsOf(1000);  // views of 512 texels once split
    const std::vector<gpu::TexelArraySize> fit{{"triangles", 1000}, {"nodes", 7}};
    EXPECT_EQ(gpu::texelViewBits(ctx, fit), 0);
    const std::vector<gpu::TexelArraySize> over{{"triangles", 1001}, {"nodes", 7}};
    EXPECT_EQ(gpu::texelViewBits(ctx, over), 9);
    EXPECT_EQ(gpu::maxTexelArray(ctx), uint64_t(VKRAY_TEXEL_VIEWS) * 512);
    const std::vector<gpu::TexelArraySize> tooLong{{"triangles", 10}, {"vertex normals", VKRAY_TEXEL_VIEWS * 512 + 1}};
    try {
        gpu::texelViewBits(ctx, tooLong);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("vertex normals"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("maxTexelBufferElements"), std::string::npos) << e.what();
    }
}

TEST(TexelViews, ASplitArrayIsUploadedViewByView) {
    const gpu::VulkanContext ctx = contextWithViewsOf(64);
    std::vector<uint32_t> words(4 * 150);  // 150 texels of 16 bytes: views of 64, 64 and 22
    for (size_t i = 0; i < words.size(); ++i) words[i] = uint32_t(i);
    const gpu::TexelArray array = gpu::uploadTexelArray(ctx, words.data(), words.size() * 4,
                                                        vk::Format::eR32G32B32A32Uint, 16, "test words", 6);
    ASSERT_EQ(array.views.size(), 3u);
    ASSERT_EQ(array.buffers.size(), 3u);
    EXPECT_EQ(array.buffers[0].size(), 64u * 16);
    EXPECT_EQ(array.buffers[2].size(), 22u * 16);
    if (array.buffers[2].hostVisible()) {
        EXPECT_EQ(static_cast<const uint32_t*>(array.buffers[2].mapped())[0], 4u * 128);
    }
}

// An array of several 4 MiB runs and a tail is copied into its buffer by all workers (parallelCopy):
// every word must arrive, the last run's included.
TEST(TexelViews, ALargeArrayIsCopiedWhole) {
    const auto& ctx = test::gpuContext();
    std::vector<uint32_t> words(4 * ((size_t(5) << 18) + 3));  // 5 Mi + 3 texels of 16 bytes: 20 MiB and 48 bytes
    for (size_t i = 0; i < words.size(); ++i) words[i] = uint32_t(i * 2654435761u);
    const gpu::TexelArray array = gpu::uploadTexelArray(ctx, words.data(), words.size() * 4,
                                                        vk::Format::eR32G32B32A32Uint, 16, "test words");
    ASSERT_EQ(array.buffers.size(), 1u);
    if (!array.buffers[0].hostVisible()) GTEST_SKIP() << "device-local memory the host cannot read back";
    EXPECT_EQ(std::memcmp(array.buffers[0].mapped(), words.data(), words.size() * 4), 0);
}

}  // namespace
}  // namespace vkray
