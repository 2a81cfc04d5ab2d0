// The CPU baseline traces the kernels' camera rays: Embree names the same primary triangle as the
// double-precision reference (brute force) on nearly every pixel, and both queries agree.
#include <cstddef>
#include <string>

#include <gtest/gtest.h>

#include "bench/embree_baseline.h"
#include "cpu/reference_renderer.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray::bench {
namespace {

double agreement(const std::vector<int32_t>& a, const std::vector<int32_t>& b) {
    size_t same = 0;
    for (size_t i = 0; i < a.size(); ++i) same += a[i] == b[i];
    return double(same) / double(a.size());
}

TEST(EmbreeBaseline, NamesTheReferencesPrimaryTriangles) {
    if (!embreeAvailable()) GTEST_SKIP() << embreeMissingNote();
    Scene scene = loadScene(std::string(VKRAY_SOURCE_DIR) + "/scenes/spheres.scene");
    scene.camera = viewCamera(scene, "close");
    const RenderOptions options{.width = 64, .height = 48, .maxDepth = 1, .threads = 0, .countTraversal = false};
    const Frame reference = renderReference(scene, options);

    const auto embree = makeEmbreeBaseline(scene, options.width, options.height);
    ASSERT_NE(embree, nullptr);
    EXPECT_NE(embree->version().find("Embree 3."), std::string::npos) << embree->version();
    EXPECT_GT(embree->traceMs(EmbreeQuery::Single, 2), 0.0);
    const std::vector<int32_t> single = embree->hits();
    ASSERT_EQ(single.size(), reference.primId.size());
    EXPECT_GT(embree->traceMs(EmbreeQuery::Packet16, 2), 0.0);
    const std::vector<int32_t> packet = embree->hits();

    size_t hits = 0;
    for (int32_t id : reference.primId) hits += id >= 0;
    EXPECT_GT(hits, reference.primId.size() / 2) << "the close-up should be mostly hits";
    // Ties on shared edges may go to either triangle (Embree has no tie rule): a few pixels at most.
    EXPECT_GE(agreement(single, reference.primId), 0.99);
    EXPECT_GE(agreement(packet, reference.primId), 0.99);
    EXPECT_GE(agreement(single, packet), 0.99);
}

}  // namespace
}  // namespace vkray::bench
