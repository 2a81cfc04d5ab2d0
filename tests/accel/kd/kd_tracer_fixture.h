// What the kd traversal tests share: a scene with its SAH kd-tree (its node boxes and parent links
// derived, which the tests read), a brute-force tracer for the truth, and the tracer of one
// traversal (kd-ropes' with the tree's ropes built).
#pragma once

#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include "accel/kd/kd_ropes.h"
#include "accel/kd/kd_traversal.h"
#include "geometry/brute_force.h"
#include "kd_test_util.h"

namespace vkray::test {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

// The tracer of `traversal` over `tree`; kd-ropes' needs the tree's ropes first, kd-backtrack's its
// parent links (kept where the test made its own).
inline std::unique_ptr<accel::kd::KdTracer> tracerFor(accel::kd::Traversal traversal, accel::kd::KdTree& tree,
                                                      std::vector<geometry::TriangleVertices> tris,
                                                      int maxSteps = VKRAY_KD_MAX_STEPS) {
    if (traversal == accel::kd::Traversal::Ropes) tree.ropes = accel::kd::buildRopes(tree, 2);
    if (traversal == accel::kd::Traversal::Backtrack && tree.extra.empty()) accel::kd::deriveNodeExtras(tree, 2);
    return accel::kd::makeKdTracer(traversal, tree, std::move(tris), maxSteps);
}

struct Fixture {
    Scene scene;
    accel::kd::KdTree tree;
    std::unique_ptr<geometry::BruteForceTracer> brute;
    std::unique_ptr<accel::kd::KdTracer> kd;

    Fixture(Scene s, accel::kd::Traversal traversal) : scene(std::move(s)) {
        tree = accel::kd::buildSahKdTree(scene.triangles, accel::kd::KdConfig{}, 2).tree;
        accel::kd::deriveNodeExtras(tree, 2);
        brute = std::make_unique<geometry::BruteForceTracer>(scene);
        kd = tracerFor(traversal, tree, geometry::triangleVertices(scene));
    }
};

}  // namespace vkray::test
