// OBJ + MTL through `geo`: triangle order, the MTL mapping of docs/scene-format.md, normals, paths, errors.
#include <fstream>

#include <gtest/gtest.h>

#include "scene_test_util.h"

namespace vkray {
namespace {

using test::parseError;
using test::parseText;

const char* kSceneWithMaterials =
    "diffuse 0.1 0.2 0.3\n"
    "specular 0.4 0.4 0.4\n"
    "translate 0 0 -5\n"
    "geo materials.obj\n";

TEST(ObjLoader, FacesInFileOrderUnderTheCurrentTransform) {
    const Scene s = test::inWorld(parseText(kSceneWithMaterials));
    // 1 + 1 + 1 + 2 (quad) + 3 (pentagon) + 1 + 1
    ASSERT_EQ(s.triangles.size(), 10u);
    EXPECT_EQ(s.triangles[0].p0, glm::vec3(0, 0, -5));
    EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, -5));
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(0, 1, -5));
    EXPECT_EQ(s.triangles[8].p0, glm::vec3(0, 0, -5));  // relative indices -5 -4 -3 = 1 2 3
    EXPECT_EQ(s.triangles[8].p2, glm::vec3(0, 1, -5));
    // The triangulated pentagon keeps to its own vertices: 1 2 4 5 3.
    for (size_t i = 5; i < 8; ++i)
        for (const glm::vec3& p : {s.triangles[i].p0, s.triangles[i].p1, s.triangles[i].p2})
            EXPECT_TRUE(p.z == -5.0f && p.y >= 0.0f && p.y <= 1.5f);
}

TEST(ObjLoader, FacesWithoutMaterialGetTheSceneMaterialState) {
    const Scene s = parseText(kSceneWithMaterials);
    const Material& m = s.materials.at(s.triangles.at(0).material);
    EXPECT_EQ(m.diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.specular, glm::vec3(0.4f));
    EXPECT_EQ(m.reflect, glm::vec3(0.4f));  // the scene's CSE167 default, not the OBJ rule
    EXPECT_EQ(m.ambient, glm::vec3(0.2f));
}

TEST(ObjLoader, MtlMappingOfDesignMd) {
    const Scene s = parseText(kSceneWithMaterials);
    const auto material = [&](size_t tri) { return s.materials.at(s.triangles.at(tri).material); };

    const Material matte = material(1);
    EXPECT_EQ(matte.ambient, glm::vec3(0.1f));
    EXPECT_EQ(matte.diffuse, glm::vec3(0.8f, 0.2f, 0.2f));
    EXPECT_EQ(matte.specular, glm::vec3(0.3f));
    EXPECT_EQ(matte.shininess, 32.0f);
    EXPECT_EQ(matte.reflect, glm::vec3(0.0f));  // illum 2: Ks is a highlight, not a mirror
    EXPECT_EQ(matte.transmit, glm::vec3(0.0f));

    const Material mirror = material(2);  // illum 3: reflect = Ks
    EXPECT_EQ(mirror.reflect, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(mirror.shininess, 200.0f);

    const Material glass = material(3);  // illum 4 with d 1: clear glass with Ni
    EXPECT_EQ(material(4), glass);
    EXPECT_EQ(glass.transmit, glm::vec3(1.0f));
    EXPECT_EQ(glass.ior, 1.5f);
    EXPECT_EQ(glass.reflect, glm::vec3(0.0f));
    EXPECT_EQ(glass.specular, glm::vec3(0.5f));

    const Material smoke = material(5);  // d 0.25: transmit 1 - d
    EXPECT_EQ(smoke.transmit, glm::vec3(0.75f));
    EXPECT_EQ(smoke.ior, 1.0f);

    const Material tinted = material(8);  // d 0.5, Tf: (1 - d) * Tf
    EXPECT_EQ(tinted.transmit, glm::vec3(0.5f, 0.25f, 0.125f));
    EXPECT_FLOAT_EQ(tinted.ior, 1.33f);

    const Material lamp = material(9);
    EXPECT_EQ(lamp.emission, glm::vec3(1.0f, 0.9f, 0.8f));
    EXPECT_EQ(lamp.diffuse, glm::vec3(0.0f));

    // Default + 6 used MTL materials (the quad's two triangles share one); 'unused' is left out.
    EXPECT_EQ(s.materials.size(), 7u);
}

TEST(ObjLoader, VertexNormalsMakeSmoothTrianglesOnlyWhenAllThreeArePresent) {
    const Scene s = parseText("rotate 0 1 0 90\ngeo materials.obj\n");
    ASSERT_EQ(s.normals.size(), 10u);
    // Face 2 has vn (0 0 -1) at every corner; rotated 90 degrees about y it points to -x.
    EXPECT_VEC3_NEAR(s.normals[2].n0, glm::vec3(-1, 0, 0), 1e-6f);
    EXPECT_VEC3_NEAR(s.normals[2].n2, glm::vec3(-1, 0, 0), 1e-6f);
    // Face 0 (earlier, flat) was backfilled with its geometric normal (0 0 1) -> +x.
    EXPECT_VEC3_NEAR(s.normals[0].n1, glm::vec3(1, 0, 0), 1e-6f);
    // Face 9 has normals on two corners only: flat.
    EXPECT_VEC3_NEAR(s.normals[9].n0, glm::vec3(1, 0, 0), 1e-6f);
}

TEST(ObjLoader, PathsAreRelativeToTheSceneAndTheMtlToTheObj) {
    const Scene s = parseText("obj sub/part.obj\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.materials.at(s.triangles[0].material).diffuse, glm::vec3(1, 0, 0));
}

TEST(ObjLoader, FacesMayReferToVerticesDefinedLater) {
    EXPECT_EQ(parseText("geo forward_ref.obj\n").triangles.size(), 1u);
}

TEST(ObjLoader, Utf8BomAndCrlfAreAccepted) {
    // Without stripping the BOM, tinyobjloader would skip the first vertex and reject "f 1 2 3".
    const Scene s = parseText("geo bom_crlf.obj\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p0, glm::vec3(0, 0, 0));
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(0, 1, 0));
}

TEST(ObjLoader, BinaryDataIsRejectedWithItsLine) {
    const std::filesystem::path file = std::filesystem::path(VKRAY_TEST_OUTPUT_DIR) / "binary.obj";
    std::ofstream(file, std::ios::binary) << std::string("v 0 0 0\nv 1\0 0 0\n", 16);
    const std::string message = parseError("geo " + file.string() + "\n");
    EXPECT_TRUE(message.starts_with(file.string() + ":2:4: binary data (NUL byte)")) << message;
}

TEST(ObjLoader, AnObjWithoutFacesAddsNothing) {
    const Scene s = parseText("geo no_faces.obj\n");
    EXPECT_TRUE(s.triangles.empty());
    EXPECT_TRUE(s.materials.empty());
}

// Errors: each names the file and line where the problem is, and the cause.
struct ObjErrorCase {
    const char* scene;
    const char* location;  // prefix of the message
    const char* cause;     // substring of the message
};

void PrintTo(const ObjErrorCase& c, std::ostream* os) { *os << testing::PrintToString(std::string(c.scene)); }

class ObjErrors : public testing::TestWithParam<ObjErrorCase> {};

TEST_P(ObjErrors, NameFileLineAndCause) {
    const ObjErrorCase& c = GetParam();
    const std::string message = parseError(c.scene);
    const std::string data = test::sceneDataDir().string() + "/";
    const std::string location =
        std::string(c.location).starts_with("test.scene") ? std::string(c.location) : data + c.location;
    EXPECT_TRUE(message.starts_with(location)) << message << "\nexpected location: " << location;
    EXPECT_NE(message.find(c.cause), std::string::npos) << message << "\nexpected cause: " << c.cause;
}

INSTANTIATE_TEST_SUITE_P(
    Table, ObjErrors,
    testing::Values(
        ObjErrorCase{"\ngeo nothere.obj\n", "test.scene:2: ", "cannot open OBJ file"},
        ObjErrorCase{"geo sub\n", "test.scene:1: ", "unsupported mesh format '(no extension)'"},
        ObjErrorCase{"geo model.stl\n", "test.scene:1: ", "unsupported mesh format '.stl' (supported: .obj, .off, .ply, .gltf, .glb)"},
        ObjErrorCase{"geo relative.scene\n", "test.scene:1: ", "unsupported mesh format '.scene'"},
        ObjErrorCase{"geo missing_mtl.obj\n", "test.scene:1: ", "cannot open material library"},
        ObjErrorCase{"geo missing_mtl.obj\n", "test.scene:1: ", "nothere.mtl"},
        ObjErrorCase{"geo nan_vertex.obj\n",
                     "nan_vertex.obj:2:5: ", "value 2 of 'v' is 'nan', not a finite number"},
        ObjErrorCase{"geo nan_vertex.obj\n", "nan_vertex.obj:2:5: ", "(OBJ loaded at test.scene:1)"},
        ObjErrorCase{"geo huge_vertex.obj\n", "huge_vertex.obj:3:5: ", "'1e999' is out of range"},
        ObjErrorCase{"geo bad_index.obj\n",
                     "bad_index.obj:5:7: ", "vertex index 4 out of range: the file defines 3 vertices"},
        ObjErrorCase{"geo bad_relative_index.obj\n",
                     "bad_relative_index.obj:3:9: ", "relative vertex index -3 reaches before the first"},
        ObjErrorCase{"geo zero_index.obj\n", "zero_index.obj:4:3: ", "OBJ indices start at 1"},
        ObjErrorCase{"geo bad_shininess.obj\n", "test.scene:1: ", "material 'shiny'"},
        ObjErrorCase{"geo bad_shininess.obj\n", "test.scene:1: ", "Ns -5 is negative"},
        ObjErrorCase{"geo nan_mtl.obj\n", "nan_mtl.mtl:2:8: ", "value 2 of 'Kd' is 'nan'"},
        ObjErrorCase{"geo unknown_material.obj\n", "test.scene:1: ", "nosuch"}));

}  // namespace
}  // namespace vkray
