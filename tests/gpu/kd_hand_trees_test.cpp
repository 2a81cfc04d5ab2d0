// The kd kernels on the hand-made trees of tests/accel/kd/kd_hand_trees.h: rays lying in split
// planes, where a walk that takes one side of an in-plane node finds the decoy on the other side.
// The scene is the tree's triangles seen from the tree's ray, at an odd size so that the centre
// pixel's camera ray is that ray exactly (its zero components zero), and every kernel walking the
// hand-made tree must name brute force's primary triangle at every pixel: triangle 0 at the centre.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/accel_spec.h"
#include "accel/kd/kd_accel.h"
#include "accel/kd/kd_hand_trees.h"
#include "accel/kd/kd_ropes.h"
#include "gpu_test_util.h"

namespace vkray {
namespace {

// The hand tree's triangles as a scene file, seen from its ray's origin along the ray.
Scene handScene(const test::HandTree& h) {
    const glm::dvec3 eye = h.ray.origin, centre = h.ray.origin + h.ray.dir;
    const glm::dvec3 up = h.ray.dir.z != 0.0 ? glm::dvec3(0, 1, 0) : glm::dvec3(0, 0, 1);
    std::string text = "size 5 5\nmaxdepth 1\nambient 1 1 1\ndiffuse 0 0 0\n";
    char line[160];
    std::snprintf(line, sizeof line, "camera %.9g %.9g %.9g  %.9g %.9g %.9g  %.9g %.9g %.9g  40\n", eye.x, eye.y, eye.z,
                  centre.x, centre.y, centre.z, up.x, up.y, up.z);
    text += line;
    for (const Triangle& t : h.scene.triangles) {
        for (const glm::vec3& p : {t.p0, t.p1, t.p2}) {
            std::snprintf(line, sizeof line, "vertex %.9g %.9g %.9g\n", p.x, p.y, p.z);
            text += line;
        }
    }
    for (size_t i = 0; i < h.scene.triangles.size(); ++i)
        text += "tri " + std::to_string(3 * i) + " " + std::to_string(3 * i + 1) + " " + std::to_string(3 * i + 2) + "\n";
    return parseSceneText(text, "hand-tree.scene", ".");
}

void expectEveryKernelFindsTriangleZero(test::HandTree h) {
    const Scene scene = handScene(h);
    ASSERT_EQ(scene.origin, glm::dvec3(0.0));  // the tree's coordinates are the scene's
    ASSERT_EQ(scene.triangles.size(), h.scene.triangles.size());
    for (size_t i = 0; i < scene.triangles.size(); ++i) {
        ASSERT_EQ(scene.triangles[i].p0, h.scene.triangles[i].p0);
        ASSERT_EQ(scene.triangles[i].p1, h.scene.triangles[i].p1);
        ASSERT_EQ(scene.triangles[i].p2, h.scene.triangles[i].p2);
    }
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
