// packScene: an accelerator's triangle order moves triangles and their normals together and keeps
// the identity; an order that is not a permutation is refused before anything reaches the GPU.
#include <gtest/gtest.h>

#include "core/error.h"
#include "gpu/scene_buffers.h"

namespace vkray {
namespace {

Scene threeTriangles() {
    Scene s;
    s.materials.push_back(Material{});
    for (int k = 0; k < 3; ++k) {
        const float x = float(k);
        s.triangles.push_back({{x, 0, 0}, {x + 1, 0, 0}, {x, 1, 0}, 0});
        s.normals.push_back({{x, 0, 1}, {0, x, 1}, {0, 0, 1}});
    }
    return s;
}

TEST(PackScene, SceneOrderByDefault) {
    const gpu::PackedScene p = gpu::packScene(threeTriangles());
    ASSERT_EQ(p.triangles.size(), 3u);
    for (uint32_t k = 0; k < 3; ++k) EXPECT_EQ(p.triangles[k].original, k);
}

TEST(PackScene, TriangleOrderMovesTrianglesAndNormalsTogether) {
    const Scene s = threeTriangles();
    const gpu::PackedScene p = gpu::packScene(s, {2, 0, 1});
    const uint32_t expected[] = {2, 0, 1};
    for (uint32_t slot = 0; slot < 3; ++slot) {
        const uint32_t k = expected[slot];
        EXPECT_EQ(p.triangles[slot].original, k);
        EXPECT_EQ(p.triangles[slot].p0, s.triangles[k].p0);
        EXPECT_EQ(glm::vec3(p.normals[slot].n0), s.normals[k].n0);
    }
}

TEST(PackScene, RefusesAnOrderThatIsNotAPermutation) {
    const Scene s = threeTriangles();
    EXPECT_THROW(gpu::packScene(s, {0, 1}), Error);
    EXPECT_THROW(gpu::packScene(s, {0, 1, 1}), Error);
    EXPECT_THROW(gpu::packScene(s, {0, 1, 3}), Error);
}

}  // namespace
}  // namespace vkray
