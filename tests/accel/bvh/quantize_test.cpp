// The quantised child boxes of a wide node (accel/bvh/quantize.h): every child's box on the grid
// holds its real box, exactly (the grid's planes are exact in double), and lies within one step of
// it on each side, plus the corner's rounding; random boxes at magnitudes from 1e-30 to 1e30, tiny
// children beside large ones, flat (walls) and point boxes, one child and four.
#include <cmath>
#include <limits>
#include <string>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "accel/bvh/quantize.h"
#include "core/error.h"

namespace vkray::bvh {
namespace {

// Checks every child of the node made of `boxes`: held, and loose by at most one step (and the
// corner's rounding, at most one float ulp of the node's largest magnitude, on the lower side).
void checkNode(const std::vector<Aabb>& boxes) {
    gpu::uvec4 child(VKRAY_BVH_NO_CHILD);
    for (size_t k = 0; k < boxes.size(); ++k) child[int(k)] = uint32_t(k) + 1;
    const gpu::GpuBvhNode node = quantizedNode(boxes, child);
    EXPECT_EQ(node.child, child);
    Aabb all;
    for (const Aabb& b : boxes) all.grow(b);
    for (size_t k = 0; k < boxes.size(); ++k) {
        const GridBox g = gridBox(node, int(k));
        ASSERT_TRUE(g.contains(boxes[k])) << "child " << k;
        for (int a = 0; a < 3; ++a) {
            const double step = gridStep(node, a);
            const double magnitude = std::max(std::abs(double(all.lo[a])), std::abs(double(all.hi[a])));
            const double cornerSlack = std::ldexp(1.0, std::ilogb(std::max(magnitude, 1e-30)) - 23);
            // The plane one step inside is inside the box (both sides exact: planes are multiples of
            // the corner's grid; the box's bound far smaller than the step would round a difference).
            EXPECT_LT(g.hi[a] - step, boxes[k].hi[a]) << "axis " << a;
            EXPECT_GT(g.lo[a] + step + cornerSlack, boxes[k].lo[a]) << "axis " << a;
            // The step is the smallest that spans the node from its corner, or the next (a corner
            // aligned with a flat child), or the floor (2^-30 of the magnitude, 2^-126).
            const bool floor =
                step <= std::ldexp(magnitude, -29) || step == std::ldexp(1.0, 1 - VKRAY_BVH_EXPONENT_BIAS);
            EXPECT_TRUE(floor || 255.0 * step < 4.0 * (double(all.hi[a]) - all.lo[a] + cornerSlack)) << "axis " << a;
        }
    }
}

Aabb randomBox(std::mt19937& rng, float centre, float size) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    Aabb b;
    for (int v = 0; v < 2; ++v)
        b.grow(glm::vec3(centre + size * u(rng), centre + size * u(rng), centre + size * u(rng)));
    return b;
}

TEST(Quantize, ChildBoxesHoldTheirBoxesWithinOneStep) {
    std::mt19937 rng(7);
    for (const float scale : {1e-30f, 1e-10f, 1e-3f, 1.0f, 3.0f, 1e4f, 1e7f, 1e20f, 1e30f}) {
        for (int trial = 0; trial < 200; ++trial) {
            SCOPED_TRACE("scale " + std::to_string(scale) + " trial " + std::to_string(trial));
            std::vector<Aabb> boxes;
            const int n = 1 + trial % VKRAY_BVH_WIDTH;
            const float centre = (trial % 3 == 0 ? 0.0f : trial % 3 == 1 ? 5.0f : -1e3f) * scale;
            const float size = scale * (trial % 7 == 0 ? 1e-5f : 1.0f);
            for (int k = 0; k < n; ++k) boxes.push_back(randomBox(rng, centre, size));
            if (trial % 5 == 0) boxes[0].hi.y = boxes[0].lo.y;  // flat on y: a wall
            if (trial % 10 == 0 && n > 1) boxes[1].hi.y = boxes[1].lo.y = boxes[0].lo.y;
            checkNode(boxes);
        }
    }
}

TEST(Quantize, TinyAndFlatChildrenBesideLargeOnes) {
    // A child's bound of 2^-56 beside the corner -0.25: the quotient (hi - corner) / step rounds to
    // a whole step in double, which the exact comparison corrects.
    checkNode({Aabb{glm::vec3(-0.25f), glm::vec3(0.0f)}, Aabb{glm::vec3(-0.125f), glm::vec3(std::ldexp(1.1f, -56))}});
    // A tiny box far from a large one, a point, a flat box, a box at 1e30.
    checkNode({Aabb{glm::vec3(1e-20f), glm::vec3(2e-20f)}, Aabb{glm::vec3(1.0f), glm::vec3(1.0f)},
               Aabb{glm::vec3(0.5f, 0.5f, 0.0f), glm::vec3(0.75f, 0.5f, 0.0f)},
               Aabb{glm::vec3(-1e30f), glm::vec3(-1e30f, 3e30f, 1e30f)}});
    // Every child the same point: no extent at all.
    checkNode({Aabb{glm::vec3(3.0f), glm::vec3(3.0f)}, Aabb{glm::vec3(3.0f), glm::vec3(3.0f)}});
}

TEST(Quantize, FlatChildrenStayFlatWhereTheCornerCanAlignWithThem) {
    // The Cornell box's light panel (y = 1.995) beside the room: off the room's grid, on its own.
    const std::vector<Aabb> boxes = {Aabb{glm::vec3(-1.0f, 0.0f, -1.0f), glm::vec3(1.0f, 2.0f, 1.0f)},
                                     Aabb{glm::vec3(-0.3f, 1.995f, -0.3f), glm::vec3(0.3f, 1.995f, 0.3f)}};
    checkNode(boxes);
    const gpu::GpuBvhNode node =
        quantizedNode(boxes, gpu::uvec4(1u, 2u, VKRAY_BVH_NO_CHILD, VKRAY_BVH_NO_CHILD));
    const GridBox panel = gridBox(node, 1);
    EXPECT_EQ(panel.lo.y, double(1.995f));
    EXPECT_EQ(panel.hi.y, double(1.995f));
}

TEST(Quantize, RefusesWhatNoGridHolds) {
    const gpu::uvec4 child(1u, VKRAY_BVH_NO_CHILD, VKRAY_BVH_NO_CHILD, VKRAY_BVH_NO_CHILD);
    EXPECT_THROW(quantizedNode(std::vector<Aabb>{Aabb{}}, child), Error);  // empty
    const float inf = std::numeric_limits<float>::infinity();
    EXPECT_THROW(quantizedNode(std::vector<Aabb>{Aabb{glm::vec3(0.0f), glm::vec3(inf)}}, child), Error);
    EXPECT_THROW(quantizedNode(std::vector<Aabb>{}, child), Error);
    EXPECT_THROW(quantizedNode(std::vector<Aabb>(VKRAY_BVH_WIDTH + 1, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)}), child),
                 Error);
}

}  // namespace
}  // namespace vkray::bvh
