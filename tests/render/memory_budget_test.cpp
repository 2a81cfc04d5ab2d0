// The memory estimate and the refusal of a scene that cannot fit (render/memory_budget.h): the
// estimate against what builds and packs really allocate, and the refusal's sentence with limits
// given by the test.
#include <gtest/gtest.h>

#include <string>

#include "accel/accel.h"
#include "core/error.h"
#include "gpu/scene_buffers.h"
#include "render/memory_budget.h"
#include "scene/scene_parser.h"

namespace vkray::render {
namespace {

const char* kCamera = "camera 0 0.5 4 0 0.5 0 0 1 0 45\n";

Scene generated(const std::string& kind, int triangles) {
    return parseSceneText(std::string(kCamera) + "generate " + kind + " " + std::to_string(triangles) + "\n",
                          "t.scene", ".");
}

uint64_t packedBytes(const gpu::PackedScene& p) {
    return p.triangles.size() * sizeof(gpu::GpuTriangle) + p.normals.size() * sizeof(gpu::GpuTriangleNormals) +
           p.materials.size() * sizeof(gpu::GpuMaterial) + p.lights.size() * sizeof(gpu::GpuLight);
}

// The estimate never falls short of what the structure's arrays and the device's scene buffers
// really take, and stays within five times the structure's arrays (the model holds a soup's, the
// kd-tree's worst case; a small scene of few, tessellated spheres is the furthest below it).
TEST(MemoryEstimate, CoversTheStructureAndTheDeviceBuffers) {
    for (const char* kind : {"soup", "spheres"}) {
        for (int n : {2000, 20000, 60000}) {
            const Scene scene = generated(kind, n);
            for (const char* name : {"bvh", "bvh-fast", "bvh-stackless", "kd-restart", "kd-backtrack", "kd-ropes"}) {
                const accel::AccelSpec spec = accel::resolveAccel(name);
                const accel::GpuAccelData data = accel::buildAccel(scene, spec)->gpuData();
                const gpu::PackedScene packed = gpu::packScene(scene, data.triangleOrder);
                const MemoryEstimate e = estimateMemory(scene, gpuRender(spec));
                const std::string what = std::string(kind) + " " + std::to_string(n) + " " + name;
                EXPECT_GE(e.structureBytes, data.bytes()) << what;
                EXPECT_LE(e.structureBytes, 5 * data.bytes()) << what;
                EXPECT_GE(e.deviceBytes, packedBytes(packed) + data.bytes()) << what;
                const uint64_t kept = scene.triangles.size() * sizeof(Triangle) + packedBytes(packed) + data.bytes();
                EXPECT_GE(e.hostBytes, kept) << what;
            }
        }
    }
}

TEST(MemoryEstimate, GrowsWithTheScene) {
    const MemoryUse use = gpuRender(accel::resolveAccel("kd-restart"));
    EXPECT_LT(estimateMemory(1000, 0, use).hostBytes, estimateMemory(2000, 0, use).hostBytes);
    EXPECT_LT(estimateMemory(1000, 0, use).hostBytes, estimateMemory(1000, 1000, use).hostBytes);
    EXPECT_LT(estimateMemory(1000, 0, use).deviceBytes, estimateMemory(1000, 1000, use).deviceBytes);
    // Without a device nothing is counted on one; the CPU reference needs no arrays for a kernel.
    EXPECT_EQ(estimateMemory(1000, 0, MemoryUse{.accel = accel::resolveAccel("bvh")}).deviceBytes, 0u);
    // A structure read from a file is not built: no builder's peak.
    MemoryUse loaded = use;
    loaded.build = false;
    EXPECT_LT(estimateMemory(1000000, 0, loaded).hostBytes, estimateMemory(1000000, 0, use).hostBytes);
}

// A count no scene could have gets an estimate past any machine, not one wrapped around 2^64.
TEST(MemoryEstimate, NeverWrapsAround) {
    for (const char* name : {"brute", "bvh", "kd-ropes", "rayquery"}) {
        MemoryUse use = gpuRender(accel::resolveAccel(name));
        use.deviceSharesHost = true;
        const MemoryEstimate big = estimateMemory(uint64_t(1) << 40, uint64_t(1) << 40, use);
        for (const uint64_t n : {uint64_t(1) << 58, uint64_t(1) << 60, UINT64_MAX}) {
            const MemoryEstimate e = estimateMemory(n, n, use);
            EXPECT_GE(e.hostBytes, big.hostBytes) << name << " " << n;
            EXPECT_GE(e.deviceBytes, big.deviceBytes) << name << " " << n;
            EXPECT_TRUE(memoryProblem(n, 0, use, MemoryLimits{.hostAvailable = uint64_t(1) << 40})) << name << " " << n;
        }
    }
}

constexpr uint64_t kMB = 1000000;

TEST(MemoryRefusal, NamesTheNeedTheLimitAndTheAcceleratorThatNeedsLess) {
    const MemoryUse kd = gpuRender(accel::resolveAccel("kd-restart"));
    const uint64_t n = 16000000;
    MemoryLimits limits{.hostAvailable = 64000 * kMB, .processLimit = 2000 * kMB};
    // Nothing fits 2 GB: not even brute force's scene arrays and parsing.
    auto problem = memoryProblem(n, 0, kd, limits);
    ASSERT_TRUE(problem);
    const std::string need = formatBytes(estimateMemory(n, 0, kd).hostBytes);
    EXPECT_EQ(problem->find("16000000 triangles need an estimated " + need +
                            " of host memory with --accel kd-restart, but the process's limit (ulimit -v) leaves "
                            "2.00 GB; no accelerator fits (--accel brute, the least, needs "),
              0u)
        << *problem;
    EXPECT_EQ(problem->find('\n'), std::string::npos);

    // Room for the BVH but not for the kd-tree: the BVH is named.
    limits.processLimit = estimateMemory(n, 0, gpuRender()).hostBytes + 1;
    problem = memoryProblem(n, 0, kd, limits);
    ASSERT_TRUE(problem);
    EXPECT_NE(problem->find("; --accel bvh needs less and fits"), std::string::npos) << *problem;
    EXPECT_FALSE(memoryProblem(n, 0, gpuRender(), limits));

    // The smallest limit is the one named.
    limits = {.hostAvailable = 1000 * kMB, .processLimit = 3000 * kMB, .cgroupLimit = 2000 * kMB};
    problem = memoryProblem(n, 0, kd, limits);
    ASSERT_TRUE(problem);
    EXPECT_NE(problem->find("but MemAvailable leaves 1.00 GB"), std::string::npos) << *problem;
}

TEST(MemoryRefusal, DeviceMemory) {
    const uint64_t n = 4000000;
    const MemoryUse bvh = gpuRender();
    const MemoryLimits limits{.hostAvailable = 1000000 * kMB, .deviceHeap = 256 * kMB};
    const auto problem = memoryProblem(n, 0, bvh, limits);
    ASSERT_TRUE(problem);
    EXPECT_EQ(problem->find("4000000 triangles need an estimated " + formatBytes(estimateMemory(n, 0, bvh).deviceBytes) +
                            " of device memory with --accel bvh, but the device's memory leaves 256 MB"),
              0u)
        << *problem;
    // A device that allocates from the host's memory counts its buffers there too.
    MemoryUse shared = bvh;
    shared.deviceSharesHost = true;
    EXPECT_GT(estimateMemory(n, 0, shared).hostBytes, estimateMemory(n, 0, bvh).hostBytes);
    EXPECT_FALSE(memoryProblem(n, 0, bvh, MemoryLimits{}));  // no limit known: nothing refused
}

// The refusal comes from the line that would make the triangles, before they are made.
TEST(MemoryRefusal, AtTheGeneratorLineBeforeItsTriangles) {
    ParseOptions options;
    const MemoryUse use = gpuRender();
    options.memoryProblem = [&](uint64_t triangles) {
        return memoryProblem(triangles, 0, use, MemoryLimits{.processLimit = 500 * kMB});
    };
    try {
        parseSceneText(std::string(kCamera) + "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\n"
                                              "generate soup 30000000\n",
                       "big.scene", ".", options);
        FAIL() << "expected a refusal";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_EQ(what.find("big.scene:6"), 0u) << what;
        EXPECT_NE(what.find("30000001 triangles need an estimated"), std::string::npos) << what;
        EXPECT_NE(what.find("the process's limit (ulimit -v) leaves 500 MB"), std::string::npos) << what;
    }
}

TEST(MemoryLimits, TheHostsAreRead) {
    const MemoryLimits l = hostMemoryLimits();
    ASSERT_TRUE(l.hostAvailable);  // Linux: /proc/meminfo
    EXPECT_GT(*l.hostAvailable, 0u);
    EXPECT_FALSE(l.deviceHeap);
}

}  // namespace
}  // namespace vkray::render
