// AAC on the cases a Morton order cannot split or where boxes cover boxes (triangles sharing one
// centroid, coplanar overlapping ones, one huge triangle among tiny ones, exact duplicates): every
// AAC preset's tree against the binned-SAH reference (bvh-sah) of the same leaf policy.
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "accel/bvh/bvh_accel.h"
#include "bvh_test_meshes.h"

namespace vkray::bvh {
namespace {

struct Preset {
    std::string name;
    Config config;
};

// The AAC presets of `vkray render --accel` (accel/accel_spec.cpp); bvh-stackless walks bvh's tree.
std::vector<Preset> aacPresets() {
    return {{"bvh", Config::aacHqRestructured()},
            {"bvh-fast", Config::aacFast()},
            {"bvh-hq", Config::aacHq()},
            {"bvh-sphere", Config::aacHqSpheres()}};
}

// How much worse than binned SAH each mesh's AAC trees may be, in SAH cost. Measured (ratios to
// binned SAH, presets bvh / bvh-fast / bvh-hq / bvh-sphere, 20,000 triangles):
//  - equal_centroids: binned SAH cannot split (every centroid in one bin, so it halves the triangle
//    order); AAC orders the tied run by box area (aac_builder.cpp, orderTiedRuns) and clusters:
//    0.56 / 0.82 / 0.62 / 0.57. No worse at all.
//  - coplanar: 0.70 / 0.98 / 0.81 / 0.35. No worse at all.
//  - huge_among_tiny: the huge triangle's box holds every other, the root pays it in any tree:
//    1.002 / 1.005 / 1.003 / 1.012. At most 2% worse.
//  - duplicated (400 triangles, 50 exact copies each): 0.99 / 1.04 / 1.33 / 0.74. Copies have equal
//    boxes, so every merge of two is a tie, which the clustering gives to the lowest position: a
//    leaf range's copies merge in a chain, whose leaf collapse keeps the bottom 8 as a leaf and
//    every copy above it as a leaf of its own; delta = 20 (bvh-hq) leaves the longest chains. At
//    most 35% worse.
double allowedRatio(const std::string& mesh) {
    if (mesh == "huge_among_tiny") return 1.02;
    if (mesh == "duplicated") return 1.35;
    return 1.0;
}

TEST(BvhTies, AacPresetsAreNoWorseThanBinnedSahOnDegenerateMeshes) {
    for (const test::NamedMesh& mesh : test::degenerateMeshes(20000)) {
        const double sah = buildFlatBvh(mesh.scene.triangles, Config::binnedSah()).flat.sahCost;
        for (const Preset& p : aacPresets()) {
            const double cost = buildFlatBvh(mesh.scene.triangles, p.config).flat.sahCost;
            std::printf("measured %s %s: sah cost %.2f, binned SAH %.2f (ratio %.3f)\n", mesh.name.c_str(),
                        p.name.c_str(), cost, sah, cost / sah);
            EXPECT_LE(cost, sah * allowedRatio(mesh.name)) << mesh.name << " " << p.name;
        }
    }
}

}  // namespace
}  // namespace vkray::bvh
