// glTF 2.0 through `geo`: files written by the test (embedded base64, an external .bin, GLB), the
// node hierarchy's transforms, the three triangle modes, normals, the material mapping, the
// warnings for what is skipped, and one test per bad input, each a one-line vkray::Error.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "scene_test_util.h"
#include "support/gltf_writer.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;
using test::GltfWriter;

class GltfLoader : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(VKRAY_TEST_OUTPUT_DIR) / "gltf_loader" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    void write(const std::string& name, const std::string& bytes) {
        std::ofstream(dir_ / name, std::ios::binary) << bytes;
    }

    Scene load(const std::string& bytes, const std::string& prefix = "", const std::string& name = "m.gltf") {
        write(name, bytes);
        std::istringstream in(prefix + "geo " + name + "\n");
        ParseOptions options;
        options.warn = [this](const std::string& w) { warnings_.push_back(w); };
        return parseScene(in, "test.scene", dir_, options);
    }

    std::string error(const std::string& bytes, const std::string& name = "m.gltf") {
        try {
            load(bytes, "", name);
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
            return what;
        }
        return "(no error)";
    }

    std::string file(const std::string& name = "m.gltf") const { return (dir_ / name).lexically_normal().string(); }

    fs::path dir_;
    std::vector<std::string> warnings_;
};

// Four corners of the unit square in z = 0.
const std::vector<float> kSquare = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};

// One mesh of one indexed triangle list (the square as two triangles), drawn by one node.
struct SquareFile {
    GltfWriter w;
    int positions = w.vec3(kSquare);
    int indices = w.indices16({0, 1, 2, 0, 2, 3});

    std::string meshes(const std::string& primitiveExtra = "") const {
        return "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(positions) +
               "}, \"indices\": " + std::to_string(indices) + primitiveExtra + "}]}]";
    }
};

TEST_F(GltfLoader, EmbeddedExternalAndBinaryBuffersReadTheSame) {
    SquareFile f;
    const std::string rest = f.meshes() + ",\n\"nodes\": [{\"mesh\": 0}], \"scenes\": [{\"nodes\": [0]}], \"scene\": 0";
    write("m.bin", f.w.buffer());
    for (const auto& [name, bytes] : {std::pair<std::string, std::string>{"e.gltf", f.w.embedded(rest)},
                                      {"x.gltf", f.w.json(rest, "m.bin")},
                                      {"b.glb", f.w.glb(rest)}}) {
        SCOPED_TRACE(name);
        const Scene s = load(bytes, "", name);
        ASSERT_EQ(s.triangles.size(), 2u);
        EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
        EXPECT_EQ(s.triangles[1].p2, glm::vec3(0, 1, 0));
        EXPECT_FALSE(s.hasSmoothNormals());
    }
    EXPECT_TRUE(warnings_.empty()) << warnings_[0];
}

TEST_F(GltfLoader, NodeTransformsComposeUnderTheSceneTransform) {
    SquareFile f;
    // Node 0: matrix translating by (10, 0, 0) (column-major); its child 1: scale 2, then rotate 90
    // degrees about z, then translate (0, 0, 1), drawing the mesh. A second root, 2, draws it too.
    const std::string rest = f.meshes() +
                             ",\n\"nodes\": [{\"matrix\": [1,0,0,0, 0,1,0,0, 0,0,1,0, 10,0,0,1], \"children\": [1]},"
                             " {\"mesh\": 0, \"translation\": [0,0,1], \"rotation\": [0,0,0.70710678,0.70710678],"
                             " \"scale\": [2,2,2]}, {\"mesh\": 0}],"
                             " \"scenes\": [{\"nodes\": [0, 2]}]";
    const Scene s = test::inWorld(load(f.w.embedded(rest), "translate 0 5 0\n"));
    ASSERT_EQ(s.triangles.size(), 4u);
    // Corner (1, 0, 0): scaled (2, 0, 0), rotated (0, 2, 0), + (0, 0, 1), + (10, 0, 0), + (0, 5, 0).
    EXPECT_NEAR(s.triangles[0].p1.x, 10.0f, 1e-5f);
    EXPECT_NEAR(s.triangles[0].p1.y, 7.0f, 1e-5f);
    EXPECT_NEAR(s.triangles[0].p1.z, 1.0f, 1e-5f);
    EXPECT_EQ(s.triangles[2].p1, glm::vec3(1, 5, 0));  // node 2: the scene transform alone
    ASSERT_EQ(warnings_.size(), 1u);
    EXPECT_EQ(warnings_[0], "in '" + file() + "': 1 meshes drawn by several nodes are copied per node: 2 instances, "
                                              "4 triangles");
}

TEST_F(GltfLoader, StripsAndFansFollowTheSpecification) {
    GltfWriter w;
    const int p = w.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 0, 2, 0});
    const std::string rest = "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) +
                             "}, \"mode\": 5}, {\"attributes\": {\"POSITION\": " + std::to_string(p) +
                             "}, \"mode\": 6}]}], \"nodes\": [{\"mesh\": 0}]";
    const Scene s = load(w.embedded(rest));
    ASSERT_EQ(s.triangles.size(), 6u);
    const auto corners = [&](size_t t) {
        return std::vector<glm::vec3>{s.triangles[t].p0, s.triangles[t].p1, s.triangles[t].p2};
    };
    const glm::vec3 v[5] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}};
    // Strip: {v_i, v_(i+1+i%2), v_(i+2-i%2)}; fan: {v_(i+1), v_(i+2), v_0}.
    EXPECT_EQ(corners(0), (std::vector<glm::vec3>{v[0], v[1], v[2]}));
    EXPECT_EQ(corners(1), (std::vector<glm::vec3>{v[1], v[3], v[2]}));
    EXPECT_EQ(corners(2), (std::vector<glm::vec3>{v[2], v[3], v[4]}));
    EXPECT_EQ(corners(3), (std::vector<glm::vec3>{v[1], v[2], v[0]}));
    EXPECT_EQ(corners(5), (std::vector<glm::vec3>{v[3], v[4], v[0]}));
}

TEST_F(GltfLoader, NormalsMakeSmoothTriangles) {
    SquareFile f;
    const int n = f.w.vec3({0, 0, 2, 0, 0, 1, 0, 1, 1, 0, 0, 1});
    const std::string rest = f.meshes().replace(f.meshes().find("}, \"indices\""), 1,
                                                ", \"NORMAL\": " + std::to_string(n) + "}") +
                             ", \"nodes\": [{\"mesh\": 0}]";
    const Scene s = load(f.w.embedded(rest));
    ASSERT_TRUE(s.hasSmoothNormals());
    EXPECT_EQ(s.normals[0].n0, glm::vec3(0, 0, 1));
    EXPECT_NEAR(s.normals[0].n2.y, std::sqrt(0.5f), 1e-6f);
}

TEST_F(GltfLoader, MaterialsMapToTheWhittedModel) {
    GltfWriter w;
    const int p = w.vec3({0, 0, 0, 1, 0, 0, 0, 1, 0});
    std::string prims;
    for (int m = -1; m < 4; ++m)
        prims += std::string(prims.empty() ? "" : ", ") + "{\"attributes\": {\"POSITION\": " + std::to_string(p) + "}" +
                 (m >= 0 ? ", \"material\": " + std::to_string(m) : "") + "}";
    const std::string rest =
        "\"extensionsUsed\": [\"KHR_materials_transmission\", \"KHR_materials_ior\"],"
        " \"extensionsRequired\": [\"KHR_materials_transmission\"],"
        "\"materials\": [{\"pbrMetallicRoughness\": {\"baseColorFactor\": [0.5, 0.25, 1, 1], \"metallicFactor\": 0}},"
        " {\"pbrMetallicRoughness\": {\"baseColorFactor\": [1, 0.5, 0.25, 1], \"roughnessFactor\": 0}},"
        " {\"pbrMetallicRoughness\": {\"metallicFactor\": 0, \"roughnessFactor\": 0},"
        "  \"extensions\": {\"KHR_materials_transmission\": {\"transmissionFactor\": 1},"
        "  \"KHR_materials_ior\": {\"ior\": 1.33}}},"
        " {\"emissiveFactor\": [1, 0.5, 0], \"pbrMetallicRoughness\": {\"metallicFactor\": 0}}],"
        "\"meshes\": [{\"primitives\": [" + prims + "]}], \"nodes\": [{\"mesh\": 0}]";
    const Scene s = load(w.embedded(rest), "ambient 0.1 0.1 0.1\ndiffuse 0.3 0.3 0.3\n");
    ASSERT_EQ(s.triangles.size(), 5u);
    const auto material = [&](size_t t) { return s.materials.at(s.triangles[t].material); };
    EXPECT_EQ(material(0).diffuse, glm::vec3(0.3f));  // no material: the scene's state
    const Material matte = material(1);
    EXPECT_EQ(matte.diffuse, glm::vec3(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(matte.ambient, glm::vec3(0.1f));
    EXPECT_FALSE(matte.reflects());
    EXPECT_FALSE(matte.refracts());
    const Material mirror = material(2);  // metallic 1 by default, roughness 0: a tinted mirror
    EXPECT_EQ(mirror.reflect, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(mirror.diffuse, glm::vec3(0.0f));
    const Material glass = material(3);
    EXPECT_EQ(glass.transmit, glm::vec3(1.0f));
    EXPECT_FLOAT_EQ(glass.ior, 1.33f);
    EXPECT_EQ(glass.diffuse, glm::vec3(0.0f));
    EXPECT_EQ(material(4).emission, glm::vec3(1.0f, 0.5f, 0.0f));
}

TEST_F(GltfLoader, PointsLinesAndTexturesAreSkippedWithOneWarningEach) {
    SquareFile f;
    std::string prims;
    for (const int mode : {0, 1, 4, 3})
        prims += std::string(prims.empty() ? "" : ", ") + "{\"attributes\": {\"POSITION\": 0}, \"indices\": 1, " +
                 "\"mode\": " + std::to_string(mode) + "}";
    const std::string rest = "\"meshes\": [{\"primitives\": [" + prims + "]}], \"nodes\": [{\"mesh\": 0}],"
                             " \"textures\": [{\"source\": 0}], \"images\": [{\"uri\": \"albedo.png\"}],"
                             " \"materials\": [{\"pbrMetallicRoughness\": {\"baseColorTexture\": {\"index\": 0}}}]";
    const Scene s = load(f.w.embedded(rest));
    EXPECT_EQ(s.triangles.size(), 2u);  // the square, from the one primitive of triangles
    ASSERT_EQ(warnings_.size(), 2u);
    EXPECT_EQ(warnings_[0], "in '" + file() + "': 3 primitives of points or lines skipped (vkray draws triangles)");
    EXPECT_EQ(warnings_[1], "in '" + file() + "': 1 textures not sampled: the materials' factors alone colour the surfaces");
}

// --- Bad files -------------------------------------------------------------------------------

TEST_F(GltfLoader, RefusesAnAccessorPastItsBuffer) {
    SquareFile f;
    const int bad = f.w.rawAccessor("{\"bufferView\": 0, \"componentType\": 5126, \"count\": 5, \"type\": \"VEC3\"}");
    const std::string rest = "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(bad) +
                             "}}]}], \"nodes\": [{\"mesh\": 0}]";
    const std::string e = error(f.w.embedded(rest));
    EXPECT_NE(e.find(file() + ": accessor 2 (POSITION of mesh 0 primitive 0): its 5 elements from byte 0 reach past "
                              "its bufferView 0 of 48 bytes (glTF loaded at test.scene:1)"),
              std::string::npos)
        << e;
}

TEST_F(GltfLoader, RefusesAMissingBufferFile) {
    SquareFile f;
    const std::string e = error(f.w.json(f.meshes() + ", \"nodes\": [{\"mesh\": 0}]", "gone.bin"));
    EXPECT_NE(e.find(file() + ": cannot open buffer file '"), std::string::npos) << e;
    EXPECT_NE(e.find("gone.bin': no such file or directory"), std::string::npos) << e;
    // A URI that percent-decodes to a line feed: the name is escaped, the message one line (error()).
    const std::string lf = error(f.w.json(f.meshes() + ", \"nodes\": [{\"mesh\": 0}]", "a%0Ab.bin"));
    EXPECT_NE(lf.find("a\\nb.bin': no such file or directory"), std::string::npos) << lf;
}

TEST_F(GltfLoader, RefusesAnIndexOutOfRange) {
    GltfWriter w;
    const int p = w.vec3(kSquare);
    const int i = w.indices32({0, 1, 7});
    const std::string rest = "\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) +
                             "}, \"indices\": " + std::to_string(i) + "}]}], \"nodes\": [{\"mesh\": 0}]";
    EXPECT_NE(error(w.embedded(rest)).find(": mesh 0 primitive 0: index 2 of accessor 1 is 7, out of range: POSITION "
                                           "has 4 vertices"),
              std::string::npos)
        << error(w.embedded(rest));
    SquareFile f;
    EXPECT_NE(error(f.w.embedded(f.meshes() + ", \"nodes\": [{\"mesh\": 3}]"))
                  .find(": mesh index 3 is out of range: the file has 1 meshes"),
              std::string::npos);
    EXPECT_NE(error(f.w.embedded(f.meshes(", \"material\": 2") + ", \"nodes\": [{\"mesh\": 0}]"))
                  .find(": material index 2 is out of range: the file has 0 materials"),
              std::string::npos);
}

TEST_F(GltfLoader, RefusesWrongJsonTypesAndBadJson) {
    SquareFile f;
    const std::string e = error(f.w.embedded(f.meshes() + ", \"nodes\": [{\"mesh\": \"zero\"}]"));
    EXPECT_NE(e.find(file() + ": nodes[0].mesh is a string, expected a non-negative integer below 2^31"),
              std::string::npos)
        << e;
    const std::string count = error(f.w.embedded(f.meshes().replace(f.meshes().find("\"indices\": 1"), 12,
                                                                    "\"indices\": 1.5")));
    EXPECT_NE(count.find(": meshes[0].primitives[0].indices is the number 1.5, expected a non-negative integer"),
              std::string::npos)
        << count;
    const std::string notArray = error(f.w.embedded(f.meshes() + ", \"accessors\": 7"));
    EXPECT_NE(notArray.find(": accessors is the integer 7, expected an array"), std::string::npos) << notArray;
    const std::string syntax = error("{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
    EXPECT_NE(syntax.find(file() + ": tinygltf: "), std::string::npos) << syntax;
    const std::string v1 = error("{\"asset\": {\"version\": \"1.0\"}, \"scene\": \"defaultScene\"}");
    EXPECT_NE(v1.find(file() + ": glTF version '1.0': vkray reads glTF 2.0"), std::string::npos) << v1;
    const std::string glb = error(std::string("glTF\2\0\0\0\x40\0\0\0", 12), "m.glb");
    EXPECT_NE(glb.find(file("m.glb") + ": tinygltf: "), std::string::npos) << glb;
}

TEST_F(GltfLoader, RefusesRequiredExtensionsItDoesNotRead) {
    SquareFile f;
    // As in a Draco-compressed file: an accessor without a buffer view, which tinygltf refuses.
    f.w.rawAccessor("{\"componentType\": 5126, \"count\": 3, \"type\": \"VEC3\"}");
    const std::string e = error(f.w.embedded(f.meshes() + ", \"nodes\": [{\"mesh\": 0}],"
                                                          " \"extensionsRequired\": [\"KHR_draco_mesh_compression\"]"));
    EXPECT_NE(e.find(file() + ": the file requires the extension 'KHR_draco_mesh_compression', which vkray does not "
                              "read (it reads KHR_materials_transmission, KHR_materials_ior, "
                              "KHR_materials_emissive_strength)"),
              std::string::npos)
        << e;
}

TEST_F(GltfLoader, RefusesANodeGraphThatIsNotAForest) {
    SquareFile f;
    const std::string cycle = error(f.w.embedded(f.meshes() + ", \"nodes\": [{\"children\": [1]}, {\"children\": [0]}],"
                                                              " \"scenes\": [{\"nodes\": [0]}]"));
    EXPECT_NE(cycle.find(": node 0 is reached twice (a cycle, or a node with two parents)"), std::string::npos) << cycle;
    const std::string range = error(f.w.embedded(f.meshes() + ", \"nodes\": [{\"children\": [4]}],"
                                                              " \"scenes\": [{\"nodes\": [0]}]"));
    EXPECT_NE(range.find(": node index 4 is out of range: the file has 1 nodes"), std::string::npos) << range;
}

}  // namespace
}  // namespace vkray
