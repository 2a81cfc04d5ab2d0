// The kd-tree kernels (render_kd_stack, render_kd_restart, render_kd_backtrack) on the GPU: each
// image against the CPU reference renderer, with the thresholds of gpu_vs_cpu_test.cpp (the same
// float watertight test, so the same measured rounding differences), and each primary hit against
// the GPU brute-force kernel: the same triangle, or a tie (an exact hit on an edge two triangles
// share). No ray may reach the iteration cap, and the statistics variant counts the work.
#include <cstdio>
#include <filesystem>
#include <map>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "cpu/reference_renderer.h"
#include "gpu/gpu_renderer.h"
#include "gpu_test_util.h"
#include "image/image_io.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

struct KdCase {
    std::string accel;  // kd-stack, kd-shortstack, kd-restart, kd-pushdown, kd-ropes, kd-backtrack, kd-packet
    std::string file;   // under scenes/
    int width, height;
    friend std::ostream& operator<<(std::ostream& os, const KdCase& c) {
        return os << c.accel << " on " << c.file << " at " << c.width << "x" << c.height;
    }
};

struct References {
    Scene scene;
    Frame cpu, gpuBrute;
};

// The CPU reference and the GPU brute-force frame, once per scene and size for all three traversals.
const References& referencesFor(const KdCase& c) {
    static std::map<std::string, References> cache;
    const std::string key = c.file + "@" + std::to_string(c.width) + "x" + std::to_string(c.height);
    auto it = cache.find(key);
    if (it == cache.end()) {
        References r;
        r.scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes" / c.file);
        const RenderOptions options{.width = c.width, .height = c.height, .maxDepth = r.scene.maxDepth};
        r.cpu = renderReference(r.scene, options);
        r.gpuBrute = test::renderGpu(r.scene, options);
        it = cache.emplace(key, std::move(r)).first;
    }
    return it->second;
}

class KdGpu : public ::testing::TestWithParam<KdCase> {};

TEST_P(KdGpu, ImageMatchesCpuReferenceAndHitsMatchGpuBrute) {
    const KdCase& c = GetParam();
    const References& ref = referencesFor(c);
    RenderOptions options{.width = c.width, .height = c.height, .maxDepth = ref.scene.maxDepth};
    gpu::GpuRenderReport report;
    const Frame kdFrame = test::renderGpu(ref.scene, options, &report, c.accel);
    // kd-packet runs its own kernel where the device has subgroup ballot, kd-stack's elsewhere.
    const bool own = c.accel != "kd-packet" || test::gpuContext().info().subgroupBallot;
    EXPECT_EQ(report.kernel, own ? "kd_" + c.accel.substr(3) : "kd_stack");
    EXPECT_EQ(report.cappedRays, 0u) << "a traversal reached its iteration cap";
    EXPECT_EQ(report.pixelsCutShort, 0u);

    // Primary hits against the CPU reference (>= 99.9%, as for brute force) and the GPU brute kernel.
    const test::PrimIdAgreement vsCpu = test::comparePrimaryHits(ref.scene, kdFrame, ref.cpu);
    const test::PrimIdAgreement vsBrute = test::comparePrimaryHits(ref.scene, kdFrame, ref.gpuBrute);
    EXPECT_GE(vsCpu.fraction(), 0.999) << vsCpu.same << " same, " << vsCpu.ties << " ties of " << vsCpu.pixels;
    EXPECT_GE(vsBrute.fraction(), 0.999) << vsBrute.same << " same, " << vsBrute.ties << " ties of " << vsBrute.pixels;

    // Image: the bounds of gpu_vs_cpu_test.cpp (RMSE 0.025, 1% of pixels off by more than 8/255).
    const Image g = test::quantisedColor(kdFrame), r = test::quantisedColor(ref.cpu);
    const CompareStats stats = compareImages(g, r, 8.0 / 255.0);
    std::printf("measured %s %s: rmse %.5f, bad %.4f%%, primid vs cpu same %zu ties %zu, vs gpu brute same %zu "
                "ties %zu of %zu\n",
                c.accel.c_str(), c.file.c_str(), stats.rmse, 100.0 * stats.badFraction, vsCpu.same, vsCpu.ties,
                vsBrute.same, vsBrute.ties, vsCpu.pixels);
    EXPECT_LE(stats.rmse, 0.025);
    EXPECT_LE(stats.badFraction, 0.01) << stats.badPixels << " pixels differ by more than 8/255";
    if (HasFailure()) {
        const std::filesystem::path dir(VKRAY_TEST_OUTPUT_DIR);
        const std::string stem = c.accel + "-" + std::filesystem::path(c.file).stem().string();
        writeColorImage(dir / (stem + "-gpu.png"), g.width, g.height, kdFrame.color);
        writeImage(dir / (stem + "-diff.png"), makeDiffImage(g, r, 8.0 / 255.0));
    }
}

// The statistics variant, on the Cornell box: every ray visits at least the root; the stackless
// traversals restart.
class KdGpuCounters : public ::testing::TestWithParam<std::string> {};

TEST_P(KdGpuCounters, RecordTheWork) {
    const KdCase c{GetParam(), "cornell.scene", 128, 128};
    const References& ref = referencesFor(c);
    RenderOptions options{.width = 64, .height = 64, .maxDepth = ref.scene.maxDepth,
                          .countTraversal = true};
    gpu::GpuRenderReport report;
    test::renderGpu(ref.scene, options, &report, c.accel);
    EXPECT_GE(report.nodesVisited, report.raysTraced + report.shadowRays);
    EXPECT_GE(report.nodesVisited, report.leavesVisited);
    EXPECT_GT(report.trianglesTested, 0u);
    if (c.accel == "kd-stack" || c.accel == "kd-packet") {
        EXPECT_EQ(report.restarts, 0u);
    } else if (c.accel == "kd-ropes") {  // only a ray leaving a leaf exactly through an edge restarts
        EXPECT_LE(report.restarts, (report.raysTraced + report.shadowRays) / 1000);
    } else {
        EXPECT_GT(report.restarts, 0u);
    }
    EXPECT_EQ(report.cappedRays, 0u);
}

// kd-shortstack's stack size is its kernel's specialization constant (kd-short-stack=N): a ring of one
// entry runs dry and restarts often, one of the whole depth never does, and both name the primary
// triangles kd-stack names, with the same triangle tests: the same leaves with triangles. (Which empty
// leaves a descent passes without stepping onto them depends on what its stack holds, kd_stack.glsl:
// the ring of one entry steps onto more of them; the deep ring walks exactly as kd-stack.)
TEST(KdGpuShortStack, AnySizeWalksTheSameLeaves) {
    const KdCase c{"kd-shortstack", "cornell.scene", 64, 48};
    const References& ref = referencesFor(c);
    const RenderOptions options{.width = c.width, .height = c.height, .maxDepth = ref.scene.maxDepth,
                                .countTraversal = true};
    gpu::GpuRenderReport stack, one, deep;
    const Frame fStack = test::renderGpu(ref.scene, options, &stack, "kd-stack");
    const Frame fOne = test::renderGpu(test::gpuContext(), ref.scene, options,
                                       accel::resolveAccel("kd-shortstack:kd-short-stack=1"), &one);
    const Frame fDeep = test::renderGpu(test::gpuContext(), ref.scene, options,
                                        accel::resolveAccel("kd-shortstack:kd-short-stack=56"), &deep);
    EXPECT_EQ(fOne.primId, fStack.primId);
    EXPECT_EQ(fDeep.primId, fStack.primId);
    EXPECT_EQ(one.trianglesTested, stack.trianglesTested);
    EXPECT_EQ(deep.trianglesTested, stack.trianglesTested);
    EXPECT_EQ(deep.nodesVisited, stack.nodesVisited);
    EXPECT_EQ(deep.leavesVisited, stack.leavesVisited);
    EXPECT_EQ(deep.restarts, 0u);
    EXPECT_GT(one.restarts, 0u);
    EXPECT_GT(one.nodesVisited, stack.nodesVisited);
}

// `kd-packet` walks kd-stack's tree with the rays of a subgroup as packets of one octant: every lane
// meets the leaves its ray reaches in kd-stack's order and ends by kd-stack's rule, so the frames are
// the same bit for bit and the lanes test the same triangles (camera, shadow and secondary rays;
// shadow rays take kd-stack's walk). The Whitted scenes' secondary rays go in every direction, so
// subgroups split into packets by octant.
TEST(KdPacketOnGpu, SameFramesAndTrianglesAsTheStackWalk) {
    test::expectPacketMatchesSingleRay("kd-stack", "kd_stack", "kd-packet", "kd_packet", true);
}

TEST(KdPacketOnGpu, CountsItsPacketsSteps) { test::expectPacketCounters("kd-stack", "kd-packet", false); }

TEST(KdPacketOnGpu, WalksOnlyCameraRaysAsPackets) { test::expectOnlyCameraRaysInPackets("kd-packet"); }

std::vector<KdCase> cases() {
    std::vector<KdCase> all;
    for (const char* accel : {"kd-stack", "kd-shortstack", "kd-restart", "kd-pushdown", "kd-ropes", "kd-backtrack", "kd-packet"})
        for (const KdCase& scene : {KdCase{"", "cornell.scene", 128, 128}, KdCase{"", "spheres.scene", 160, 90},
                                    KdCase{"", "objects.scene", 128, 96}})
            all.push_back({accel, scene.file, scene.width, scene.height});
    return all;
}

std::string testName(std::string name) {
    for (char& ch : name)
        if (ch == '-') ch = '_';
    return name;
}

INSTANTIATE_TEST_SUITE_P(Traversals, KdGpu, ::testing::ValuesIn(cases()), [](const auto& info) {
    return testName(info.param.accel + "_" + std::filesystem::path(info.param.file).stem().string());
});
INSTANTIATE_TEST_SUITE_P(Traversals, KdGpuCounters,
                         ::testing::Values("kd-stack", "kd-shortstack", "kd-restart", "kd-pushdown", "kd-ropes",
                                           "kd-backtrack", "kd-packet"),
                         [](const auto& info) { return testName(info.param); });

}  // namespace
}  // namespace vkray
