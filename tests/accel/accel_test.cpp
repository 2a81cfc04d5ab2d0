// The accelerator registry: every `--accel` name (README.md, "Accelerators") parses to the family and
// traversal it names, an unknown name is an error that lists the known ones, and every accelerator built
// over the same scene answers like brute force through the common BuiltAccel interface.
#include <algorithm>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "core/error.h"
#include "cpu/brute_force.h"

namespace vkray::accel {
namespace {

TEST(Accel, EveryDesignNameParses) {
    for (const std::string name : {"bvh", "bvh-fast", "bvh-hq", "kd-restart", "kd-backtrack", "kd-stack", "brute"})
        EXPECT_NE(std::find(accelNames().begin(), accelNames().end(), name), accelNames().end()) << name;
    EXPECT_EQ(parseAccel("brute").family, Family::Brute);
    EXPECT_EQ(parseAccel("bvh-hq").family, Family::Bvh);
    EXPECT_TRUE(parseAccel("bvh-sah").bvhSahReference);
    EXPECT_FALSE(parseAccel("bvh").bvhSahReference);
    EXPECT_EQ(parseAccel("kd-stack").kdTraversal, KdTraversal::Stack);
    EXPECT_EQ(parseAccel("kd-restart").kdTraversal, KdTraversal::Restart);
    EXPECT_EQ(parseAccel("kd-backtrack").kdTraversal, KdTraversal::Backtrack);
    EXPECT_EQ(parseAccel("kd-backtrack").family, Family::Kd);
}

TEST(Accel, UnknownNameListsTheKnownOnes) {
    try {
        parseAccel("octree");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("octree"), std::string::npos) << what;
        EXPECT_NE(what.find("kd-backtrack"), std::string::npos) << what;
    }
}

// A random soup of small triangles in the unit cube, one material.
Scene randomSoup(int count, unsigned seed) {
    Scene s;
    s.materials.push_back(Material{});
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-1.0f, 1.0f), off(-0.2f, 0.2f);
    for (int k = 0; k < count; ++k) {
        const glm::vec3 c{pos(rng), pos(rng), pos(rng)};
        s.triangles.push_back({c + glm::vec3(off(rng), off(rng), off(rng)),
                               c + glm::vec3(off(rng), off(rng), off(rng)),
                               c + glm::vec3(off(rng), off(rng), off(rng)), 0});
    }
    return s;
}

// Every accelerator through the one interface the renderers use: same closest triangle and t as
// brute force, same any-hit answer, and a triangle order that is a permutation when given.
class EveryAccel : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryAccel, AnswersLikeBruteForce) {
    const Scene scene = randomSoup(600, 7);
    const auto built = buildAccel(scene, parseAccel(GetParam()), BuildOptions{.threads = 2, .progress = {}});
    const cpu::BruteForceTracer brute(scene);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    int hits = 0;
    for (int k = 0; k < 2000; ++k) {
        // From outside or inside the soup towards a point in it: most rays meet something.
        const glm::dvec3 origin{u(rng) * 3.0, u(rng) * 3.0, u(rng) * 3.0};
        const glm::dvec3 target{u(rng), u(rng), u(rng)};
        const cpu::Ray ray{origin, glm::normalize(target - origin)};
        const cpu::Hit want = brute.closest(ray, 1e30), got = built->tracer().closest(ray, 1e30);
        ASSERT_EQ(got.triangle, want.triangle) << GetParam() << " ray " << k;
        if (want.found()) {
            ++hits;
            EXPECT_NEAR(got.t, want.t, 1e-9 * want.t);
        }
        EXPECT_EQ(built->tracer().occluded(ray, 1.5), brute.occluded(ray, 1.5)) << GetParam() << " ray " << k;
    }
    EXPECT_GT(hits, 1000);  // the rays do meet the soup

    const GpuAccelData gpu = built->gpuData();
    if (!gpu.triangleOrder.empty()) {
        std::vector<uint32_t> sorted = gpu.triangleOrder;
        std::sort(sorted.begin(), sorted.end());
        for (uint32_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], k);
        EXPECT_EQ(sorted.size(), scene.triangles.size());
    }
}

INSTANTIATE_TEST_SUITE_P(Names, EveryAccel, ::testing::ValuesIn(accelNames()),
                         [](const auto& info) {
                             std::string n = info.param;
                             std::replace(n.begin(), n.end(), '-', '_');
                             return n;
                         });

}  // namespace
}  // namespace vkray::accel
