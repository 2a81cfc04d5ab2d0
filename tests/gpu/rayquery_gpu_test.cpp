// The `rayquery` kernel (the driver's own structure and traversal, VK_KHR_ray_query) on every scene
// of scenes/ and scenes/primary/ (the close-ups) against the CPU reference (double precision, brute
// force's answers): the primary hits and the image within the limits every vkray accelerator is held
// to (bvh_gpu_test.cpp), the driver's structure built on the device, no pixel cut short.
// A lavapipe without ray query fails them; a GPU without it skips them (gpu_test_util.h,
// rayQuerySkipped()).
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_util.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

struct RayQueryCase {
    std::string file;  // under scenes/
    int width, height;
    friend std::ostream& operator<<(std::ostream& os, const RayQueryCase& c) {
        return os << c.file << " at " << c.width << "x" << c.height;
    }
};

class RayQueryOnGpu : public ::testing::TestWithParam<RayQueryCase> {};

TEST_P(RayQueryOnGpu, SameHitsAndImageAsReference) {
    const RayQueryCase& c = GetParam();
    if (test::rayQuerySkipped()) GTEST_SKIP() << "the device has no ray query (VKRAY_SYSTEM_MESA=1, or a GPU without it)";
    const gpu::VulkanContext* ctx = test::rayQueryContext();
    ASSERT_NE(ctx, nullptr) << "the test device has no VK_KHR_ray_query (see `vkray devices`); scripts/install-deps.sh "
                               "installs a lavapipe that has it";
    const std::filesystem::path file = std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / c.file;
    Scene scene = loadScene(file);
    // The primary-ray scenes are measured as close-ups (docs/performance.md).
    if (c.file.starts_with("primary/")) scene.camera = viewCamera(scene, "close");
    const RenderOptions options{.width = c.width, .height = c.height, .maxDepth = scene.maxDepth};

    gpu::GpuRenderReport report;
    const auto built = accel::buildAccel(scene, accel::resolveAccel("rayquery"));
    const Frame gpuFrame = gpu::renderOnGpu(*ctx, scene, options, built->gpuData(), &report);
    EXPECT_EQ(report.kernel, "rayquery");
    ASSERT_TRUE(report.driverBuildMs.has_value());
    EXPECT_GT(report.accelBytes, 0u);
    EXPECT_EQ(report.pixelsCutShort, 0u);
    // The reference with bvh's CPU traversal, which answers exactly as brute force (tests/accel).
    const auto bvh = accel::buildAccel(scene, accel::resolveAccel("bvh"));
    const Frame cpuFrame = renderReference(scene, options, *bvh->makeTracer(scene));

    const test::PrimIdAgreement hits = test::comparePrimaryHits(scene, gpuFrame, cpuFrame);
    const CompareStats stats =
        compareImages(test::quantisedColor(gpuFrame), test::quantisedColor(cpuFrame), 8.0 / 255.0);
    std::printf("measured %s rayquery vs CPU: rmse %.5f, bad %.4f%%, primid same %zu ties %zu of %zu (%.4f%%)\n",
                c.file.c_str(), stats.rmse, 100.0 * stats.badFraction, hits.same, hits.ties, hits.pixels,
                100.0 * hits.fraction());
    // The limits of every vkray accelerator (bvh_gpu_test.cpp), not loosened for the driver's own
    // triangle test and tie rule.
    EXPECT_GE(hits.fraction(), 0.999) << hits.same << " same, " << hits.ties << " ties of " << hits.pixels;
    EXPECT_LE(stats.rmse, 0.025);
    EXPECT_LE(stats.badFraction, 0.01) << stats.badPixels << " pixels differ by more than 8/255";
}

// Small images: lavapipe's ray-query traversal is far slower than vkray's kernels on it.
INSTANTIATE_TEST_SUITE_P(Scenes, RayQueryOnGpu,
                         ::testing::Values(RayQueryCase{"cornell.scene", 96, 96}, RayQueryCase{"default.scene", 96, 72},
                                           RayQueryCase{"spheres.scene", 96, 54}, RayQueryCase{"objects.scene", 96, 72},
                                           RayQueryCase{"lights.scene", 96, 72}, RayQueryCase{"bunny.scene", 64, 48},
                                           RayQueryCase{"armadillo.scene", 64, 48}, RayQueryCase{"dragon.scene", 64, 48},
                                           RayQueryCase{"diplodocus.scene", 64, 48},
                                           RayQueryCase{"elephant.scene", 64, 48},
                                           RayQueryCase{"refined-elephant.scene", 64, 48},
                                           RayQueryCase{"primary/bunny.scene", 64, 48},
                                           RayQueryCase{"primary/armadillo.scene", 64, 48},
                                           RayQueryCase{"primary/dragon.scene", 64, 48},
                                           RayQueryCase{"primary/spheres-1m.scene", 64, 48}),
                         [](const auto& info) {
                             std::string name = info.param.file.substr(0, info.param.file.size() - 6);
                             for (char& ch : name)
                                 if (ch == '-' || ch == '/') ch = '_';
                             return name;
                         });

}  // namespace
}  // namespace vkray
