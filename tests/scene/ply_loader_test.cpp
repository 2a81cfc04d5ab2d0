// PLY meshes through `geo`: the three encodings read the same triangles, fan triangulation in file
// order, normals, vertex and face colours, properties and elements read past; and one test per bad
// input, each a vkray::Error naming the file, where in it, and the cause.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "scene/scene_builder.h"
#include "scene_test_util.h"
#include "support/ply_writer.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;
using test::PlyEncoding;
using test::PlyMesh;

class PlyLoader : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(VKRAY_TEST_OUTPUT_DIR) / "ply_loader" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    Scene load(const std::string& ply, const std::string& prefix = "") {
        std::ofstream(dir_ / "m.ply", std::ios::binary) << ply;
        std::istringstream in(prefix + "geo m.ply\n");
        ParseOptions options;
        options.warn = [this](const std::string& w) { warnings_.push_back(w); };
        return parseScene(in, "test.scene", dir_, options);
    }

    std::string error(const std::string& ply) {
        try {
            load(ply);
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error)";
    }

    std::string file() const { return (dir_ / "m.ply").lexically_normal().string(); }

    fs::path dir_;
    std::vector<std::string> warnings_;
};

// A unit quad in z = 0 and a triangle above it.
PlyMesh quadAndTriangle() {
    PlyMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}};
    m.faces = {{0, 1, 2, 3}, {4, 1, 0}};
    return m;
}

const char* kHeaderStart = "ply\nformat ascii 1.0\n";

TEST_F(PlyLoader, EveryEncodingFansPolygonsInFileOrder) {
    for (const PlyEncoding e : {PlyEncoding::Ascii, PlyEncoding::LittleEndian, PlyEncoding::BigEndian}) {
        SCOPED_TRACE(int(e));
        const Scene s = load(test::writePly(quadAndTriangle(), e));
        ASSERT_EQ(s.triangles.size(), 3u);
        // Quad 0 1 2 3 -> (0 1 2), (0 2 3); then the triangle 4 1 0.
        EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
        EXPECT_EQ(s.triangles[0].p2, glm::vec3(1, 1, 0));
        EXPECT_EQ(s.triangles[1].p0, glm::vec3(0, 0, 0));
        EXPECT_EQ(s.triangles[1].p1, glm::vec3(1, 1, 0));
        EXPECT_EQ(s.triangles[1].p2, glm::vec3(0, 1, 0));
        EXPECT_EQ(s.triangles[2].p0, glm::vec3(0, 0, 1));
        EXPECT_EQ(s.triangles[2].p2, glm::vec3(0, 0, 0));
        EXPECT_FALSE(s.hasSmoothNormals());
    }
}

TEST_F(PlyLoader, UsesTheCurrentTransformAndMaterial) {
    const Scene s = test::inWorld(load(test::writePly(quadAndTriangle(), PlyEncoding::LittleEndian),
                                       "diffuse 0.1 0.2 0.3\ntranslate 0 0 -5\nscale 2 2 2\n"));
    ASSERT_EQ(s.triangles.size(), 3u);
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(2, 2, -5));
    ASSERT_EQ(s.materials.size(), 1u);
    EXPECT_EQ(s.materials[0].diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
}

TEST_F(PlyLoader, NormalsMakeSmoothTriangles) {
    PlyMesh m = quadAndTriangle();
    m.normals = {{0, 0, 2}, {0, 0, 1}, {0, 1, 1}, {0, 0, 1}, {0, 0, 0}};  // scaled, tilted, and a zero one
    const Scene s = load(test::writePly(m, PlyEncoding::BigEndian));
    ASSERT_TRUE(s.hasSmoothNormals());
    EXPECT_EQ(s.normals[0].n0, glm::vec3(0, 0, 1));  // unit length
    EXPECT_NEAR(s.normals[0].n2.y, std::sqrt(0.5f), 1e-6f);
    // The triangle with the zero normal is flat: its geometric normal three times.
    EXPECT_EQ(s.normals[2].n0, s.normals[2].n1);
    EXPECT_EQ(s.normals[2].n0, geometricNormal(s.triangles[2].p0, s.triangles[2].p1, s.triangles[2].p2));
}

TEST_F(PlyLoader, VertexColoursAreTheDiffuseOfTheFacesTheyStart) {
    PlyMesh m = quadAndTriangle();
    m.colours = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {0, 0, 0}, {51, 102, 255}};
    const Scene s = load(test::writePly(m, PlyEncoding::Ascii), "ambient 0.3 0.3 0.3\nspecular 0.5 0.5 0.5\n");
    ASSERT_EQ(s.triangles.size(), 3u);
    const Material& quad = s.materials.at(s.triangles[0].material);
    EXPECT_EQ(quad.diffuse, glm::vec3(1, 0, 0));          // the quad's first corner, vertex 0
    EXPECT_EQ(quad.ambient, glm::vec3(0.3f));              // the rest from the scene's state
    EXPECT_EQ(quad.specular, glm::vec3(0.5f));
    EXPECT_EQ(s.triangles[1].material, s.triangles[0].material);
    EXPECT_EQ(s.materials.at(s.triangles[2].material).diffuse, glm::vec3(0.2f, 0.4f, 1.0f));  // vertex 4
    EXPECT_EQ(s.materials.size(), 2u);
}

TEST_F(PlyLoader, FaceColoursWinAndOtherPropertiesAndElementsAreReadPast) {
    std::string ply = "ply\nformat binary_little_endian 1.0\nobj_info from a scanner\n"
                      "element vertex 3\nproperty double x\nproperty float confidence\nproperty double y\n"
                      "property list ushort float texcoord\nproperty double z\nproperty uchar red\n"
                      "property uchar green\nproperty uchar blue\n"
                      "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
                      "element face 1\nproperty list uint uint16 vertex_index\nproperty float red\n"
                      "property float green\nproperty float blue\nproperty list char double flags\n"
                      "element material 0\nproperty float nothing\nend_header\n";
    const auto le = [&](auto v) { test::appendPlyValue(ply, v, PlyEncoding::LittleEndian); };
    const double xyz[3][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    for (const auto& p : xyz) {
        le(p[0]), le(0.5f), le(p[1]), le(uint16_t(2)), le(0.25f), le(0.75f), le(p[2]);
        le(uint8_t(9)), le(uint8_t(9)), le(uint8_t(9));
    }
    le(int32_t(0)), le(int32_t(1));                                     // the edge
    le(uint32_t(3)), le(uint16_t(0)), le(uint16_t(1)), le(uint16_t(2));  // the face
    le(0.5f), le(0.25f), le(1.0f), le(int8_t(1)), le(7.0);
    const Scene s = load(ply);
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.materials.at(s.triangles[0].material).diffuse, glm::vec3(0.5f, 0.25f, 1.0f));
}

TEST_F(PlyLoader, CrlfHeaderAndAsciiValuesAnywhereOnTheirLines) {
    const Scene s = load("ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n"
                         "property float z\r\nelement face 1\r\nproperty list uchar int vertex_indices\r\n"
                         "end_header\r\n0 0 0 1 0 0\r\n0 1 0\r\n3 0 1 2");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(0, 1, 0));
}

// --- Bad files: one line, naming the file, the place and the cause ---------------------------

// A truncated body whose elements have a fixed size is refused by the counts' check (below).
TEST_F(PlyLoader, RefusesATruncatedBinaryFileAtItsByteOffset) {
    std::string ply = test::writePly(quadAndTriangle(), PlyEncoding::LittleEndian);
    ply.resize(ply.size() - 3);  // the last index loses 3 of its 4 bytes
    const std::string e = error(ply);
    // The last face's length (1 byte) and three indices (12 bytes) started 10 bytes before the end.
    const size_t lastFaceAt = ply.size() - 10;
    EXPECT_NE(e.find(file() + ": byte " + std::to_string(lastFaceAt) + ": element 'face' 1 of 2, property "
                              "'vertex_indices': a list of 3 items does not fit in the 9 bytes left in the file"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("(PLY loaded at test.scene:1)"), std::string::npos) << e;
}

// Found by the fuzzer (tests/fuzz/regressions/ply): the header's check counts each element at its
// least size, but the face's list takes 13 bytes, not 1, so the elements read past after it no longer
// fit; skipping them must not move past the end of the file (and read there).
TEST_F(PlyLoader, RefusesElementsReadPastThatALongerListLeftNoRoomFor) {
    std::ifstream in(fs::path(VKRAY_SOURCE_DIR) / "tests/fuzz/regressions/ply/list-then-skipped-elements.ply",
                     std::ios::binary);
    const std::string ply((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string e = error(ply);
    EXPECT_NE(e.find(file() + ": byte " + std::to_string(ply.size()) +
                     ": 1 elements 'extra' of 4 bytes each do not fit in the 0 bytes left in the file"),
              std::string::npos)
        << e;
}

TEST_F(PlyLoader, RefusesAFaceIndexOutOfRange) {
    PlyMesh m = quadAndTriangle();
    m.faces[1][1] = 5;
    const std::string bin = error(test::writePly(m, PlyEncoding::BigEndian));
    EXPECT_NE(bin.find(": element 'face' 1 of 2, property 'vertex_indices': vertex index 5 out of range: the "
                       "file has 5 vertices (0-based)"),
              std::string::npos)
        << bin;
    EXPECT_NE(bin.find(": byte "), std::string::npos) << bin;
    const std::string ascii = error(test::writePly(m, PlyEncoding::Ascii));
    // The second face's line is the header's 10 lines, 5 vertex lines and the first face later.
    EXPECT_NE(ascii.find(file() + ":17:5: element 'face' 1 of 2"), std::string::npos) << ascii;
    EXPECT_NE(ascii.find("vertex index 5 out of range"), std::string::npos) << ascii;
}

TEST_F(PlyLoader, RefusesCountsTheFileCannotHoldBeforeReadingThem) {
    std::string ply = test::writePly(quadAndTriangle(), PlyEncoding::LittleEndian);
    ply.replace(ply.find("element vertex 5"), 16, "element vertex 500000000");
    const std::string e = error(ply);
    EXPECT_NE(e.find(file() + ":4: 500000000 elements 'vertex' of at least 12 bytes each cannot fit in the "),
              std::string::npos)
        << e;
    std::string ascii = test::writePly(quadAndTriangle(), PlyEncoding::Ascii);
    ascii.replace(ascii.find("element face 2"), 14, "element face 9223372036854775807");
    EXPECT_NE(error(ascii).find("9223372036854775807 elements 'face' of at least 2 bytes each cannot fit"),
              std::string::npos)
        << error(ascii);
}

TEST_F(PlyLoader, RefusesCountsSmallerThanTheData) {
    std::string bin = test::writePly(quadAndTriangle(), PlyEncoding::LittleEndian);
    bin.replace(bin.find("element face 2"), 14, "element face 1");
    EXPECT_NE(error(bin).find(": 13 bytes after the last element (the header's counts are too small)"),
              std::string::npos)
        << error(bin);
    std::string ascii = test::writePly(quadAndTriangle(), PlyEncoding::Ascii);
    ascii.replace(ascii.find("element face 2"), 14, "element face 1");
    EXPECT_NE(error(ascii).find(file() + ":17:1: unexpected '3' after the last element"), std::string::npos)
        << error(ascii);
}

TEST_F(PlyLoader, RefusesAnUnknownFormat) {
    const std::string e = error("ply\nformat binary_middle_endian 1.0\nend_header\n");
    EXPECT_NE(e.find(file() + ":2:8: unknown PLY format 'binary_middle_endian' (expected ascii, "
                              "binary_little_endian or binary_big_endian)"),
              std::string::npos)
        << e;
    EXPECT_NE(error("ply\nformat ascii 2.0\nend_header\n").find(":2:14: unsupported PLY version '2.0'"),
              std::string::npos);
}

// Blender 2.4x wrote "Created by Blender ..." into the header without `comment`: such lines are read
// past as comments, with one warning for the file.
TEST_F(PlyLoader, HeaderLinesWithoutAKeywordAreCommentsWithOneWarning) {
    const std::string body = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                             "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const Scene s = load(std::string(kHeaderStart) + "Created by Blender 2.47\nelment typo 1\n" + body);
    EXPECT_EQ(s.triangles.size(), 1u);
    ASSERT_EQ(warnings_.size(), 1u);
    EXPECT_NE(warnings_[0].find("2 header line(s) with no PLY keyword read as comments (the first: line 3)"),
              std::string::npos)
        << warnings_[0];
    warnings_.clear();
    load(std::string(kHeaderStart) + body);
    EXPECT_TRUE(warnings_.empty());
}

TEST_F(PlyLoader, RefusesBadHeaders) {
    const auto expect = [&](const std::string& ply, const std::string& what) {
        const std::string e = error(ply);
        EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    };
    expect("OFF\n3 1 0\n", file() + ":1:1: not a PLY file: the first line is not 'ply'");
    expect("", file() + ": not a PLY file: it is empty");
    expect(std::string(kHeaderStart) + "element vertex 0\n", ": the PLY header has no 'end_header' line");
    expect("ply\nelement vertex 0\nend_header\n", ":3:1: the PLY header has no 'format' line");
    expect(std::string(kHeaderStart) + "property float x\nend_header\n", ":3:1: 'property' before any 'element'");
    expect(std::string(kHeaderStart) + "element vertex 1\nproperty float32 x\nproperty half y\nend_header\n",
           ":5:10: unknown PLY property type 'half'");
    expect(std::string(kHeaderStart) + "element vertex -1\nend_header\n",
           ":3:16: the count of element 'vertex' is not a non-negative integer: '-1'");
    expect(std::string(kHeaderStart) + "element face 0\nproperty list float int vertex_indices\nend_header\n",
           ":4:15: a list's length type must be an integer type, not 'float'");
    expect(std::string(kHeaderStart) + "element vertex 0\nproperty float x\nproperty float y\nend_header\n",
           ":3: element 'vertex' has no property 'z'");
    expect(std::string(kHeaderStart) + "element vertex 0\nproperty float x\nproperty float x\nend_header\n",
           ":5:16: element 'vertex' has a second property 'x'");
    expect(std::string(kHeaderStart) + "element face 1\nproperty list uchar int vertex_indices\n"
                                       "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                       "end_header\n3 0 1 2\n0 0 0\n1 0 0\n0 1 0\n",
           ":3: element 'face' comes before element 'vertex'");
    expect(std::string(kHeaderStart) + "element vertex 0\nproperty float x\nproperty float y\nproperty float z\n"
                                       "element face 0\nproperty list uchar float vertex_indices\nend_header\n",
           ":8: property 'vertex_indices' of 'face' must be a list of integers");
}

TEST_F(PlyLoader, RefusesBadValues) {
    const std::string head = std::string(kHeaderStart) +
                             "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                             "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const auto expect = [&](const std::string& body, const std::string& what) {
        const std::string e = error(head + body);
        EXPECT_NE(e.find(what), std::string::npos) << "expected '" << what << "' in: " << e;
    };
    expect("0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n", ":11:5: element 'vertex' 1 of 3, property 'z':");
    expect("0 0 0\n1 0 0\n0 1 0\n2 0 1\n", ":13:1: element 'face' 0 of 1, property 'vertex_indices': a face needs "
                                         "at least 3 vertices, got 2");
    expect("0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n", ":13:1: element 'face' 0 of 1, property 'vertex_indices': the "
                                             "value 256 is out of its type's range");
    expect("0 0 0\n1 0 0\n0 1 0\n3 0 1\n", ":14:1: element 'face' 0 of 1, property 'vertex_indices': the file "
                                         "ends early");
    expect("0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n", "a list of 200 items does not fit in the");
}

TEST_F(PlyLoader, ReadsDoublesPastTheFloatRangeInPropertiesItSkips) {
    const Scene s = load(std::string(kHeaderStart) +
                         "element vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                         "property double time\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 0 1e300\n1 0 0 -2.5e-310\n0 1 0 0\n3 0 1 2\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_NE(error(std::string(kHeaderStart) + "element vertex 1\nproperty double x\nproperty double y\n"
                                                "property double z\nend_header\n1e300 0 0\n")
                  .find(":8:9: element 'vertex' 0 of 1: 'x' is not a finite 32-bit float"),
              std::string::npos)
        << error(std::string(kHeaderStart) + "element vertex 1\nproperty double x\nproperty double y\n"
                                             "property double z\nend_header\n1e300 0 0\n");
}

TEST_F(PlyLoader, RefusesANegativeListLength) {
    std::string ply = "ply\nformat binary_big_endian 1.0\nelement vertex 0\nproperty float x\nproperty float y\n"
                      "property float z\nelement face 1\nproperty list char int vertex_indices\nend_header\n";
    const size_t at = ply.size();
    test::appendPlyValue(ply, int8_t(-3), PlyEncoding::BigEndian);
    const std::string e = error(ply);
    EXPECT_NE(e.find(": byte " + std::to_string(at) + ": element 'face' 0 of 1, property 'vertex_indices': a "
                                                       "list of negative length -3"),
              std::string::npos)
        << e;
}

}  // namespace
}  // namespace vkray
