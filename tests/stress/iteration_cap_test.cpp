// No ray may hang the GPU (lavapipe has no watchdog): every traversal loop has an iteration
// cap, and a ray that reaches it is reported (GpuRenderReport::cappedRays), not hidden and not
// looping forever. The trees here are malformed on purpose, so that every ray that enters them
// loops: a BVH whose root names itself as its right child, and a kd-tree whose root is its own
// above child. The builders never make such trees; this checks the kernels' last line of defence.
#include <cstring>
#include <vector>

#include <gtest/gtest.h>

#include "../gpu/gpu_test_util.h"
#include "accel/accel.h"
#include "accel/bvh/quantize.h"
#include "gpu/gpu_renderer.h"
#include "gpu/kernel_registry.h"
#include "shared/bvh_layout.h"
#include "shared/kd_layout.h"

namespace vkray {
namespace {

constexpr int kSize = 8;

// One triangle in z = 0 under a camera looking down -z; its box [-2, 2]^2 x [-1, 1] fills the view.
Scene oneTriangleScene() {
    Scene s;
    s.width = s.height = kSize;
    s.maxDepth = 1;
    s.camera = Camera{{0, 0, 3}, {0, 0, 0}, {0, 1, 0}, 40};
    s.hasCamera = true;
    s.materials.push_back(Material{});
    s.triangles.push_back({{-2, -2, 0}, {2, -2, 0}, {0, 2, 0}, 0});
    return s;
}

const glm::vec3 kLo(-2, -2, -1), kHi(2, 2, 1);

accel::GpuAccelData cyclicBvh(accel::Traversal traversal) {
    accel::GpuAccelData data;
    data.traversal = traversal;
    // One node whose first child is a leaf (triangle slot 0) and whose second is itself: the leaf is
    // tested, the node popped again, forever.
    const bvh::Aabb box{kLo, kHi};
    const bvh::Aabb boxes[] = {box, box};
    const gpu::GpuBvhNode node = bvh::quantizedNode(
        boxes, gpu::uvec4(VKRAY_BVH_LEAF_BIT, 0u, VKRAY_BVH_NO_CHILD, VKRAY_BVH_NO_CHILD));
    const std::vector<gpu::GpuBvhNode> nodes = {node};
    data.nodes = accel::asBytes(nodes);
    if (traversal == accel::Traversal::BvhSphere) {  // the same two children as spheres holding the box
        const glm::vec3 c = 0.5f * (kLo + kHi);
        const float r = glm::length(kHi - kLo);
        const gpu::GpuBvhSphereNode sphere{.centreX = gpu::vec4(c.x), .centreY = gpu::vec4(c.y),
                                           .centreZ = gpu::vec4(c.z), .radius = gpu::vec4(r), .child = node.child};
        data.nodes = accel::asBytes(std::vector<gpu::GpuBvhSphereNode>{sphere});
    }
    // The root's parent link (the stackless walk: bvh-stackless, and every BVH kernel's shadow
    // rays), in the box node (quantizedNode's) or beside the sphere node; the walk goes down into
    // itself before it ever climbs.
    if (traversal == accel::Traversal::BvhSphere) data.indices = accel::asBytes(std::vector<uint32_t>{VKRAY_BVH_NO_PARENT});
    return data;
}

accel::GpuAccelData cyclicKd(accel::Traversal traversal) {
    accel::GpuAccelData data;
    data.traversal = traversal;
    data.nodeTexelBytes = VKRAY_KD_NODE_TEXEL_BYTES;  // as the kd-tree's own gpuData() says
    const gpu::KdTreeHeader header{.lo = kLo, .nodeCount = 2, .hi = kHi, .indexCount = 1};
    // Root: split z = 0.5, below child = node 1 (a leaf), above child = the root itself. A ray coming
    // down from z = 3 enters the above side first, forever.
    const std::vector<gpu::KdNode> nodes = {gpu::KdNode::inner(2, 0.5f, 0), gpu::KdNode::leaf(0, 1)};
    data.nodes.resize(sizeof(header) + nodes.size() * sizeof(gpu::KdNode));
    std::memcpy(data.nodes.data(), &header, sizeof(header));
    std::memcpy(data.nodes.data() + sizeof(header), nodes.data(), nodes.size() * sizeof(gpu::KdNode));
    data.indices = accel::asBytes(std::vector<uint32_t>{0});
    if (traversal == accel::Traversal::KdBacktrack)
        data.extra = accel::asBytes(std::vector<gpu::KdNodeExtra>{
            {.lo = kLo, .parent = VKRAY_KD_NO_PARENT, .hi = kHi, .pad0 = 0}, {.lo = kLo, .parent = 0, .hi = kHi, .pad0 = 0}});
    return data;
}

class IterationCap : public ::testing::TestWithParam<accel::Traversal> {};

TEST_P(IterationCap, RunawayRaysEndAndAreCounted) {
    const Scene scene = oneTriangleScene();
    const accel::Traversal traversal = GetParam();
    const bool bvh = traversal == accel::Traversal::Bvh || traversal == accel::Traversal::BvhStackless ||
                     traversal == accel::Traversal::BvhPacket || traversal == accel::Traversal::BvhSphere;
    const accel::GpuAccelData data = bvh ? cyclicBvh(traversal) : cyclicKd(traversal);
    RenderOptions options{.width = kSize, .height = kSize, .maxDepth = 1};
    gpu::GpuRenderReport report;
    const Frame f = gpu::renderOnGpu(test::gpuContext(), scene, options, data, &report);
    // Every camera ray enters the box and loops: each ends at the cap and is counted (the render
    // returns at all: no hang), and the image is still delivered.
    EXPECT_EQ(report.cappedRays, uint64_t(kSize * kSize));
    EXPECT_EQ(report.pixelsCutShort, 0u);
    EXPECT_EQ(f.primId.size(), size_t(kSize * kSize));
}

INSTANTIATE_TEST_SUITE_P(Stress, IterationCap,
                         ::testing::Values(accel::Traversal::Bvh, accel::Traversal::BvhStackless, accel::Traversal::BvhPacket, accel::Traversal::BvhSphere, accel::Traversal::KdStack, accel::Traversal::KdRestart,
                                           accel::Traversal::KdPushDown, accel::Traversal::KdShortStack, accel::Traversal::KdRopes,
                                           accel::Traversal::KdBacktrack, accel::Traversal::KdPacket),
                         [](const auto& info) { return std::string(gpu::kernelName(info.param)); });

}  // namespace
}  // namespace vkray
