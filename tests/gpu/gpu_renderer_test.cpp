// The GPU renderer on scenes built in code: tiling, AOVs, depth semantics, device choice, limits.
#include <cmath>
#include <filesystem>
#include <limits>

#include <gtest/gtest.h>

#include "core/error.h"
#include "cpu/reference_renderer.h"
#include "support/scene_builder.h"
#include "support/window_check.h"
#include "gpu/buffer.h"
#include "gpu/gpu_renderer.h"
#include "gpu/lockstep.h"
#include "gpu_test_util.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

// A lit square filling the view, so every pixel has a distinct colour from the point light.
Scene litSquare() {
    Scene s = test::sceneLookingDownZ();
    Material m = test::blackMaterial();
    m.diffuse = glm::vec3(0.8f, 0.6f, 0.4f);
    m.specular = glm::vec3(0.3f);
    m.shininess = 20.0f;
    test::addSquare(s, 0.0f, 10.0f, true, test::addMaterial(s, m));
    test::addPointLight(s, {1.0f, 0.5f, 2.0f}, glm::vec3(1.0f));
    return s;
}

TEST(GpuRenderer, TilesCoverTheImageInPlace) {
    // 300x260 spans 2x2 tiles of 256: a tile written at the wrong offset or a missed edge would
    // put wrong colours (or no hit) there.
    const Scene s = litSquare();
    RenderOptions o{.width = 300, .height = 260, .maxDepth = 1};
    gpu::GpuRenderReport report;
    const Frame g = test::renderGpu(s, o, &report);
    const Frame c = renderReference(s, o);
    EXPECT_EQ(report.tiles, 4u);
    ASSERT_EQ(g.color.size(), c.color.size());
    for (size_t i = 0; i < g.color.size(); ++i) {
        ASSERT_NE(g.primId[i], -1) << "pixel " << i << " not written";
        for (int ch = 0; ch < 3; ++ch)
            ASSERT_NEAR(g.color[i][ch], c.color[i][ch], 1e-4f) << "pixel " << i % 300 << "," << i / 300;
    }
}

TEST(GpuRenderer, WindowPixelsAreBitIdenticalToTheWholeImages) {
    // A window crossing the 256-pixel tile edges, one corner pixel and a band of rows, with two
    // samples a pixel and a reflection: the same rays as the whole render, whatever the tiling.
    Scene s = litSquare();
    s.materials[0].reflect = glm::vec3(0.5f);
    test::addPointLight(s, {-1.0f, -0.5f, 3.0f}, glm::vec3(0.5f));
    RenderOptions o{.width = 300, .height = 260, .maxDepth = 3, .spp = 2};
    for (const char* accel : {"bvh", "kd-backtrack"}) {
        SCOPED_TRACE(accel);
        const Frame whole = test::renderGpu(s, o, nullptr, accel);
        for (const PixelWindow w : {PixelWindow{37, 5, 290, 200}, PixelWindow{299, 259, 300, 260},
                                    PixelWindow{0, 130, 300, 195}}) {
            RenderOptions part = o;
            part.window = w;
            gpu::GpuRenderReport report;
            test::expectSamePixels(whole, test::renderGpu(s, part, &report, accel), w);
            EXPECT_GT(report.raysTraced, 0u);
        }
    }
}

TEST(GpuRenderer, WindowOutsideTheImageIsAnError) {
    RenderOptions o{.width = 64, .height = 48, .maxDepth = 1, .window = PixelWindow{10, 10, 65, 20}};
    EXPECT_THROW(test::renderGpu(litSquare(), o), Error);
    o.window = PixelWindow{10, 10, 10, 20};  // empty
    EXPECT_THROW(test::renderGpu(litSquare(), o), Error);
}

TEST(GpuRenderer, DepthAndPrimIdAovs) {
    Scene s = litSquare();
    RenderOptions o{.width = 33, .height = 33, .maxDepth = 1};
    const Frame f = test::renderGpu(s, o);
    // The centre pixel of an odd image looks straight down -z: t = 5 exactly, on triangle 0 or 1
    // (it lies on their shared diagonal).
    const size_t centre = f.index(16, 16);
    EXPECT_NEAR(f.depth[centre], 5.0f, 1e-5f);
    EXPECT_TRUE(f.primId[centre] == 0 || f.primId[centre] == 1);
    EXPECT_NEAR(f.normal[centre].z, 1.0f, 1e-6f);
    // Pixels off the diagonal belong to one triangle; the lower-right half is triangle 0.
    EXPECT_EQ(f.primId[f.index(30, 30)], 0);
    EXPECT_EQ(f.primId[f.index(2, 2)], 1);
}

TEST(GpuRenderer, MissesAreBlackWithInfiniteDepth) {
    Scene s = test::sceneLookingDownZ();
    Material m;
    m.ambient = glm::vec3(0.5f);
    test::addSquare(s, 0.0f, 0.5f, true, test::addMaterial(s, m));  // small: corners miss
    RenderOptions o{.width = 16, .height = 16, .maxDepth = 3};
    const Frame f = test::renderGpu(s, o);
    const size_t corner = f.index(0, 0);
    EXPECT_EQ(f.primId[corner], -1);
    EXPECT_EQ(f.depth[corner], std::numeric_limits<float>::infinity());
    EXPECT_EQ(f.color[corner], glm::vec3(0.0f));
    EXPECT_NEAR(f.color[f.index(8, 8)].x, 0.5f, 1e-6f);
}

TEST(GpuRenderer, MaxDepthOneLeavesOutReflection) {
    // A mirror facing the camera, with an emissive square behind the camera: visible only by
    // reflection, so depth 1 shows black and depth 2 shows the emission.
    Scene s = test::sceneLookingDownZ();
    Material mirror = test::blackMaterial();
    mirror.reflect = glm::vec3(1.0f);
    test::addSquare(s, 0.0f, 10.0f, true, test::addMaterial(s, mirror));
    Material glow = test::blackMaterial();
    glow.emission = glm::vec3(0.25f, 0.5f, 0.75f);
    test::addSquare(s, 10.0f, 30.0f, false, test::addMaterial(s, glow));
    RenderOptions o{.width = 9, .height = 9, .maxDepth = 1};
    gpu::GpuRenderReport report;
    Frame f = test::renderGpu(s, o, &report);
    EXPECT_FALSE(report.features.reflection);
    EXPECT_EQ(f.color[f.index(4, 4)], glm::vec3(0.0f));
    o.maxDepth = 2;
    o.width = o.height = 64;
    f = test::renderGpu(s, o, &report);
    EXPECT_TRUE(report.features.reflection);
    EXPECT_FALSE(report.features.refraction);
    // Every pixel sees the emitter in the mirror: a reflected ray that hit its own mirror (a
    // speckle from a bad origin offset) would be black.
    for (size_t i = 0; i < f.color.size(); ++i)
        ASSERT_NEAR(f.color[i].z, 0.75f, 1e-6f) << "pixel " << i % 64 << "," << i / 64;
}

TEST(GpuRenderer, NoShadowAcneAtGrazingLight) {
    // A directional light 2 degrees above a large plane: every pixel is lit, none self-shadowed.
    Scene s = test::sceneLookingDownZ();
    s.camera.eye = {0.0f, 3.0f, 5.0f};
    Material m = test::blackMaterial();
    m.diffuse = glm::vec3(1.0f);
    const uint32_t mat = test::addMaterial(s, m);
    test::addSquare(s, 0.0f, 50.0f, true, mat);
    for (Triangle& t : s.triangles) {  // lay the square into the plane y = 0, normal +y
        for (glm::vec3* p : {&t.p0, &t.p1, &t.p2}) *p = glm::vec3(p->x, 0.0f, -p->y);
    }
    const float a = glm::radians(2.0f);
    test::addDirectionalLight(s, {std::cos(a), std::sin(a), 0.0f}, glm::vec3(1.0f));
    RenderOptions o{.width = 64, .height = 64, .maxDepth = 1};
    const Frame f = test::renderGpu(s, o);
    size_t hits = 0;
    for (size_t i = 0; i < f.color.size(); ++i) {
        if (f.primId[i] < 0) continue;
        ++hits;
        ASSERT_NEAR(f.color[i].x, std::sin(a), 1e-5f) << "pixel " << i % 64 << "," << i / 64;
    }
    EXPECT_GT(hits, f.color.size() / 3);
}

// A render that saves no AOV leaves the primary-hit AOVs out of the kernel's output: its colour, ray
// counts and traversal counters are those of a render with them, bit for bit, and its AOVs stay at
// their miss values.
TEST(GpuRenderer, WithoutPrimaryAovsTheImageAndCountsAreTheSame) {
    const Scene s = litSquare();
    for (const char* accel : {"bvh", "kd-stack"}) {
        SCOPED_TRACE(accel);
        RenderOptions with{.width = 40, .height = 30, .maxDepth = 2, .countTraversal = true};
        RenderOptions without = with;
        without.primaryAovs = false;
        gpu::GpuRenderReport a, b;
        const Frame f = test::renderGpu(s, with, &a, accel);
        const Frame g = test::renderGpu(s, without, &b, accel);
        EXPECT_TRUE(a.features.primaryAovs);
        EXPECT_FALSE(b.features.primaryAovs);
        ASSERT_EQ(f.color.size(), g.color.size());
        ASSERT_TRUE(f.hasAovs());
        EXPECT_FALSE(g.hasAovs());  // no arrays to fill and throw away
        EXPECT_TRUE(g.depth.empty() && g.primId.empty() && g.normal.empty());
        for (size_t i = 0; i < f.color.size(); ++i) {
            ASSERT_EQ(f.color[i], g.color[i]) << "pixel " << i;
            ASSERT_NE(f.primId[i], -1) << "the square fills the view";
        }
        EXPECT_EQ(a.raysTraced, b.raysTraced);
        EXPECT_EQ(a.shadowRays, b.shadowRays);
        EXPECT_GT(a.nodesVisited, 0u);
        EXPECT_EQ(a.nodesVisited, b.nodesVisited);
        EXPECT_EQ(a.trianglesTested, b.trianglesTested);
    }
}

// A render that keeps neither AOVs nor counters takes the compact records (GpuPixelColor, and the
// ray counts summed a tile: render_main.glsl, "Pixel records"): the same pixels bit for bit and the
// same ray counts as the full records, over several tiles a batch (each its own counts) and batches, with
// reflection, refraction, both kinds of light and pixels of the last tiles outside the image.
TEST(GpuRenderer, CompactRecordsGiveTheSamePixelsAndCounts) {
    Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / "objects.scene");
    scene.background = glm::vec3(0.25f, 0.5f, 0.75f);  // no record is all zeros: stale counts would show
    const RenderOptions full{.width = 520, .height = 270, .maxDepth = 3};  // 6 tiles: two batches on lavapipe
    RenderOptions compact = full;
    compact.primaryAovs = false;
    for (const char* accel : {"bvh", "kd-stack", "kd-backtrack"}) {
        SCOPED_TRACE(accel);
        gpu::GpuRenderReport a, b;
        const Frame f = test::renderGpu(scene, full, &a, accel);
        const Frame g = test::renderGpu(scene, compact, &b, accel);
        EXPECT_FALSE(a.features.compactPixels());
        EXPECT_TRUE(b.features.compactPixels());
        EXPECT_EQ(b.tiles, 6u);
        ASSERT_EQ(f.color.size(), g.color.size());
        for (size_t i = 0; i < f.color.size(); ++i) ASSERT_EQ(f.color[i], g.color[i]) << "pixel " << i;
        EXPECT_GT(a.shadowRays, 0u);
        EXPECT_GT(a.raysTraced, uint64_t(full.width) * full.height);  // secondary rays too
        EXPECT_EQ(b.raysTraced, a.raysTraced);
        EXPECT_EQ(b.shadowRays, a.shadowRays);
        EXPECT_EQ(b.cappedRays, a.cappedRays);
        EXPECT_EQ(b.pixelsCutShort, 0u);
    }
}

// The lock-step count of a one-tile render is the per-pixel counts' (gpu/lockstep.h) with the
// device's subgroup size, and at least the steps themselves.
TEST(GpuRenderer, LockstepNodesFromThePixelCounts) {
    const Scene s = litSquare();
    const RenderOptions options{.width = 40, .height = 30, .maxDepth = 1, .countTraversal = true};
    gpu::GpuRenderReport rep;
    test::renderGpu(s, options, &rep, "bvh");
    ASSERT_EQ(rep.nodesPerPixel.size(), size_t(40 * 30));
    EXPECT_EQ(rep.lockstepLanes, test::gpuContext().info().subgroupSize);
    EXPECT_GE(rep.lockstepLanes, 1u);
    const uint64_t expected =
        gpu::lockstepNodes(40, 30, rep.lockstepLanes, [&](uint32_t x, uint32_t y) { return rep.nodesPerPixel[y * 40 + x]; });
    EXPECT_EQ(rep.lockstepNodes, expected);
    EXPECT_GE(rep.lockstepNodes, rep.nodesVisited);
    EXPECT_GT(rep.nodesVisited, 0u);
}

// The plain kernel renders one pixel an invocation on a GPU and several on a CPU device
// (render_main.glsl, "Pixels per invocation"). Every count gives the same pixels, AOVs, ray and
// traversal counts, on an image whose last block rows leave some invocations' later pixels outside
// it, with reflection, refraction, both kinds of light and smooth normals.
TEST(GpuRenderer, PixelsPerInvocationChangeNoPixel) {
    const gpu::DeviceInfo& device = test::gpuContext().info();
    EXPECT_EQ(device.pixelsPerInvocation, device.type == "cpu" ? uint32_t(VKRAY_MAX_PIXELS_PER_INVOCATION) : 1u);
    const Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / "objects.scene");
    const RenderOptions o{.width = 70, .height = 45, .maxDepth = 3, .countTraversal = true};
    std::vector<std::unique_ptr<gpu::VulkanContext>> contexts;
    for (uint32_t n = 1; n <= VKRAY_MAX_PIXELS_PER_INVOCATION; ++n) {
        gpu::ContextOptions options = test::gpuContextOptions();
        options.pixelsPerInvocation = n;
        contexts.push_back(std::make_unique<gpu::VulkanContext>(options));
    }
    for (const char* accel : {"bvh", "kd-restart", "brute"}) {
        SCOPED_TRACE(accel);
        gpu::GpuRenderReport one;
        const Frame reference = test::renderGpu(*contexts[0], scene, o, &one, accel);
        EXPECT_EQ(one.features.pixelsPerInvocation, 1);
        EXPECT_GT(one.shadowRays, 0u);
        for (uint32_t n = 2; n <= VKRAY_MAX_PIXELS_PER_INVOCATION; ++n) {
            SCOPED_TRACE(n);
            gpu::GpuRenderReport rep;
            const Frame f = test::renderGpu(*contexts[n - 1], scene, o, &rep, accel);
            EXPECT_EQ(rep.features.pixelsPerInvocation, int(n));
            test::expectSamePixels(reference, f, PixelWindow{0, 0, o.width, o.height});
            EXPECT_EQ(rep.raysTraced, one.raysTraced);
            EXPECT_EQ(rep.shadowRays, one.shadowRays);
            EXPECT_EQ(rep.nodesPerPixel, one.nodesPerPixel);
            EXPECT_EQ(rep.trianglesTested, one.trianglesTested);
            EXPECT_EQ(rep.pixelsCutShort, 0u);
        }
    }
}

TEST(GpuRenderer, FeaturesFollowTheScene) {
    Scene s = litSquare();
    auto f = gpu::ShaderFeatures::forScene(s, 5);
    EXPECT_TRUE(f.pointLights);
    EXPECT_FALSE(f.directionalLights);
    EXPECT_FALSE(f.reflection);  // specular 0.3 but reflect 0: built in code, no CSE167 default
    EXPECT_FALSE(f.refraction);
    EXPECT_FALSE(f.smoothNormals);
    Material glass = test::blackMaterial();
    glass.transmit = glm::vec3(1.0f);
    glass.ior = 1.5f;
    test::addSquare(s, 1.0f, 0.1f, true, test::addMaterial(s, glass));
    f = gpu::ShaderFeatures::forScene(s, 5);
    EXPECT_TRUE(f.refraction);
    EXPECT_TRUE(f.reflection);  // Fresnel reflection of glass
    f = gpu::ShaderFeatures::forScene(s, 1);
    EXPECT_FALSE(f.refraction);
    EXPECT_FALSE(f.reflection);
}

TEST(GpuRenderer, DataBeyondEveryViewOfABindingIsAnErrorBeforeAllocating) {
    const auto& ctx = test::gpuContext();
    const size_t tooBig = (size_t(gpu::maxTexelArray(ctx)) + 1) * 16;
    try {
        // No data behind the pointer: the limit must be checked before anything is read or allocated.
        gpu::uploadTexelArray(ctx, nullptr, tooBig, vk::Format::eR32G32B32A32Uint, 16, "triangles");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("maxTexelBufferElements"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("triangles"), std::string::npos) << e.what();
    }
}

TEST(GpuRenderer, UnknownDeviceIsAnError) {
    EXPECT_THROW(gpu::VulkanContext({.validation = false, .device = "999"}), Error);
    EXPECT_THROW(gpu::VulkanContext({.validation = false, .device = "no such device name"}), Error);
}

TEST(GpuRenderer, UnknownAcceleratorIsAnError) {
    RenderOptions o{.width = 8, .height = 8, .maxDepth = 1};
    EXPECT_THROW(test::renderGpu(litSquare(), o, nullptr, "octree"), Error);
}

}  // namespace
}  // namespace vkray
