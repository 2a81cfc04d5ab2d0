// A mesh file loaded by itself (scene/mesh_scene.h): its triangles as `geo` loads them, a camera
// that sees all of them, lights, a visible default material and the OBJ's own materials; and the
// error of a mesh a scene names but the repository does not hold.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene/mesh_scene.h"
#include "scene/scene_parser.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

using test::sceneDataDir;

TEST(MeshScene, AnOffMeshIsFramedLitAndVisible) {
    const Scene s = loadScene(sceneDataDir() / "cube.off");  // loadScene hands a mesh to loadMeshScene
    ASSERT_EQ(s.triangles.size(), 12u);  // six quads
    EXPECT_TRUE(s.hasCamera);
    EXPECT_EQ(s.sourceFile, sceneDataDir() / "cube.off");
    EXPECT_TRUE(s.output.empty());  // the image is cube.png
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0], kMeshDefaultMaterial);
    EXPECT_GT(kMeshDefaultMaterial.diffuse.g, 0.3f);  // not the CSE167 default, black
    ASSERT_FALSE(s.lights.empty());
    for (const Light& l : s.lights) EXPECT_GT(l.color.r, 0.0f);
    test::expectFramed(s, test::triangleBox(s));
    // The default direction: from +z, above and to the right.
    const glm::vec3 back = glm::normalize(s.camera.eye - s.camera.center);
    const glm::vec3 want = glm::normalize(kMeshViewDirection);
    EXPECT_NEAR(glm::dot(back, want), 1.0f, 1e-5f);
    EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
    // The key light is on the camera's side: the faces it sees are lit.
    EXPECT_GT(glm::dot(s.lights[0].vector, back), 0.0f);
}

TEST(MeshScene, AnObjKeepsItsMaterialsAndFillsTheRest) {
    const Scene s = loadScene(sceneDataDir() / "materials.obj");
    ASSERT_EQ(s.triangles.size(), 10u);
    EXPECT_EQ(s.materials.at(s.triangles[0].material), kMeshDefaultMaterial);  // before any usemtl
    const Material& matte = s.materials.at(s.triangles[1].material);
    EXPECT_EQ(matte.diffuse, glm::vec3(0.8f, 0.2f, 0.2f));  // materials.mtl's Kd
    EXPECT_EQ(matte.shininess, 32.0f);
    test::expectFramed(s, test::triangleBox(s));
}

// MTL texture maps are not sampled: one warning for the file, and the material's colours stand.
TEST(MeshScene, AnObjsTextureMapsAreWarnedOnceAndTheirColoursKept) {
    const std::filesystem::path dir = std::filesystem::path(VKRAY_TEST_OUTPUT_DIR) / "mesh_scene_textures";
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "t.mtl") << "newmtl a\nKd 0.5 0.25 0.125\nmap_Kd a.png\nnewmtl b\nKd 1 1 1\nmap_Kd b.png\n";
    std::ofstream(dir / "t.obj") << "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n";
    ParseOptions options;
    std::vector<std::string> warnings;
    options.warn = [&](const std::string& w) { warnings.push_back(w); };
    const Scene s = loadScene(dir / "t.obj", options);
    EXPECT_EQ(s.materials.at(s.triangles.at(0).material).diffuse, glm::vec3(0.5f, 0.25f, 0.125f));
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("2 MTL material(s) with texture maps (map_Kd ...): not sampled"), std::string::npos)
        << warnings[0];
}

TEST(MeshScene, ErrorsNameTheMeshFile) {
    try {
        loadScene(sceneDataDir() / "no_such_mesh.off");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot open OFF file '"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("no_such_mesh.off': no such file"), std::string::npos) << e.what();
        EXPECT_EQ(std::string(e.what()).find("fetch-scenes"), std::string::npos) << e.what();
    }
    try {
        loadScene(sceneDataDir() / "bad_index.obj");
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad_index.obj:"), std::string::npos) << e.what();
    }
}

// The repository's scenes find their meshes in scenes/meshes/, fetched, not committed: a missing
// one names the script that fetches it, at the scene's line; a missing mesh elsewhere does not.
TEST(MeshScene, AMissingMeshOfTheScenesNamesTheFetchScript) {
    const std::string fetched = test::parseError("camera 0 0 3 0 0 0 0 1 0 45\ngeo scenes/meshes/bunny.obj\n");
    EXPECT_NE(fetched.find("test.scene:2: cannot open OBJ file '"), std::string::npos) << fetched;
    EXPECT_NE(fetched.find("scenes/meshes/bunny.obj': no such file or directory"), std::string::npos) << fetched;
    EXPECT_NE(fetched.find("scripts/fetch-scenes.sh"), std::string::npos) << fetched;
    const std::string off = test::parseError("geo ../scenes/./meshes/elephant.off\n");
    EXPECT_NE(off.find("test.scene:1: cannot open OFF file"), std::string::npos) << off;
    EXPECT_NE(off.find("scripts/fetch-scenes.sh"), std::string::npos) << off;
    const std::string elsewhere = test::parseError("geo meshes/bunny.obj\n");
    EXPECT_NE(elsewhere.find("test.scene:1: cannot open OBJ file"), std::string::npos) << elsewhere;
    EXPECT_EQ(elsewhere.find("fetch-scenes"), std::string::npos) << elsewhere;
}

}  // namespace
}  // namespace vkray
