// OFF meshes through `geo`: fan triangulation in file order, the transform and material state,
// the optional parts of the format (counts on the header line, comments, colours), and one test
// per bad input, each a vkray::Error naming file:line and the cause.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "scene_test_util.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;
using namespace std::string_view_literals;

class OffLoader : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::path(VKRAY_TEST_OUTPUT_DIR) / "off_loader" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    // Writes `off` as NAME and loads a scene that places it with `prefix` lines before `geo`.
    Scene load(const std::string& off, const std::string& prefix = "", const std::string& name = "m.off") {
        write(name, off);
        std::istringstream in(prefix + "geo " + name + "\n");
        return parseScene(in, "test.scene", dir_);
    }

    std::string error(const std::string& off, const std::string& name = "m.off") {
        try {
            load(off, "", name);
        } catch (const Error& e) {
            return e.what();
        }
        return "(no error)";
    }

    void write(const std::string& name, const std::string& text) {
        std::ofstream(dir_ / name, std::ios::binary) << text;
    }

    std::string file(const std::string& name = "m.off") const { return (dir_ / name).lexically_normal().string(); }

    fs::path dir_;
};

const char* kQuadAndTriangle =
    "OFF\n"
    "5 2 0\n"
    "0 0 0\n"
    "1 0 0\n"
    "1 1 0\n"
    "0 1 0\n"
    "0 0 1\n"
    "4 0 1 2 3\n"
    "3 4 1 0\n";

TEST_F(OffLoader, FansPolygonsInFileOrder) {
    const Scene s = load(kQuadAndTriangle);
    ASSERT_EQ(s.triangles.size(), 3u);
    // Quad 0 1 2 3 -> (0 1 2), (0 2 3); then the triangle 4 1 0.
    EXPECT_EQ(s.triangles[0].p0, glm::vec3(0, 0, 0));
    EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(1, 1, 0));
    EXPECT_EQ(s.triangles[1].p0, glm::vec3(0, 0, 0));
    EXPECT_EQ(s.triangles[1].p1, glm::vec3(1, 1, 0));
    EXPECT_EQ(s.triangles[1].p2, glm::vec3(0, 1, 0));
    EXPECT_EQ(s.triangles[2].p0, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.triangles[2].p2, glm::vec3(0, 0, 0));
    EXPECT_FALSE(s.hasSmoothNormals());  // OFF has no normals: flat shading
}

TEST_F(OffLoader, UsesTheCurrentTransformAndMaterial) {
    const Scene s = test::inWorld(load(kQuadAndTriangle, "diffuse 0.1 0.2 0.3\ntranslate 0 0 -5\nscale 2 2 2\n"));
    ASSERT_EQ(s.triangles.size(), 3u);
    EXPECT_EQ(s.triangles[0].p2, glm::vec3(2, 2, -5));
    for (const Triangle& t : s.triangles) {
        ASSERT_LT(t.material, s.materials.size());
        EXPECT_EQ(s.materials[t.material].diffuse, glm::vec3(0.1f, 0.2f, 0.3f));
    }
}

TEST_F(OffLoader, AcceptsCommentsBlankLinesCrlfAndCountsOnTheHeaderLine) {
    const Scene s = load("# made by hand\r\nOFF 3 1 0   # counts here\r\n\r\n0 0 0\r\n# a comment\r\n"
                         "1 0 0\r\n0 1 0\r\n3 0 1 2\r\n\r\n# trailing comment\r\n");
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.triangles[0].p1, glm::vec3(1, 0, 0));
}

TEST_F(OffLoader, IgnoresVertexAndFaceColours) {
    const Scene s = load("COFF\n3 2\n0 0 0 255 0 0 255\n1 0 0 0 255 0\n0 1 0 0 0 1 1\n3 0 1 2 1 0 0\n3 2 1 0 0.5 0.5 0.5 1\n");
    ASSERT_EQ(s.triangles.size(), 2u);
    EXPECT_EQ(s.triangles[1].p0, glm::vec3(0, 1, 0));
}

TEST_F(OffLoader, ExtensionIsCaseInsensitiveAndEmptyMeshesAddNothing) {
    EXPECT_EQ(load("OFF\n0 0 0\n", "", "empty.OFF").triangles.size(), 0u);
}

TEST_F(OffLoader, MissingFileNamesTheSceneLine) {
    std::istringstream in("geo nothing.off\n");
    try {
        parseScene(in, "test.scene", dir_);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("test.scene:1"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("cannot open OFF file"), std::string::npos) << e.what();
    }
}

// Each bad input: the message starts with file:line[:col] and names the cause.
struct BadOff {
    const char* name;
    std::string_view text;
    const char* location;  // after the file name
    const char* cause;
};

const BadOff kBadOffs[] = {
    {"no_header", "3 1 0\n0 0 0\n", ":1:1:", "expected the header 'OFF'"},
    {"noff", "NOFF\n3 1 0\n", ":1:1:", "unsupported OFF variant 'NOFF'"},
    {"binary", "OFF BINARY\n", ":1:5:", "binary OFF is not supported"},
    {"counts_not_numbers", "OFF\nthree 1 0\n", ":2:1:", "the vertex count"},
    {"counts_missing_faces", "OFF\n3\n", ":2:1:", "expected the counts"},
    {"counts_negative", "OFF\n3 -1 0\n", ":2:1:", "negative counts"},
    {"counts_lie", "OFF\n1000000000 2000000000 0\n0 0 0\n", ":2:1:", "cannot fit in a file of"},
    {"vertex_nan", "OFF\n3 1 0\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n", ":4:3:", "is 'nan', not a finite number"},
    {"vertex_inf", "OFF\n3 1 0\n0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n", ":4:5:", "is '-inf', not a finite number"},
    {"vertex_huge", "OFF\n3 1 0\n0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n", ":4:1:", "1e39"},
    {"vertex_two_values", "OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2\n", ":4:1:", "3 numbers x y z for vertex 1"},
    {"vertex_not_a_number", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n", ":4:3:", "'x'"},
    {"face_two_vertices", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n", ":6:1:", "at least 3 vertices"},
    {"face_short", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", ":6:1:", "lists only 3 values"},
    {"face_index_range", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", ":6:7:", "vertex index 3 out of range"},
    {"face_index_negative", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", ":6:5:", "vertex index -1 out of range"},
    {"face_index_float", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n", ":6:5:", "vertex index"},
    {"face_too_many_values", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2 1 1 1 1 1\n", ":6:9:", "5 values after its indices"},
    {"truncated_vertices", "OFF\n4 1 0\n0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n", ":4:", "file ends early: 2 of the 4 vertices announced at line 2"},
    {"truncated_faces", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", ":6:", "1 of the 2 faces announced at line 2"},
    {"no_counts", "OFF\n# nothing else\n", ":2:", "no counts after the header"},
    {"empty_file", "", ": ", "no 'OFF' header"},
    {"trailing_content", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n", ":7:1:", "after the last of the 1 faces"},
    {"nul_byte", "OFF\n3 1 0\n0 0\0 0\n1 0 0\n0 1 0\n3 0 1 2\n"sv, ":3:4:", "binary data"},
};

TEST_F(OffLoader, EveryBadInputIsOneErrorWithFileAndLine) {
    for (const BadOff& bad : kBadOffs) {
        SCOPED_TRACE(bad.name);
        const std::string message = error(std::string(bad.text), std::string(bad.name) + ".off");
        const std::string where = file(std::string(bad.name) + ".off") + bad.location;
        EXPECT_EQ(message.rfind(where, 0), 0u) << message << "\n  expected to start with " << where;
        EXPECT_NE(message.find(bad.cause), std::string::npos) << message;
        // Bytes are checked by the shared text reader (text_input.h), as for OBJ, before the
        // OFF reader sees a line: its message names the OFF file but not the scene line.
        if (bad.name != "nul_byte"sv) {
            EXPECT_NE(message.find("(OFF loaded at test.scene:1)"), std::string::npos) << message;
        }
    }
}

}  // namespace
}  // namespace vkray
