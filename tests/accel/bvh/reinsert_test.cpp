// Insertion-based optimisation (accel/bvh/reinsert.h): the tree stays a full binary tree over the
// same primitives with exact boxes and the same root box, it lowers the SAH cost of AAC's trees,
// and it is deterministic.
#include <cstdio>
#include <cstring>

#include <gtest/gtest.h>

#include "accel/bvh/aac_builder.h"
#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/leaf_collapse.h"
#include "accel/bvh/primitives.h"
#include "accel/bvh/reinsert.h"
#include "binary_tree_check.h"
#include "bvh_test_meshes.h"

namespace vkray::bvh {
namespace {

BinaryTree aacTree(const PrimitiveSet& prims, const Config& config) {
    PhaseLog log;
    return buildAac(prims, config, log);
}

Config reinserting(Config c, int iterations) {
    c.reinsertIterations = iterations;
    return c;
}

TEST(Reinsertion, KeepsTheTreeValid) {
    for (const test::NamedMesh& mesh : test::testMeshes())
        for (const double batch : {0.01, 0.05, 1.0}) {
            SCOPED_TRACE(mesh.name + ", batch " + std::to_string(batch));
            const PrimitiveSet prims = primitivesOf(mesh.scene.triangles);
            Config config = reinserting(Config::aacFast(), 5);
            config.reinsertBatch = batch;
            BinaryTree tree = aacTree(prims, config);
            const Aabb rootBox = tree.nodes[tree.root].box;
            reinsertNodes(tree, config);
            test::checkBinaryTree(tree, prims);
            EXPECT_EQ(tree.nodes[tree.root].box.lo, rootBox.lo);
            EXPECT_EQ(tree.nodes[tree.root].box.hi, rootBox.hi);
        }
}

// Trees of two and three primitives: nothing to move, or one inner node below the root to take
// out; either way the same primitives stay.
TEST(Reinsertion, TinyTrees) {
    for (int n = 1; n <= 4; ++n) {
        const Scene scene = test::randomSoup(5, n, 0.3f);
        const PrimitiveSet prims = primitivesOf(scene.triangles);
        const Config config = reinserting(Config::aacHq(), 3);
        BinaryTree tree = aacTree(prims, config);
        reinsertNodes(tree, config);
        test::checkBinaryTree(tree, prims);
    }
}

// AAC-Fast's and AAC-HQ's trees of a sphere and of a random soup: the optimisation must lower the
// collapsed tree's SAH cost by more than the rounding of summing it.
TEST(Reinsertion, LowersTheCostOfAacTrees) {
    const Scene sphere = test::uvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 60, 120);
    const Scene soup = test::randomSoup(3, 5000, 0.05f);
    for (const Scene* scene : {&sphere, &soup})
        for (const Config& preset : {Config::aacFast(), Config::aacHq()}) {
            const double before = buildFlatBvh(scene->triangles, preset).flat.sahCost;
            const double after = buildFlatBvh(scene->triangles, reinserting(preset, 20)).flat.sahCost;
            std::printf("measured: sah cost %.4f, reinserted %.4f\n", before, after);
            EXPECT_LT(after, before * 0.99);
        }
}

TEST(Reinsertion, SameTreeEveryRun) {
    const Scene soup = test::randomSoup(9, 20000, 0.03f);
    const PrimitiveSet prims = primitivesOf(soup.triangles);
    const Config config = reinserting(Config::aacHq(), 10);
    BinaryTree a = aacTree(prims, config), b = aacTree(prims, config);
    reinsertNodes(a, config);
    reinsertNodes(b, config);
    EXPECT_EQ(a.root, b.root);
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    EXPECT_EQ(std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BinaryNode)), 0);
}

}  // namespace
}  // namespace vkray::bvh
