// Happy paths of the .scene parser: every command, transform order with numbers, material state.
#include <cmath>

#include "scene/scene_builder.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

using test::parseText;

TEST(SceneParser, EmptySceneHasTheDocumentedDefaults) {
    const Scene s = parseText("# nothing but a comment\n\n   \t\n");
    EXPECT_EQ(s.width, 640);
    EXPECT_EQ(s.height, 480);
    EXPECT_EQ(s.maxDepth, 5);
    EXPECT_FALSE(s.hasCamera);
    EXPECT_EQ(s.attenuation, glm::vec3(1.0f, 0.0f, 0.0f));
    EXPECT_EQ(s.background, glm::vec3(0.0f));
    EXPECT_TRUE(s.triangles.empty());
    EXPECT_TRUE(s.materials.empty());
    EXPECT_TRUE(s.lights.empty());
    EXPECT_TRUE(s.output.empty());
    EXPECT_FALSE(s.hasSmoothNormals());
}

TEST(SceneParser, SettingsCameraAndLights) {
    const Scene s = parseText(
        "size 320 200\n"
        "output picture.png\n"
        "maxdepth 3\n"
        "camera 0 1 5  0 0 0  0 1 0  30\n"
        "point 1 2 3 0.5 0.25 1\n"
        "directional 0 -1 0 0.2 0.2 0.2\n"
        "attenuation 0.5 0.1 0.02\n"
        "background 0.1 0.2 0.4\n"
        "maxverts 10\n"
        "maxvertnorms 4\n");
    EXPECT_EQ(s.width, 320);
    EXPECT_EQ(s.height, 200);
    EXPECT_EQ(s.output, "picture.png");
    EXPECT_EQ(s.maxDepth, 3);
    ASSERT_TRUE(s.hasCamera);
    EXPECT_EQ(s.camera.eye, glm::vec3(0, 1, 5));
    EXPECT_EQ(s.camera.center, glm::vec3(0, 0, 0));
    EXPECT_EQ(s.camera.up, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.camera.fovyDegrees, 30.0f);
    ASSERT_EQ(s.lights.size(), 2u);
    EXPECT_EQ(s.lights[0].type, Light::Type::Point);
    EXPECT_EQ(s.lights[0].vector, glm::vec3(1, 2, 3));
    EXPECT_EQ(s.lights[0].color, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(s.lights[1].type, Light::Type::Directional);
    EXPECT_EQ(s.lights[1].vector, glm::vec3(0, -1, 0));
    EXPECT_EQ(s.attenuation, glm::vec3(0.5f, 0.1f, 0.02f));
    EXPECT_EQ(s.background, glm::vec3(0.1f, 0.2f, 0.4f));
}

TEST(SceneParser, LightsIgnoreTheCurrentTransform) {
    const Scene s = parseText("translate 10 0 0\npoint 1 2 3 1 1 1\n");
    EXPECT_EQ(s.lights.at(0).vector, glm::vec3(1, 2, 3));
}

TEST(SceneParser, TolerantSyntax) {
    // UTF-8 BOM, CRLF, tabs, trailing comments, '+' signs, exponents, UTF-8 in a comment.
    const Scene s = parseText(
        "\xEF\xBB\xBFvertex\t+1 2e0 .5   # caf\xC3\xA9\r\n"
        "vertex -1 0 0\r\n"
        "  vertex 0 1.0E+0 0\r\n"
        "tri 0 1 2 # a comment right after\r\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p0, glm::vec3(1.0f, 2.0f, 0.5f));
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(0.0f, 1.0f, 0.0f));
}

TEST(SceneParser, TrianglesInLoadOrderWithWorldPositions) {
    const Scene s = parseText(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
        "tri 0 1 2\ntri 3 2 1\n");
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.triangles[1].p0, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.triangles[1].p2, glm::vec3(1, 0, 0));
    EXPECT_FALSE(s.hasSmoothNormals());
}

TEST(SceneParser, TransformsRightMultiplyInOpenGLOrder) {
    // translate then scale: p' = T(S p) = (2*1 + 1, 0, 0) = (3, 0, 0); the other order would give 4.
    const Scene s = parseText(
        "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
        "translate 1 0 0\nscale 2 2 2\ntri 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_VEC3_NEAR(s.triangles[0].p0, glm::vec3(3, 0, 0), 1e-6f);
    EXPECT_VEC3_NEAR(s.triangles[0].p1, glm::vec3(1, 2, 0), 1e-6f);
    EXPECT_VEC3_NEAR(s.triangles[0].p2, glm::vec3(1, 0, 2), 1e-6f);
}

TEST(SceneParser, RotateIsCounterClockwiseDegreesAboutTheAxis) {
    // 90 degrees about +z maps x to y; then translate applied before rotate: R(T p).
    const Scene s = test::inWorld(parseText(
        "vertex 1 0 0\nvertex 0 1 0\nvertex 0 0 1\n"
        "rotate 0 0 2 90\ntranslate 1 0 0\ntri 0 1 2\n"));
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_VEC3_NEAR(s.triangles[0].p0, glm::vec3(0, 2, 0), 1e-6f);   // R(2,0,0)
    EXPECT_VEC3_NEAR(s.triangles[0].p1, glm::vec3(-1, 1, 0), 1e-6f);  // R(1,1,0)
    EXPECT_VEC3_NEAR(s.triangles[0].p2, glm::vec3(0, 1, 1), 1e-6f);   // R(1,0,1)
}

TEST(SceneParser, PushAndPopRestoreTheTransform) {
    const Scene s = parseText(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "translate 0 0 1\n"
        "pushTransform\n  translate 5 0 0\n  pushTransform\n    scale 3 3 3\n    tri 0 1 2\n"
        "  popTransform\n  tri 0 1 2\npopTransform\ntri 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 3u);
    EXPECT_VEC3_NEAR(s.triangles[0].p1, glm::vec3(8, 0, 1), 1e-6f);
    EXPECT_VEC3_NEAR(s.triangles[1].p1, glm::vec3(6, 0, 1), 1e-6f);
    EXPECT_VEC3_NEAR(s.triangles[2].p1, glm::vec3(1, 0, 1), 1e-6f);
}

TEST(SceneParser, VerticesTakeTheTransformOfTheTriLine) {
    const Scene s = test::inWorld(parseText("vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntranslate 0 0 -2\ntri 0 1 2\n"));
    EXPECT_VEC3_NEAR(s.triangles.at(0).p0, glm::vec3(0, 0, -2), 0.0f);
}

TEST(SceneParser, MaterialStateAtCreationTime) {
    const Scene s = parseText(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "tri 0 1 2\n"
        "ambient 0.1 0.2 0.3\ndiffuse 0.4 0.5 0.6\nspecular 0.7 0.8 0.9\n"
        "emission 0.01 0.02 0.03\nshininess 20\nrefract 1.5 0.9 0.8 0.7\n"
        "tri 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 2u);
    ASSERT_EQ(s.materials.size(), 2u);
    const Material& first = s.materials[s.triangles[0].material];
    EXPECT_EQ(first, Material{});  // every default of scene.h: ambient 0.2, shininess 1, ior 1
    const Material& m = s.materials[s.triangles[1].material];
    EXPECT_EQ(m.ambient, glm::vec3(0.1f, 0.2f, 0.3f));
    EXPECT_EQ(m.diffuse, glm::vec3(0.4f, 0.5f, 0.6f));
    EXPECT_EQ(m.specular, glm::vec3(0.7f, 0.8f, 0.9f));
    EXPECT_EQ(m.emission, glm::vec3(0.01f, 0.02f, 0.03f));
    EXPECT_EQ(m.shininess, 20.0f);
    EXPECT_EQ(m.ior, 1.5f);
    EXPECT_EQ(m.transmit, glm::vec3(0.9f, 0.8f, 0.7f));
    EXPECT_EQ(m.reflect, m.specular);  // reflect never given: follows specular
}

TEST(SceneParser, ReflectFollowsSpecularUntilSetExplicitly) {
    const Scene s = parseText(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "specular 0.5 0.5 0.5\ntri 0 1 2\n"
        "specular 0.25 0 0\ntri 0 1 2\n"
        "reflect 0 0 1\ntri 0 1 2\n"
        "specular 1 1 1\ntri 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 4u);
    EXPECT_EQ(s.materials[s.triangles[0].material].reflect, glm::vec3(0.5f));
    EXPECT_EQ(s.materials[s.triangles[1].material].reflect, glm::vec3(0.25f, 0, 0));
    EXPECT_EQ(s.materials[s.triangles[2].material].reflect, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.materials[s.triangles[3].material].reflect, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.materials[s.triangles[3].material].specular, glm::vec3(1.0f));
}

TEST(SceneParser, EqualMaterialsShareOneIndex) {
    const Scene s = parseText(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "diffuse 1 0 0\ntri 0 1 2\n"
        "diffuse 0 1 0\ntri 0 1 2\n"
        "diffuse 1 0 0\ntri 0 1 2\n"
        "ambient 0.2 0.2 0.2\ntri 0 1 2\n"  // the default value again: still the same material
        "diffuse 0 0 0\ndiffuse 0 1 0\ntri 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 5u);
    EXPECT_EQ(s.materials.size(), 2u);
    EXPECT_EQ(s.triangles[0].material, s.triangles[2].material);
    EXPECT_EQ(s.triangles[0].material, s.triangles[3].material);
    EXPECT_EQ(s.triangles[1].material, s.triangles[4].material);
    EXPECT_NE(s.triangles[0].material, s.triangles[1].material);
}

TEST(SceneParser, MaterialsWithoutPrimitivesAreNotStored) {
    const Scene s = parseText("diffuse 1 0 0\ndiffuse 0 1 0\n");
    EXPECT_TRUE(s.materials.empty());
}

TEST(SceneParser, SmoothNormalsBackfillGeometricNormals) {
    const Scene s = parseText(
        "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
        "vertexnormal 0 0 0 1 0 0\nvertexnormal 1 0 0 0 1 0\nvertexnormal 0 1 0 0 0 1\n"
        "tri 0 1 2\ntri 0 2 1\n"
        "trinormal 0 1 2\n"
        "tri 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 4u);
    ASSERT_EQ(s.normals.size(), 4u);
    EXPECT_EQ(s.normals[0].n0, glm::vec3(0, 0, 1));  // backfilled: geometric, 3 times
    EXPECT_EQ(s.normals[0].n2, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.normals[1].n1, glm::vec3(0, 0, -1));  // reversed winding
    EXPECT_EQ(s.normals[2].n0, glm::vec3(1, 0, 0));   // given per vertex
    EXPECT_EQ(s.normals[2].n1, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.normals[2].n2, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.normals[3].n1, glm::vec3(0, 0, 1));  // flat after smooth: geometric
    EXPECT_EQ(s.triangles[2].p1, glm::vec3(1, 0, 0));
}

TEST(SceneParser, NormalsUseTheInverseTransposeAndAreRenormalized) {
    // Under scale 2 1 1 a surface normal (1, 1, 0) becomes (1/2, 1, 0), renormalized.
    const Scene s = parseText(
        "vertexnormal 0 0 0 1 1 0\nvertexnormal 1 0 0 1 1 0\nvertexnormal 0 0 1 0 0 5\n"
        "scale 2 1 1\ntrinormal 0 1 2\n");
    ASSERT_EQ(s.normals.size(), 1u);
    const glm::vec3 expected = glm::normalize(glm::vec3(0.5f, 1.0f, 0.0f));
    EXPECT_VEC3_NEAR(s.normals[0].n0, expected, 1e-6f);
    EXPECT_VEC3_NEAR(s.normals[0].n2, glm::vec3(0, 0, 1), 1e-6f);
    EXPECT_VEC3_NEAR(s.triangles[0].p1, glm::vec3(2, 0, 0), 0.0f);
}

TEST(SceneParser, GeometricNormalOfADegenerateTriangleStaysFinite) {
    EXPECT_EQ(geometricNormal(glm::vec3(1), glm::vec3(1), glm::vec3(1)), glm::vec3(0, 0, 1));
    EXPECT_EQ(geometricNormal(glm::vec3(0), glm::vec3(0, 2, 0), glm::vec3(0, 0, 3)), glm::vec3(1, 0, 0));
}

TEST(SceneParser, SphereIsTessellatedWithTheDefaultResolution) {
    const Scene s = parseText("sphere 0 0 0 1\n");
    EXPECT_EQ(s.triangles.size(), 960u);  // 16 stacks x 32 slices
    EXPECT_TRUE(s.hasSmoothNormals());
    EXPECT_EQ(s.normals.size(), s.triangles.size());
}

TEST(SceneParser, SphereStepsSetTheResolution) {
    const Scene s = parseText("spheresteps 3\nsphere 0 0 0 1\nspheresteps 12\nsphere 0 0 0 1\n");
    EXPECT_EQ(s.triangles.size(), 24u + 528u);
}

TEST(SceneParser, SphereUnderTransformIsAnEllipsoidWithAnalyticNormals) {
    const Scene s = parseText("translate 1 2 3\nscale 2 1 1\nspheresteps 8\nsphere 0 0 0 1\n");
    ASSERT_EQ(s.triangles.size(), 224u);
    for (size_t i = 0; i < s.triangles.size(); ++i) {
        const glm::vec3 p[3] = {s.triangles[i].p0, s.triangles[i].p1, s.triangles[i].p2};
        const glm::vec3 n[3] = {s.normals[i].n0, s.normals[i].n1, s.normals[i].n2};
        for (int k = 0; k < 3; ++k) {
            const glm::vec3 q = p[k] - glm::vec3(1, 2, 3);  // on x^2/4 + y^2 + z^2 = 1
            EXPECT_NEAR(q.x * q.x / 4 + q.y * q.y + q.z * q.z, 1.0f, 1e-5f);
            // The gradient of that implicit surface is the normal.
            EXPECT_VEC3_NEAR(n[k], glm::normalize(glm::vec3(q.x / 4, q.y, q.z)), 1e-5f);
        }
    }
}

TEST(SceneParser, OutputAndGeoTakeOneFileNameToken) {
    const Scene s = parseText("output out-1.png\ngeo sub/part.obj\n");
    EXPECT_EQ(s.output, "out-1.png");
    EXPECT_EQ(s.triangles.size(), 1u);
}

TEST(SceneParser, LoadSceneResolvesGeoAgainstTheSceneFile) {
    const std::filesystem::path file = test::sceneDataDir() / "relative.scene";
    const Scene s = loadScene(file);
    EXPECT_EQ(s.sourceFile, file);
    EXPECT_TRUE(s.hasCamera);
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.materials.at(s.triangles[0].material).diffuse, glm::vec3(1, 0, 0));
}

}  // namespace
}  // namespace vkray
