// Huge and tiny coordinates (docs/stability.md): scenes/stress/magnitude.scene moved by p -> s p + o, for
// translations o up to 1e7 and scales s down to 1e-6, stored as the loader stores it (relative to its
// local origin, Scene::origin), rendered on the GPU (bvh, the default; every kernel gives the
// brute-force kernel's hits, stress_cases_test.cpp) and by the CPU reference.
// Three figures per magnitude, printed as `| magnitude | ... |` rows (docs/stability.md):
//  - GPU against the CPU at the same magnitude: what float tracing and float ray offsets cost;
//  - CPU at that magnitude against the CPU at magnitude 1: what storing the scene in float costs
//    (in world space, vertices at 1e6 would be 1/16 apart; relative to the origin they are not);
//  - GPU at that magnitude against the CPU at magnitude 1: both.
// The scene has thin contacts (a cube and a sphere standing on the floor, a plate 0.02 and a wall
// 0.01 thick) lit at a low angle: a ray offset too small shows as shadow acne (GPU darker than the
// CPU), one too large as lost contact shadows (GPU brighter).
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "image/image_io.h"
#include "scene/scene_parser.h"
#include "stress_support.h"

namespace vkray {
namespace {

struct Mapping {
    const char* name;
    double scale, offset;
    // GPU against the CPU at the same magnitude: the fractions of primary hits differing (ties and
    // grazes, none unexplained) and of pixels off by more than 8/255 allowed, measured (stability.md):
    // none at any magnitude since the local origin (the translations are multiples of its grid but
    // 1e2 and 1e3, whose local floats are those of the scene moved by 4 and 8).
    double maxMismatch, maxBad;
};

class Magnitude : public ::testing::TestWithParam<Mapping> {};

const Scene& baseScene() {
    static const Scene s = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes/stress/magnitude.scene");
    return s;
}

const Frame& baseReference() {
    static const Frame f = [] {
        const Scene& s = baseScene();
        return renderReference(s, {.width = s.width, .height = s.height, .maxDepth = s.maxDepth});
    }();
    return f;
}

// One table row; the primid mismatches of renders of two different scenes are not classified.
void printRow(const char* name, const char* what, const stress::Disagreement& d, bool classified) {
    const std::string unexplained = classified ? std::to_string(d.unexplained()) : "-";
    std::printf("| %s | %s | %zu (%.2f%%) | %s | %.4f | %.3f | %lld (%zu darker, %zu brighter) |\n", name, what,
                d.primIdMismatches, 100.0 * d.mismatchFraction(), unexplained.c_str(), d.rmse, d.maxError,
                static_cast<long long>(d.badPixels), d.darker, d.brighter);
}

TEST_P(Magnitude, GpuFollowsTheCpuAtEveryMagnitude) {
    const Mapping& m = GetParam();
    const Scene scene = stress::mappedScene(baseScene(), m.scale, m.offset);
    const RenderOptions options{.width = scene.width, .height = scene.height, .maxDepth = scene.maxDepth};
    gpu::GpuRenderReport report;
    const Frame gpuFrame = test::renderGpu(scene, options, &report, "bvh");
    const Frame cpuFrame = renderReference(scene, options);

    const stress::Disagreement gpuVsCpu = stress::disagreement(gpuFrame, cpuFrame, &scene);
    const stress::Disagreement cpuVsBase = stress::disagreement(cpuFrame, baseReference());
    const stress::Disagreement gpuVsBase = stress::disagreement(gpuFrame, baseReference());
    printRow(m.name, "gpu vs cpu", gpuVsCpu, true);
    printRow(m.name, "cpu vs cpu at x1", cpuVsBase, false);
    printRow(m.name, "gpu vs cpu at x1", gpuVsBase, false);

    EXPECT_EQ(report.cappedRays, 0u);
    // Float against double at the same magnitude: the same primary hits but for a few float ties
    // on edges, and neither acne nor lost contacts beyond the case's bound.
    EXPECT_EQ(gpuVsCpu.unexplained(), 0u) << "primary hits differ from the CPU beyond rounding";
    EXPECT_LE(gpuVsCpu.mismatchFraction(), m.maxMismatch);
    EXPECT_LE(double(gpuVsCpu.badPixels), m.maxBad * double(gpuVsCpu.pixels))
        << gpuVsCpu.darker << " darker (acne), " << gpuVsCpu.brighter << " brighter (lost contact shadows)";
    if (HasFailure()) {
        const std::filesystem::path dir(VKRAY_TEST_OUTPUT_DIR);
        const std::string stem = std::string("magnitude-") + m.name;
        writeColorImage(dir / (stem + "-gpu.png"), gpuFrame.width, gpuFrame.height, gpuFrame.color);
        writeColorImage(dir / (stem + "-cpu.png"), cpuFrame.width, cpuFrame.height, cpuFrame.color);
    }
}

INSTANTIATE_TEST_SUITE_P(Stress, Magnitude,
                         ::testing::Values(Mapping{"x1", 1.0, 0.0, 0.0, 0.0},
                                           Mapping{"plus1e2", 1.0, 1e2, 0.0, 0.0},
                                           Mapping{"plus1e3", 1.0, 1e3, 0.0, 0.0},
                                           Mapping{"plus1e4", 1.0, 1e4, 0.0, 0.0},
                                           Mapping{"plus1e5", 1.0, 1e5, 0.0, 0.0},
                                           Mapping{"plus1e6", 1.0, 1e6, 0.0, 0.0},
                                           Mapping{"plus1e7", 1.0, 1e7, 0.0, 0.0},
                                           Mapping{"times1e-2", 1e-2, 0.0, 0.0, 0.0},
                                           Mapping{"times1e-4", 1e-4, 0.0, 0.0, 0.0},
                                           Mapping{"times1e-6", 1e-6, 0.0, 0.0, 0.0}),
                         [](const auto& info) {
                             std::string n = info.param.name;
                             for (char& c : n)
                                 if (c == '-') c = '_';
                             return n;
                         });

// The scene files far-1e6.scene and far-1e7.scene (magnitude.scene translated in the file, camera
// and point light written out at 1e6 and 1e7) through the loader, against magnitude.scene: the
// local origin takes the offset off in double, so the same renderer gives the same image but for
// pixels where an exact tie flips (sphere vertices rounded from double at the offset can move by
// one float ulp). Bounds: at most 0.5% of the pixels off by more than 8/255 on the GPU, 0.1% on
// the CPU reference.
class FarScene : public ::testing::TestWithParam<const char*> {};

TEST_P(FarScene, RendersAsAtTheOrigin) {
    const std::filesystem::path dir = std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes/stress";
    const Scene far = loadScene(dir / GetParam());
    const Scene& base = baseScene();
    EXPECT_NE(far.origin, glm::dvec3(0.0));
    const RenderOptions options{.width = base.width, .height = base.height, .maxDepth = base.maxDepth};
    const Frame gpuBase = test::renderGpu(base, options, nullptr, "bvh");
    const Frame gpuFar = test::renderGpu(far, options, nullptr, "bvh");
    const Frame cpuFar = renderReference(far, options);
    const stress::Disagreement gpu = stress::disagreement(gpuFar, gpuBase);
    const stress::Disagreement cpu = stress::disagreement(cpuFar, baseReference());
    printRow(GetParam(), "gpu vs gpu at the origin", gpu, false);
    printRow(GetParam(), "cpu vs cpu at the origin", cpu, false);
    EXPECT_LE(double(gpu.badPixels), 0.005 * double(gpu.pixels)) << "RMSE " << gpu.rmse;
    EXPECT_LE(double(cpu.badPixels), 0.001 * double(cpu.pixels)) << "RMSE " << cpu.rmse;
    // Depth is a distance: the same in the local frame as in the world.
    size_t depthDiffers = 0;
    for (size_t i = 0; i < cpuFar.depth.size(); ++i)
        if (cpuFar.primId[i] == baseReference().primId[i] &&
            std::abs(cpuFar.depth[i] - baseReference().depth[i]) > 1e-5f * std::abs(baseReference().depth[i]))
            ++depthDiffers;
    EXPECT_EQ(depthDiffers, 0u);
}

INSTANTIATE_TEST_SUITE_P(Stress, FarScene, ::testing::Values("far-1e6.scene", "far-1e7.scene"),
                         [](const auto& info) {
                             std::string n = info.param;
                             for (char& c : n)
                                 if (c == '-' || c == '.') c = '_';
                             return n;
                         });

}  // namespace
}  // namespace vkray
