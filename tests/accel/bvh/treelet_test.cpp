// Treelet restructuring (accel/bvh/treelet.h): the tree stays a full binary tree over the same
// primitives with exact boxes, its SAH cost never rises, and on a tree small enough to be one
// treelet it is the optimal tree, checked against an exhaustive search over every binary tree.
#include <bit>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include "accel/bvh/aac_builder.h"
#include "accel/bvh/bvh_accel.h"
#include "accel/bvh/leaf_collapse.h"
#include "accel/bvh/primitives.h"
#include "accel/bvh/treelet.h"
#include "binary_tree_check.h"
#include "bvh_test_meshes.h"

namespace vkray::bvh {
namespace {

BinaryTree aacTree(const PrimitiveSet& prims, const Config& config) {
    PhaseLog log;
    return buildAac(prims, config, log);
}

double sahCost(const BinaryTree& tree, const Config& config) { return collapseLeaves(tree, config).sahCost; }

using test::checkBinaryTree;

TEST(Treelets, KeepTheTreeValidAndNeverRaiseItsCost) {
    for (const test::NamedMesh& mesh : test::testMeshes()) {
        SCOPED_TRACE(mesh.name);
        const PrimitiveSet prims = primitivesOf(mesh.scene.triangles);
        Config config = Config::aacHq();
        BinaryTree tree = aacTree(prims, config);
        double before = sahCost(tree, config);
        for (int pass = 0; pass < 3; ++pass) {
            config.treeletPasses = 1;
            restructureTreelets(tree, config);
            checkBinaryTree(tree, prims);
            const double after = sahCost(tree, config);
            EXPECT_LE(after, before * (1.0 + 1e-12)) << "pass " << pass;
            before = after;
        }
    }
}

TEST(Treelets, LowerTheCostOfAnAacTree) {
    const Scene sphere = test::uvSphere({0.0f, 0.0f, 0.0f}, 1.0f, 60, 120);
    const Scene soup = test::randomSoup(3, 5000, 0.05f);
    for (const Scene* scene : {&sphere, &soup}) {
        const double hq = buildFlatBvh(scene->triangles, Config::aacHq()).flat.sahCost;
        const double restructured = buildFlatBvh(scene->triangles, Config::aacHqRestructured()).flat.sahCost;
        std::printf("measured: sah cost aac-hq %.4f, restructured %.4f\n", hq, restructured);
        EXPECT_LT(restructured, hq * 0.995);
    }
}

// The least cost over every full binary tree on the primitives in `set` (bit i = primitive i),
// under the collapse's rule (a subtree may become one leaf of at most maxLeafSize primitives).
double exhaustiveCost(const PrimitiveSet& prims, const Config& config, uint32_t set) {
    Aabb box;
    for (uint32_t rest = set; rest; rest &= rest - 1) box.grow(prims.boxes[std::countr_zero(rest)]);
    const double area = box.halfArea();
    const int count = std::popcount(set);
    if (count == 1) return config.sah.intersection * area;
    double best = std::numeric_limits<double>::infinity();
    for (uint32_t p = (set - 1) & set; p; p = (p - 1) & set)  // both orders of each split: harmless
        best = std::min(best, config.sah.traversal * area + exhaustiveCost(prims, config, p) +
                                  exhaustiveCost(prims, config, set ^ p));
    if (count <= config.maxLeafSize) best = std::min(best, config.sah.intersection * area * count);
    return best;
}

// Up to kTreeletLeaves primitives, the root's treelet holds them all: one pass must reach the
// optimum, whatever AAC built first.
TEST(Treelets, OneTreeletOverTheWholeTreeIsOptimal) {
    for (uint32_t seed = 1; seed <= 40; ++seed)
        for (int n = 3; n <= kTreeletLeaves; ++n) {
            SCOPED_TRACE("seed " + std::to_string(seed) + ", " + std::to_string(n) + " triangles");
            const Scene scene = test::randomSoup(seed, n, 0.4f);
            const PrimitiveSet prims = primitivesOf(scene.triangles);
            Config config = Config::withAac(1, 0.0);  // one primitive per range: a poor first tree
            config.maxLeafSize = seed % 2 ? 1 : 3;    // with and without the leaf option mattering
            BinaryTree tree = aacTree(prims, config);
            config.treeletPasses = 1;
            restructureTreelets(tree, config);
            checkBinaryTree(tree, prims);
            const double rootArea = tree.nodes[tree.root].box.halfArea();
            const double optimum = exhaustiveCost(prims, config, (1u << n) - 1) / rootArea;
            EXPECT_NEAR(sahCost(tree, config), optimum, optimum * 1e-9);
        }
}

// Node ids and boxes do not depend on the number of worker threads.
TEST(Treelets, SameTreeForAnyThreadCount) {
    const Scene big = test::randomSoup(17, 60000, 0.02f);
    const PrimitiveSet prims = primitivesOf(big.triangles);
    const Config config = Config::aacHqRestructured();
    auto build = [&](int threads) {
        return tbb::task_arena(threads).execute([&] {
            BinaryTree tree = aacTree(prims, config);
            restructureTreelets(tree, config);
            return tree;
        });
    };
    const BinaryTree one = build(1);
    for (int threads : {2, 4}) {
        const BinaryTree r = build(threads);
        EXPECT_EQ(r.root, one.root);
        ASSERT_EQ(r.nodes.size(), one.nodes.size());
        EXPECT_EQ(std::memcmp(r.nodes.data(), one.nodes.data(), one.nodes.size() * sizeof(BinaryNode)), 0)
            << threads << " threads";
    }
}

}  // namespace
}  // namespace vkray::bvh
