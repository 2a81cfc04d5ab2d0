// The scene files shipped in scenes/: each loads, has a camera, lights and triangles, and the
// camera looks at its content (the centre of the triangles' bounding box is in the view).
#include <algorithm>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

// Whether the scene loads a mesh that scripts/fetch-scenes.sh fetches (`geo meshes/...`): those
// are too large for these checks and may be absent; mesh_scenes_test.cpp covers them.
bool usesFetchedMesh(const std::filesystem::path& file) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (line.starts_with("geo meshes/") || line.starts_with("obj meshes/")) return true;
    return false;
}

// The hand-made scenes: everything in scenes/ but the fetched-mesh ones.
std::vector<std::filesystem::path> shippedScenes() {
    std::vector<std::filesystem::path> files;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::filesystem::path(VKRAY_SOURCE_DIR) / "scenes"))
        if (entry.path().extension() == ".scene" && !usesFetchedMesh(entry.path())) files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

TEST(ShippedScenes, TheDocumentedOnesExist) {
    std::vector<std::string> names;
    for (const auto& f : shippedScenes()) names.push_back(f.stem().string());
    for (const char* name : {"cornell", "default", "lights", "objects", "spheres"})
        EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}

TEST(ShippedScenes, LoadAndFrameTheirContent) {
    for (const auto& file : shippedScenes()) {
        SCOPED_TRACE(file.string());
        const Scene s = loadScene(file);
        ASSERT_TRUE(s.hasCamera);
        EXPECT_EQ(s.width, 640);
        EXPECT_EQ(s.height, 480);
        EXPECT_FALSE(s.lights.empty());
        ASSERT_FALSE(s.triangles.empty());
        EXPECT_LT(s.triangles.size(), 6000u);
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const Triangle& t : s.triangles) {
            ASSERT_LT(t.material, s.materials.size());
            for (const glm::vec3& p : {t.p0, t.p1, t.p2}) lo = glm::min(lo, p), hi = glm::max(hi, p);
        }
        const CameraFrame f = makeCameraFrame(s.camera, s.width, s.height);
        const glm::dvec3 d = glm::dvec3((lo + hi) * 0.5f) - f.eye;
        const double depth = -glm::dot(d, f.w);
        ASSERT_GT(depth, 0.0) << "the content is behind the camera";
        EXPECT_LT(std::abs(glm::dot(d, f.u) / depth), f.tanX) << "outside the view horizontally";
        EXPECT_LT(std::abs(glm::dot(d, f.v) / depth), f.tanY) << "outside the view vertically";
    }
}

}  // namespace
}  // namespace vkray
