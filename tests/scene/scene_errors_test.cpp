// Malformed .scene input: every bad line is an error naming file:line[:col] and what was expected.
#include <fstream>

#include <gtest/gtest.h>

#include "scene_test_util.h"

namespace vkray {
namespace {

using test::parseError;

struct ErrorCase {
    std::string scene;
    int line;
    int col;            // 0: the column is not checked
    const char* cause;  // substring of the message
};

void PrintTo(const ErrorCase& c, std::ostream* os) { *os << testing::PrintToString(c.scene); }

class SceneErrors : public testing::TestWithParam<ErrorCase> {};

TEST_P(SceneErrors, NameFileLineAndCause) {
    const ErrorCase& c = GetParam();
    const std::string message = parseError(c.scene);
    std::string location = "test.scene:" + std::to_string(c.line);
    location += c.col > 0 ? ":" + std::to_string(c.col) + ": " : std::string(":");
    EXPECT_TRUE(message.starts_with(location)) << message << "\nexpected location: " << location;
    EXPECT_NE(message.find(c.cause), std::string::npos) << message << "\nexpected cause: " << c.cause;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
}

const std::string kThreeVertices = "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n";
const std::string kCamera = "camera 0 0 5 0 0 0 0 1 0 ";

INSTANTIATE_TEST_SUITE_P(
    Commands, SceneErrors,
    testing::Values(
        ErrorCase{"# ok\nfoo 1 2\n", 2, 1, "unknown command 'foo' (the commands are listed in docs/scene-format.md)"},
        ErrorCase{"sphre 1 2 3 1\n", 1, 1, "unknown command 'sphre' (did you mean 'sphere'?)"},
        ErrorCase{"vertx 1 2 3\n", 1, 1, "(did you mean 'vertex'?)"},
        ErrorCase{"difuse 1 1 1\n", 1, 1, "(did you mean 'diffuse'?)"},
        ErrorCase{"ambiant 1 1 1\n", 1, 1, "(did you mean 'ambient'?)"},
        ErrorCase{"shinyness 10\n", 1, 1, "(did you mean 'shininess'?)"},
        ErrorCase{"PushTransform\n", 1, 1, "did you mean 'pushTransform'?"},
        ErrorCase{"  Vertex 1 2 3\n", 1, 3, "did you mean 'vertex'?"},
        ErrorCase{"vertex 1 2\n", 1, 1, "expected 3 numbers after 'vertex' (x y z), got 2"},
        ErrorCase{"vertex 1 2 3 4\n", 1, 14, "expected 3 numbers after 'vertex' (x y z), got 4"},
        ErrorCase{"size 640\n", 1, 0, "expected 2 integers after 'size' (width height), got 1"},
        ErrorCase{"camera 0 0 5 0 0 0 0 1 0\n", 1, 0, "expected 10 numbers after 'camera'"},
        ErrorCase{"refract 1.5 1 1\n", 1, 0, "expected 4 numbers after 'refract' (ior tr tg tb), got 3"},
        ErrorCase{"shininess\n", 1, 0, "expected 1 number after 'shininess' (s), got 0"},
        ErrorCase{"pushTransform 1\n", 1, 15, "expected no arguments after 'pushTransform', got 1"},
        ErrorCase{"output\n", 1, 0, "expected 1 file name after 'output', got 0"},
        ErrorCase{"output my picture.png\n", 1, 0, "expected 1 file name after 'output', got 2"},
        ErrorCase{"geo a.obj b.obj\n", 1, 0, "expected 1 file name after 'geo', got 2"},
        ErrorCase{"tri 0 1\n", 1, 0, "expected 3 integers after 'tri'"},
        ErrorCase{"sphere 0 0 0\n", 1, 0, "expected 4 numbers after 'sphere' (x y z radius), got 3"}));

INSTANTIATE_TEST_SUITE_P(
    Numbers, SceneErrors,
    testing::Values(
        ErrorCase{"vertex 1 abc 3\n", 1, 10, "expected a number for argument 2 of 'vertex', got 'abc'"},
        ErrorCase{"vertex 1,5 0 0\n", 1, 8, "expected a number for argument 1 of 'vertex', got '1,5'"},
        ErrorCase{"vertex 1.5x 0 0\n", 1, 8, "got '1.5x'"},
        ErrorCase{"vertex nan 0 0\n", 1, 8, "argument 1 of 'vertex' is 'nan', not a finite number"},
        ErrorCase{"vertex 0 -inf 0\n", 1, 10, "is '-inf', not a finite number"},
        ErrorCase{"diffuse 1 1 INFINITY\n", 1, 0, "not a finite number"},
        ErrorCase{"vertex 0 0 1e999\n", 1, 12, "argument 3 of 'vertex' '1e999' is out of range"},
        ErrorCase{"vertex 0 0 1e39\n", 1, 12, "'1e39' is out of range for a 32-bit float"},
        ErrorCase{"point 0 0 1e-999 1 1 1\n", 1, 0, "out of range"},
        ErrorCase{"size 640.0 480\n", 1, 6, "expected an integer for argument 1 of 'size', got '640.0'"},
        ErrorCase{"maxdepth 99999999999999999999\n", 1, 10, "is out of range"},
        ErrorCase{kThreeVertices + "tri 0 1 1.5\n", 4, 9, "expected an integer for argument 3 of 'tri'"},
        ErrorCase{"ambient + 1 1\n", 1, 9, "got '+'"}));

INSTANTIATE_TEST_SUITE_P(
    Values, SceneErrors,
    testing::Values(
        ErrorCase{"vertex 0 0 0\nvertex 1 0 0\ntri 0 1 2\n", 3, 9,
                  "vertex index 2 out of range (2 defined, valid 0..1)"},
        ErrorCase{kThreeVertices + "tri 0 -1 2\n", 4, 7, "vertex index -1 out of range"},
        ErrorCase{"tri 0 0 0\n", 1, 5, "vertex index 0 out of range (none defined yet)"},
        ErrorCase{kThreeVertices + "trinormal 0 1 2\n", 4, 11,
                  "vertexnormal index 0 out of range (none defined yet)"},
        ErrorCase{"vertexnormal 0 0 0 0 1 0\ntrinormal 0 0 1\n", 2, 15, "vertexnormal index 1 out of range"},
        ErrorCase{"popTransform\n", 1, 1, "popTransform without a matching pushTransform"},
        ErrorCase{"pushTransform\npopTransform\npopTransform\n", 3, 1, "without a matching pushTransform"},
        ErrorCase{"size 0 480\n", 1, 6, "image size 0x480 is invalid: each side must be 1..16384"},
        ErrorCase{"size 640 -480\n", 1, 10, "1..16384"},
        ErrorCase{"size 20000 100\n", 1, 6, "each side must be 1..16384"},
        ErrorCase{"size 16384 16384\n", 1, 0, "the total at most 67108864 pixels (2^26)"},
        ErrorCase{"maxdepth 0\n", 1, 10, "maxdepth 0 is outside 1..64"},
        ErrorCase{"maxdepth 65\n", 1, 10, "maxdepth 65 is outside 1..64"},
        ErrorCase{"shininess -1\n", 1, 11, "shininess -1 is negative"},
        ErrorCase{"refract 0 1 1 1\n", 1, 9, "index of refraction 0 must be positive"},
        ErrorCase{"refract -1.5 1 1 1\n", 1, 9, "must be positive"},
        ErrorCase{kCamera + "0\n", 1, 26, "camera fovy 0 is outside (0, 180) degrees"},
        ErrorCase{kCamera + "180\n", 1, 26, "outside (0, 180)"},
        ErrorCase{kCamera + "-10\n", 1, 26, "outside (0, 180)"},
        ErrorCase{"camera 0 0 5 0 0 5 0 1 0 45\n", 1, 8, "camera eye and look-at centre coincide"},
        ErrorCase{"camera 0 5 0 0 0 0 0 2 0 45\n", 1, 20, "parallel to the viewing direction"},
        ErrorCase{"camera 0 0 5 0 0 0 0 0 0 45\n", 1, 20, "camera up vector is zero"},
        ErrorCase{"attenuation 0 0 0\n", 1, 13, "not all zero"},
        ErrorCase{"attenuation 1 -0.5 0\n", 1, 13, "non-negative coefficients"},
        ErrorCase{"background 0.2 -0.1 0\n", 1, 12, "background needs non-negative r g b"},
        ErrorCase{"spp 0\n", 1, 5, "spp 0 is outside 1..4096"},
        ErrorCase{"spheresteps 2\n", 1, 13, "spheresteps 2 is outside 3..512"},
        ErrorCase{"spheresteps 513\n", 1, 13, "spheresteps 513 is outside 3..512"},
        ErrorCase{"sphere 0 0 0 0\n", 1, 14, "sphere radius 0 must be positive"},
        ErrorCase{"sphere 0 0 0 -2\n", 1, 14, "sphere radius -2 must be positive"},
        ErrorCase{"rotate 0 0 0 45\n", 1, 8, "rotate axis is the zero vector"},
        ErrorCase{"scale 1 0 1\n", 1, 9, "scale factor 0"},
        ErrorCase{"directional 0 0 0 1 1 1\n", 1, 13, "directional light direction is the zero vector"},
        ErrorCase{"vertexnormal 0 0 0 0 0 0\n", 1, 20, "normal is the zero vector"},
        ErrorCase{"maxverts -1\n", 1, 10, "maxverts -1 is negative"},
        ErrorCase{"scale 1e30 1e30 1e30\nscale 1e30 1 1\n" + kThreeVertices + "tri 0 1 2\n", 6, 1,
                  "does not fit a 32-bit float"}));

INSTANTIATE_TEST_SUITE_P(
    Encoding, SceneErrors,
    testing::Values(
        ErrorCase{"vertex 1 2 3\r\nvertex 1 2\r\n", 2, 1, "got 2"},
        ErrorCase{std::string("size 1 1\nvertex 1 2 3\0\n", 23), 2, 13, "binary data (NUL byte)"},
        ErrorCase{"\x01\x02\x03\x04garbage\n", 1, 1, "binary data (control byte 0x01)"},
        ErrorCase{"size 1 1\n# caf\xE9 in Latin-1\n", 2, 6, "binary data or invalid UTF-8 (byte 0xE9)"},
        ErrorCase{"# overlong \xC0\xAF\n", 1, 12, "invalid UTF-8 (byte 0xC0)"},
        ErrorCase{"# surrogate \xED\xA0\x80\n", 1, 13, "invalid UTF-8 (byte 0xED)"},
        ErrorCase{"# cut \xE2\x82\n", 1, 7, "invalid UTF-8"},
        ErrorCase{std::string("\xFF\xFEs\0i\0z\0e\0", 10), 1, 0, "UTF-16 is not supported; save as UTF-8"},
        ErrorCase{std::string("\xFE\xFF\0s\0i\0z\0e", 10), 1, 0, "UTF-16 is not supported; save as UTF-8"},
        // UTF-16 without a byte-order mark: ASCII interleaved with NUL bytes, either order.
        ErrorCase{std::string("s\0i\0z\0e\0", 8), 1, 0, "UTF-16 is not supported (no byte-order mark"},
        ErrorCase{std::string("\0s\0i\0z\0e", 8), 1, 0, "UTF-16 is not supported (no byte-order mark"},
        // Text that has a NUL byte later is binary data, not UTF-16.
        ErrorCase{std::string("size\0\0\0\0", 8), 1, 5, "binary data (NUL byte)"}));

TEST(SceneErrorsFile, MissingSceneFile) {
    try {
        loadScene("no/such/dir/missing.scene");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()), "no/such/dir/missing.scene: cannot open scene file: no such file or directory");
        ASSERT_TRUE(e.hasLocation());
        EXPECT_EQ(e.location().file, "no/such/dir/missing.scene");
    }
}

TEST(SceneErrorsFile, ADirectoryIsNotASceneFile) { EXPECT_THROW(loadScene(test::sceneDataDir()), Error); }

TEST(SceneErrorsFile, ErrorsInAFileNameItsPath) {
    const std::filesystem::path file =
        std::filesystem::path(VKRAY_TEST_OUTPUT_DIR) / "scene_errors_bad.scene";
    std::ofstream(file) << "size 64 48\n\nvertex 1 2\n";
    try {
        loadScene(file);
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_EQ(std::string(e.what()),
                  file.string() + ":3:1: expected 3 numbers after 'vertex' (x y z), got 2");
        EXPECT_EQ(e.location().line, 3);
        EXPECT_EQ(e.location().col, 1);
    }
}

TEST(SceneErrorsFile, AnEmptyFileIsAnEmptyScene) {
    const std::filesystem::path file = std::filesystem::path(VKRAY_TEST_OUTPUT_DIR) / "empty.scene";
    std::ofstream{file};
    const Scene s = loadScene(file);
    EXPECT_TRUE(s.triangles.empty());
    EXPECT_FALSE(s.hasCamera);
}

TEST(SceneErrorsFile, ASceneWithoutTrianglesOrCameraIsNotAParseError) {
    const Scene s = test::parseText("size 64 48\npoint 0 1 0 1 1 1\n");
    EXPECT_FALSE(s.hasCamera);
    EXPECT_TRUE(s.triangles.empty());
    EXPECT_EQ(s.lights.size(), 1u);
}

TEST(SceneErrorsFile, UnbalancedPushTransformAtTheEndIsAccepted) {
    EXPECT_NO_THROW(test::parseText("pushTransform\ntranslate 1 0 0\n"));
}

}  // namespace
}  // namespace vkray
