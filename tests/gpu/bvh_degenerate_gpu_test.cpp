// Every BVH accelerator on the degenerate meshes of a Morton-ordered build (tests/accel/bvh,
// degenerateMeshes: 20,000 triangles sharing one centroid, coplanar and overlapping, one huge among
// tiny ones, duplicated), seen from inside the mesh: a camera ray from where every box overlaps
// enters nearly every box, so one ray's walk can outlast llvmpipe's whole loop budget of Mesa 22.3
// (trace_status.glsl). Each render must equal the GPU brute-force kernel's bit for bit, primary
// hits and colours: every kernel runs the same float triangle test and tie rule, so no traversal
// order shows, and no ray may reach an iteration cap. On Mesa 22.3 the plain kernels run out of
// the budget and their resumable variants take the walks up where they stopped; on a driver
// without the budget each BVH render is made a second time resumable from the start
// (ContextOptions::resumableFromStart), where the variant's own budget cuts the walks all the same.
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../accel/bvh/bvh_test_meshes.h"
#include "gpu_test_util.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

// The camera inside the mesh's cube [-1, 1]^3, two lights (shadow rays walk the BVH too), no
// secondary rays. The one triangle here only gives the parsed scene its material and a local frame
// whose origin is the world's (its bounds hold (0, 0, 0)); the mesh replaces it.
constexpr const char* kView = R"(
size 16 16
maxdepth 1
camera 0.05 0.03 0.02  0.3 0.2 -1  0 1 0  60
directional 0.4 1 0.7  0.8 0.8 0.8
point 0.2 0.3 0.1  0.6 0.6 0.6
ambient 0.05 0.05 0.05
diffuse 0.7 0.5 0.3
specular 0 0 0
vertex -1 -1 0
vertex 1 -1 0
vertex 0 1 0
tri 0 1 2
)";

const std::vector<std::string> kBvhAccels = {"bvh", "bvh-fast", "bvh-hq", "bvh-sah", "bvh-stackless", "bvh-packet", "bvh-sphere"};

// Renders `s` with `accel` on `ctx` and expects brute force's frame and ray counts.
void expectBruteForceFrame(const gpu::VulkanContext& ctx, const Scene& s, const std::string& accel,
                           const std::string& what, const Frame& brute, const gpu::GpuRenderReport& bruteReport) {
    const RenderOptions o{.width = s.width, .height = s.height, .maxDepth = s.maxDepth};
    gpu::GpuRenderReport r;
    const Frame f = test::renderGpu(ctx, s, o, &r, accel);
    std::printf("measured %s: %u resumed tiles, %u dispatches, %llu capped rays\n", what.c_str(), r.resumedTiles,
                r.resumeDispatches, (unsigned long long)r.cappedRays);
    EXPECT_EQ(r.pixelsCutShort, 0u) << what;
    EXPECT_EQ(r.cappedRays, 0u) << what;
    EXPECT_EQ(r.raysTraced, bruteReport.raysTraced) << what;
    EXPECT_EQ(r.shadowRays, bruteReport.shadowRays) << what;
    ASSERT_EQ(f.color.size(), brute.color.size());
    size_t primIdsOff = 0, coloursOff = 0;
    for (size_t i = 0; i < f.color.size(); ++i) {
        primIdsOff += f.primId[i] != brute.primId[i];
        coloursOff += f.color[i] != brute.color[i];
    }
    EXPECT_EQ(primIdsOff, 0u) << what;
    EXPECT_EQ(coloursOff, 0u) << what;
}

TEST(BvhDegenerateMeshes, EveryBvhKernelMatchesBruteForceBitForBit) {
    const bool budget = test::gpuContext().loopBudget();
    std::optional<gpu::VulkanContext> alwaysResumable;
    if (!budget) {
        gpu::ContextOptions options = test::gpuContextOptions();
        options.resumableFromStart = true;
        alwaysResumable.emplace(options);
    }
    for (const test::NamedMesh& mesh : test::degenerateMeshes(20000)) {
        Scene s = parseSceneText(kView, "test.scene", ".");
        s.triangles = mesh.scene.triangles;
        gpu::GpuRenderReport bruteReport;
        const Frame brute =
            test::renderGpu(s, RenderOptions{.width = s.width, .height = s.height, .maxDepth = s.maxDepth}, &bruteReport);
        ASSERT_EQ(bruteReport.pixelsCutShort, 0u) << mesh.name;
        for (const std::string& accel : kBvhAccels) {
            expectBruteForceFrame(test::gpuContext(), s, accel, mesh.name + " " + accel, brute, bruteReport);
            if (alwaysResumable)
                expectBruteForceFrame(*alwaysResumable, s, accel, mesh.name + " " + accel + " resumable", brute,
                                      bruteReport);
        }
    }
}

}  // namespace
}  // namespace vkray
