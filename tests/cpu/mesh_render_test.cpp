// A mesh rendered by itself (`vkray render MESH`, scene/mesh_scene.h) is a visible, lit object: the
// CPU reference's image of tests/scene/data/cube.off has the box in the middle, its three faces the
// camera sees each lit well above the ambient term, and the background around it.
#include <algorithm>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "cpu/reference_renderer.h"
#include "scene/mesh_scene.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

TEST(MeshRender, TheMeshIsLitAndInView) {
    const Scene scene = loadScene(std::filesystem::path(VKRAY_SOURCE_DIR) / "tests/scene/data/cube.off");
    RenderOptions options;
    options.width = 64;
    options.height = 48;
    options.maxDepth = scene.maxDepth;
    options.threads = 2;
    options.primaryAovs = true;
    const Frame f = renderReference(scene, options);
    // The ambient term alone, for the brightest channel: a lit pixel has more than twice it.
    const float ambient = kMeshDefaultMaterial.ambient.g;
    size_t hits = 0, lit = 0;
    std::vector<bool> facesLit(6, false);  // by quad: two triangles each, in cube.off's order
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const size_t i = f.index(x, y);
            const bool border = x == 0 || y == 0 || x == f.width - 1 || y == f.height - 1;
            if (f.primId[i] < 0) continue;
            EXPECT_FALSE(border) << "the mesh touches the image's edge at " << x << "," << y;
            ++hits;
            const glm::vec3 c = f.color[i];
            if (std::max({c.r, c.g, c.b}) > 2.0f * ambient) {
                ++lit;
                facesLit[size_t(f.primId[i]) / 2] = true;
            }
        }
    EXPECT_GT(hits, size_t(f.width * f.height) / 5) << "the mesh should fill a good part of the image";
    EXPECT_GT(lit, hits * 9 / 10) << "the faces in view should be lit";
    EXPECT_TRUE(facesLit[1]) << "front (+z)";
    EXPECT_TRUE(facesLit[3]) << "top (+y)";
    EXPECT_TRUE(facesLit[5]) << "right (+x)";
}

}  // namespace
}  // namespace vkray
