// Shared by the GPU tests: one Vulkan context per test binary (validation always on: a validation
// error fails the test that caused it), and Frame comparisons.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "accel/accel_spec.h"
#include "frame/frame.h"
#include "geometry/ray.h"
#include "geometry/ray_triangle.h"
#include "gpu/gpu_renderer.h"
#include "gpu/lockstep.h"
#include "gpu/vulkan_context.h"
#include "image/compare.h"
#include "image/image.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "scene/scene_parser.h"

namespace vkray::test {

// The test device's options: VKRAY_TEST_DEVICE picks it (index or name substring); default:
// vkray's usual choice, which is lavapipe on a machine without a GPU. Validation always on.
inline gpu::ContextOptions gpuContextOptions() {
    const char* dev = std::getenv("VKRAY_TEST_DEVICE");
    return gpu::ContextOptions{.validation = true, .device = dev ? dev : ""};
}

inline const gpu::VulkanContext& gpuContext() {
    static std::unique_ptr<gpu::VulkanContext> ctx = std::make_unique<gpu::VulkanContext>(gpuContextOptions());
    return *ctx;
}

// The test device with the driver's ray tracing enabled (`--accel rayquery`), one per test binary;
// null when the device has none. On lavapipe its tests fail then rather than skip: `make test`
// installs a lavapipe that has it (Mesa from bookworm-backports, scripts/install-deps.sh); only with
// VKRAY_SYSTEM_MESA=1, the install's opt-out that keeps Debian's own Mesa, are they skipped. On any
// other device (VKRAY_TEST_DEVICE naming a GPU) ray query is the hardware's to have or not (the
// data-centre GPUs have no ray-tracing units), so they are skipped there (rayQuerySkipped()).
inline const gpu::VulkanContext* rayQueryContext() {
    static const std::unique_ptr<gpu::VulkanContext> ctx = []() -> std::unique_ptr<gpu::VulkanContext> {
        gpu::ContextOptions options = gpuContextOptions();
        if (!gpu::VulkanContext(options).info().rayQuery) return nullptr;
        options.rayQuery = true;
        return std::make_unique<gpu::VulkanContext>(options);
    }();
    return ctx.get();
}

inline bool rayQuerySkipped() {
    if (rayQueryContext()) return false;
    const char* v = std::getenv("VKRAY_SYSTEM_MESA");
    const bool systemMesa = v && std::string_view(v) == "1";
    const bool lavapipe = gpuContext().info().driver.starts_with("llvmpipe");
    if (!systemMesa && lavapipe) return false;
    static const int said = std::fprintf(stderr, "rayquery skipped: %s has no VK_KHR_ray_query\n",
                                         gpuContext().info().name.c_str());
    (void)said;
    return true;
}

// Builds `spec`'s structure with options.threads workers and renders it on ctx's device.
inline Frame renderGpu(const gpu::VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                       const accel::AccelSpec& spec, gpu::GpuRenderReport* report = nullptr) {
    const auto built = accel::buildAccel(scene, spec, {.threads = options.threads, .progress = {}});
    return gpu::renderOnGpu(ctx, scene, options, built->gpuData(), report);
}

// The same with the accelerator named `accel` (`brute`, the reference the GPU tests compare with,
// unless told).
inline Frame renderGpu(const gpu::VulkanContext& ctx, const Scene& scene, const RenderOptions& options,
                       gpu::GpuRenderReport* report = nullptr, std::string_view accel = "brute") {
    return renderGpu(ctx, scene, options, accel::resolveAccel(accel), report);
}

// The same on the test device.
inline Frame renderGpu(const Scene& scene, const RenderOptions& options, gpu::GpuRenderReport* report = nullptr,
                       std::string_view accel = "brute") {
    return renderGpu(gpuContext(), scene, options, report, accel);
}

// Pixels whose primary triangle, depth or colour differ between two frames of one size, bit for bit.
inline size_t differingPixels(const Frame& a, const Frame& b) {
    size_t differing = 0;
    for (size_t i = 0; i < a.color.size(); ++i)
        differing += a.primId[i] != b.primId[i] || a.depth[i] != b.depth[i] || a.color[i][0] != b.color[i][0] ||
                     a.color[i][1] != b.color[i][1] || a.color[i][2] != b.color[i][2];
    return differing;
}

// A packet accelerator against the single-ray walk of the same tree: on five hand-made scenes at
// 125x93 (odd sizes leave tiles whose last subgroups have lanes outside the image; the Whitted
// scenes trace packets of the lanes whose pixels still have rays pending) the frames are the same
// bit for bit, and so are the rays traced and, with `sameTriangles`, the triangles tested. The
// packet runs `packetKernel`, or on a device without subgroup ballot the single walk's kernel.
inline void expectPacketMatchesSingleRay(std::string_view single, std::string_view singleKernel, std::string_view packet,
                                         std::string_view packetKernel, bool sameTriangles) {
    for (const char* file : {"cornell.scene", "default.scene", "lights.scene", "objects.scene", "spheres.scene"}) {
        const Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / file);
        const RenderOptions options{.width = 125, .height = 93, .maxDepth = scene.maxDepth, .countTraversal = sameTriangles};
        gpu::GpuRenderReport stack, packed;
        const Frame a = renderGpu(scene, options, &stack, single);
        const Frame b = renderGpu(scene, options, &packed, packet);
        EXPECT_EQ(packed.kernel, gpuContext().info().subgroupBallot ? packetKernel : singleKernel);
        EXPECT_EQ(packed.pixelsCutShort, 0u) << file;
        EXPECT_EQ(packed.raysTraced, stack.raysTraced) << file;
        EXPECT_EQ(packed.shadowRays, stack.shadowRays) << file;
        if (sameTriangles) {
            EXPECT_EQ(packed.trianglesTested, stack.trianglesTested) << file;
        }
        ASSERT_EQ(a.color.size(), b.color.size()) << file;
        EXPECT_EQ(differingPixels(a, b), 0u) << file;
    }
}

// Which rays a packet accelerator walks as packets: its camera rays alone (traceCamera,
// accelerator.glsl). With reflections, refractions and shadow rays added to the same camera rays,
// the idle steps, which only a packet walk counts, stay those of the camera rays, one a pixel.
inline void expectOnlyCameraRaysInPackets(std::string_view packet) {
    if (!gpuContext().info().subgroupBallot) GTEST_SKIP() << "no subgroup ballot: the packet runs the single walk";
    for (const char* file : {"cornell.scene", "spheres.scene"}) {
        const Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / file);
        Scene unlit = scene;
        unlit.lights.clear();
        RenderOptions options{.width = 96, .height = 72, .maxDepth = 1, .countTraversal = true};
        gpu::GpuRenderReport camera, full;
        renderGpu(unlit, options, &camera, packet);
        options.maxDepth = 4;
        renderGpu(scene, options, &full, packet);
        const uint64_t pixels = uint64_t(options.width) * uint64_t(options.height);
        EXPECT_EQ(camera.cameraRays, pixels) << file;
        EXPECT_EQ(full.cameraRays, pixels) << file;
        EXPECT_GT(full.raysTraced, pixels) << file << ": the scene should spawn secondary rays";
        EXPECT_GT(full.shadowRays, 0u) << file;
        EXPECT_GT(camera.idleSteps, 0u) << file;
        EXPECT_EQ(full.idleSteps, camera.idleSteps) << file;
    }
}

// A packet accelerator's counters on camera rays (no lights, depth 1: every ray walks as a packet):
// the lock-step steps are the packets' steps, the nodes the lanes' rays entered plus the steps they
// sat out (GpuRenderReport::idleSteps), which the lanes of a packet on the hand-made scenes' edges and
// corners do; the single walk counts none. With `slowestLane` (bvh-packet, one packet a subgroup of
// camera rays), a packet takes at least the steps of its slowest lane. Without subgroup ballot the
// packet runs the single walk's kernel, which counts no packet.
inline void expectPacketCounters(std::string_view single, std::string_view packet, bool slowestLane) {
    for (const char* file : {"cornell.scene", "objects.scene", "spheres.scene"}) {
        Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / file);
        scene.lights.clear();
        const RenderOptions options{.width = 125, .height = 93, .maxDepth = 1, .countTraversal = true};
        gpu::GpuRenderReport walk, packed;
        renderGpu(scene, options, &walk, single);
        renderGpu(scene, options, &packed, packet);
        EXPECT_FALSE(walk.packetWalk);
        EXPECT_EQ(walk.idleSteps, 0u) << file;
        if (!gpuContext().info().subgroupBallot) {
            EXPECT_FALSE(packed.packetWalk);
            continue;
        }
        EXPECT_TRUE(packed.packetWalk);
        EXPECT_EQ(packed.shadowRays, 0u) << file;
        EXPECT_GT(packed.idleSteps, 0u) << file;
        EXPECT_EQ(packed.restarts, 0u) << file;
        EXPECT_EQ(packed.lockstepNodes, packed.nodesVisited + packed.idleSteps) << file;
        if (slowestLane) {
            EXPECT_GE(packed.lockstepNodes,
                      gpu::lockstepNodes(uint32_t(options.width), uint32_t(options.height), packed.lockstepLanes,
                                         [&](uint32_t x, uint32_t y) { return packed.nodesPerPixel[size_t(y) * size_t(options.width) + x]; }))
                << file;
        }
    }
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

struct PrimIdAgreement {
    size_t pixels = 0, same = 0;
    size_t ties = 0;  // different triangles, both hit by the exact ray at the same distance
                      // (up to float rounding: within 1e-5 of the triangle's size)
    double fraction() const { return pixels ? double(same + ties) / double(pixels) : 1.0; }
};

// Compares the primary hits of a GPU frame with the CPU reference's. Where they name different
// triangles, the exact camera ray (double precision, watertight) is intersected with the GPU's
// triangle: if it hits at the reference's depth, the ray went through an edge the two triangles
// share (a Cornell-box corner seen at 45 degrees puts whole diagonals of pixel centres there), both
// answers are right and it counts as a tie (float rounding may put the GPU's hit a hair past the
// edge, hence the 1e-5 growth below); anything else is a disagreement.
inline PrimIdAgreement comparePrimaryHits(const Scene& scene, const Frame& gpu, const Frame& ref) {
    const CameraFrame cam = makeCameraFrame(scene.camera, ref.width, ref.height);
    PrimIdAgreement a;
    a.pixels = ref.primId.size();
    for (int j = 0; j < ref.height; ++j)
        for (int i = 0; i < ref.width; ++i) {
            const size_t k = ref.index(i, j);
            if (gpu.primId[k] == ref.primId[k]) {
                ++a.same;
                continue;
            }
            if (gpu.primId[k] < 0 || ref.primId[k] < 0) continue;
            // Grown by 1e-5 about its centroid: float rounding moves a hit that much off an edge.
            const Triangle& t = scene.triangles[size_t(gpu.primId[k])];
            const glm::dvec3 c = (glm::dvec3(t.p0) + glm::dvec3(t.p1) + glm::dvec3(t.p2)) / 3.0;
            const auto grow = [&](const glm::vec3& p) { return c + (glm::dvec3(p) - c) * (1.0 + 1e-5); };
            const geometry::Ray ray{cam.eye, primaryDirection(cam, i, j)};
            const auto hit = geometry::intersectTriangle(ray, {grow(t.p0), grow(t.p1), grow(t.p2)}, 0.0,
                                                    std::numeric_limits<double>::infinity());
            if (hit && std::abs(hit->t - ref.depth[k]) <= 1e-5 * ref.depth[k]) ++a.ties;
        }
    return a;
}

}  // namespace vkray::test
