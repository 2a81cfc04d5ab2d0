// The kd kernels on the hand-made trees of tests/accel/kd/kd_hand_trees.h: rays lying in split
// planes, where a walk that takes one side of an in-plane node finds the decoy on the other side.
// The scene, built in code, is the tree's triangles seen from the tree's ray, at an odd size so that
// the centre pixel's camera ray is that ray exactly (its zero components zero), and every kernel
// walking the hand-made tree must name brute force's primary triangle at every pixel: triangle 0 at
// the centre.
#include <gtest/gtest.h>

#include "accel/accel_spec.h"
#include "accel/kd/kd_accel.h"
#include "accel/kd/kd_hand_trees.h"
#include "accel/kd/kd_ropes.h"
#include "gpu_test_util.h"
#include "support/scene_builder.h"

namespace vkray {
namespace {

// The hand tree's triangles (in the tree's coordinates: origin 0) seen from its ray's origin
// along the ray, in a material that shows only which triangle a pixel sees.
Scene handScene(const test::HandTree& h) {
    Scene s = h.scene;
    s.camera.eye = glm::vec3(h.ray.origin);
    s.camera.center = glm::vec3(h.ray.origin + h.ray.dir);
    s.camera.up = h.ray.dir.z != 0.0 ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
    s.camera.fovyDegrees = 40.0f;
    s.hasCamera = true;
    s.materials = {test::blackMaterial()};
    return s;
}

void expectEveryKernelFindsTriangleZero(test::HandTree h) {
    const Scene scene = handScene(h);
    const RenderOptions options{.width = 5, .height = 5, .maxDepth = 1};
    ASSERT_EQ(primaryDirection(makeCameraFrame(scene.camera, 5, 5), 2, 2), h.ray.dir);  // the centre ray lies in the planes
    const Frame brute = test::renderGpu(scene, options);
    ASSERT_EQ(brute.primId[brute.index(2, 2)], 0);
    h.tree.ropes = accel::kd::buildRopes(h.tree, 1);
    using accel::kd::Traversal;
    for (const Traversal traversal : {Traversal::Stack, Traversal::ShortStack, Traversal::Restart, Traversal::PushDown,
                                      Traversal::Ropes, Traversal::Backtrack, Traversal::Packet}) {
        const accel::GpuAccelData data = accel::kdGpuData(h.tree, traversal, accel::AccelSpec{}.kdShortStack);
        gpu::GpuRenderReport report;
        const Frame f = gpu::renderOnGpu(test::gpuContext(), scene, options, data, &report);
        EXPECT_EQ(f.primId, brute.primId) << report.kernel;
        EXPECT_EQ(f.primId[f.index(2, 2)], 0) << report.kernel << ": the decoy, or nothing";
        EXPECT_EQ(report.cappedRays, 0u) << report.kernel;
    }
}

TEST(KdGpuHandTrees, RayInSplitPlaneFindsTriangleTouchingItFromAbove) {
    expectEveryKernelFindsTriangleZero(test::triangleTouchingThePlaneFromAbove());
}

TEST(KdGpuHandTrees, RayAlongTwoSplitPlanesFindsTheNearestOfFourLeaves) {
    expectEveryKernelFindsTriangleZero(test::rayAlongTwoSplitPlanes());
}

}  // namespace
}  // namespace vkray
