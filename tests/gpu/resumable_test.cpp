// Resumable pixels (shaders/include/render_main.glsl): scenes whose pixels need more loop
// iterations than llvmpipe of Mesa 22.3 allows one invocation render across several dispatches, to
// the same image, bit for bit, as an accelerator that needs no resuming. On a device whose loops
// never end early the same renders are made resumable from the start, so that the resumable
// variant's own budget splits them over dispatches all the same.
#include <optional>
#include <string_view>

#include <gtest/gtest.h>

#include "gpu_test_util.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

// 50,000 triangles, three lights and mirror reflections: brute force tests 4 triangles per loop
// iteration, so one pixel's camera ray and shadow rays need about 50,000 iterations (within one
// budget: the plain kernel runs first), its reflected rays as many again, beyond llvmpipe's 65,535
// per invocation.
constexpr const char* kHeavyScene = R"(
size 24 16
maxdepth 3
camera 0 1.7 3.2  0 0.25 0  0 1 0  40
directional 0.4 1 0.7  0.5 0.5 0.48
point -2.5 3 2.5  0.5 0.5 0.55
point 1.5 2 1  0.3 0.3 0.3
ambient 0.05 0.04 0.04
diffuse 0.75 0.35 0.2
specular 0.4 0.4 0.4
shininess 60
generate spheres 50000 1
)";

// 100,000 triangles and two lights: a camera ray and its shadow rays need 75,000 loop passes of
// brute force, beyond one budget, so on llvmpipe every tile is resumable from the start.
constexpr const char* kBruteFromStartScene = R"(
size 8 8
maxdepth 2
camera 0 1.7 3.2  0 0.25 0  0 1 0  20
directional 0.4 1 0.7  0.5 0.5 0.48
point -2.5 3 2.5  0.5 0.5 0.55
ambient 0.05 0.04 0.04
diffuse 0.75 0.35 0.2
specular 0.4 0.4 0.4
generate spheres 100000 1
)";

// 80,000 triangles sharing one centroid seen from close by, four lights, mirrors: every ray crosses
// every BVH node, so the BVH, not only brute force, runs out of llvmpipe's budget; the kd-tree
// (which cuts the burst by planes) needs no resuming and is the reference. (40,000 were enough
// while a subgroup's 8 pixels were a row; on a 4x2 block their walks overlap more, and 50,000 no
// longer ran out.)
constexpr const char* kBurstScene = R"(
size 8 8
maxdepth 4
camera 0 0.5 1.0  0 0.5 0  0 1 0  20
directional 0.4 1 0.7  0.8 0.8 0.8
point 1 2 2  0.6 0.6 0.6
point -1 2 2  0.6 0.6 0.6
point 0 -2 2  0.6 0.6 0.6
ambient 0.05 0.05 0.05
diffuse 0.7 0.5 0.3
specular 0.5 0.5 0.5
generate burst 80000 1
)";

// 500,000 triangles, two lights and mirror reflections: one ray alone needs more than a whole
// budget of brute force, and the 8 pixels of a subgroup, sharing one budget, drift apart (one is
// adding its lights while another still traces its reflection), so some pixel gets nothing done in
// a dispatch while the others spend the budget. That pixel waits its turn; it is not stuck.
constexpr const char* kSubgroupSharingScene = R"(
size 8 6
maxdepth 3
camera 0 1.7 3.2  0 0.25 0  0 1 0  40
directional 0.4 1 0.7  0.5 0.5 0.48
point -2.5 3 2.5  0.5 0.5 0.55
ambient 0.04 0.05 0.06
diffuse 0.3 0.5 0.75
specular 0.3 0.3 0.3
shininess 40
reflect 0.2 0.2 0.2
generate spheres 500000 1
)";

void expectSameFrames(const Frame& a, const Frame& b) {
    ASSERT_EQ(a.color.size(), b.color.size());
    for (size_t i = 0; i < a.color.size(); ++i) {
        ASSERT_EQ(a.primId[i], b.primId[i]) << "pixel " << i;
        ASSERT_EQ(a.depth[i], b.depth[i]) << "pixel " << i;
        for (int c = 0; c < 3; ++c) ASSERT_EQ(a.color[i][c], b.color[i][c]) << "pixel " << i << " channel " << c;
    }
}

// Renders `sceneText` with `resumed`, which must run out of the driver's loop budget and be resumed
// (`fromStart`: resumable from the start), and with `reference`, which must not, and expects the
// same frames and ray counts. Without such a budget (VulkanContext::loopBudget()), `resumed` renders
// on a context that makes every render resumable from the start.
void expectResumedLikeReference(const char* sceneText, std::string_view resumed, std::string_view reference,
                                bool fromStart = false) {
    const Scene s = parseSceneText(sceneText, "test.scene", ".");
    const RenderOptions o{.width = s.width, .height = s.height, .maxDepth = s.maxDepth};
    const bool budget = test::gpuContext().loopBudget();
    std::optional<gpu::VulkanContext> alwaysResumable;
    if (!budget) {
        gpu::ContextOptions options = test::gpuContextOptions();
        options.resumableFromStart = true;
        alwaysResumable.emplace(options);
    }
    gpu::GpuRenderReport a, b;
    const Frame fa = test::renderGpu(budget ? test::gpuContext() : *alwaysResumable, s, o, &a, resumed);
    const Frame fb = test::renderGpu(s, o, &b, reference);
    // The case these tests are for: the plain kernel could not finish (or would not have), the
    // resumable one did, over several dispatches.
    EXPECT_EQ(a.resumedTiles, 1u);
    EXPECT_GT(a.resumeDispatches, 1u);
    EXPECT_EQ(a.resumedFromStart, fromStart || !budget);
    EXPECT_EQ(b.resumedTiles, 0u);
    EXPECT_EQ(a.pixelsCutShort, 0u);
    EXPECT_EQ(a.raysTraced, b.raysTraced);
    EXPECT_EQ(a.shadowRays, b.shadowRays);
    expectSameFrames(fa, fb);
}

// VulkanContext::loopBudget()'s probe against a render: the plain brute-force kernel runs out on the
// heavy scene exactly where the probe says the driver ends long loops.
TEST(ResumablePixels, TheLoopBudgetProbeAgreesWithTheKernels) {
    const Scene s = parseSceneText(kHeavyScene, "test.scene", ".");
    gpu::GpuRenderReport r;
    test::renderGpu(s, RenderOptions{.width = s.width, .height = s.height, .maxDepth = s.maxDepth}, &r, "brute");
    EXPECT_FALSE(r.resumedFromStart);
    EXPECT_EQ(r.resumedTiles > 0, test::gpuContext().loopBudget());
    EXPECT_EQ(r.pixelsCutShort, 0u);
}

TEST(ResumablePixels, BruteForceBeyondTheLoopBudgetMatchesTheBvhBitForBit) {
    expectResumedLikeReference(kHeavyScene, "brute", "bvh");
}

TEST(ResumablePixels, BruteForceOverManyTrianglesIsResumableFromTheStart) {
    expectResumedLikeReference(kBruteFromStartScene, "brute", "bvh", true);
}

TEST(ResumablePixels, BvhOverOverlappingTrianglesBeyondTheLoopBudgetMatchesTheKdTree) {
    expectResumedLikeReference(kBurstScene, "bvh", "kd-stack");
}

// bvh-packet's resumable variant walks closest hits one ray at a time, stackless
// (render_bvh_packet.comp): its resumed tiles must match too.
TEST(ResumablePixels, BvhPacketOverOverlappingTrianglesBeyondTheLoopBudgetMatchesTheKdTree) {
    expectResumedLikeReference(kBurstScene, "bvh-packet", "kd-stack");
}

// The heavy scene under a kd-tree held to depth 1: two leaves of up to 25,704 triangles. The plain
// kernel tests one triangle a leaf-loop pass and runs out of llvmpipe's budget; the resumable
// variant, specialised to test four a pass for such leaves (ShaderFeatures::leafSlots()), finishes
// in two dispatches.
TEST(ResumablePixels, KdTreeWithLargeLeavesBeyondTheLoopBudgetMatchesTheBvh) {
    expectResumedLikeReference(kHeavyScene, "kd-stack:kd-max-depth=1", "bvh");
}

TEST(ResumablePixels, APixelWaitingWhileItsSubgroupSpendsTheBudgetIsNotStuck) {
    expectResumedLikeReference(kSubgroupSharingScene, "brute", "bvh", true);
}

}  // namespace
}  // namespace vkray
