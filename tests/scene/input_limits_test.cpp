// Hardened input: limits that keep a hostile or broken file from costing unbounded time
// or memory, files that are not text files, and meshes served from memory (the fuzzer's way in).
#include <sys/stat.h>

#include <fstream>
#include <map>
#include <thread>

#include <gtest/gtest.h>

#include "scene/obj_check.h"
#include "scene/scene_builder.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

// Mesh files from memory: `files` by name, anything else "not in the test's files".
ParseOptions inMemory(std::map<std::string, std::string> files, int64_t maxTriangles = kMaxSceneTriangles) {
    ParseOptions options;
    options.maxTriangles = maxTriangles;
    options.readFile = [files = std::move(files)](const fs::path& file, std::string& whyNot) -> std::optional<std::string> {
        const auto it = files.find(file.filename().string());
        if (it == files.end()) {
            whyNot = "not in the test's files";
            return std::nullopt;
        }
        return it->second;
    };
    return options;
}

std::string errorOf(const std::string& scene, const ParseOptions& options) {
    try {
        parseSceneText(scene, "test.scene", "mem", options);
    } catch (const Error& e) {
        return e.what();
    }
    return "(no error)";
}

std::string repeat(const std::string& line, int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += line;
    return s;
}

const std::string kTriangle = "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\ntri 0 1 2\n";
const std::string kObjTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

TEST(Quoted, ShortTextIsQuotedWhole) {
    EXPECT_EQ(quoted("abc"), "'abc'");
    EXPECT_EQ(excerpt("1.5"), "1.5");
}

TEST(Quoted, LongTextKeepsItsStartAndLength) {
    EXPECT_EQ(quoted(std::string(1000, 'x'), 4), "'xxxx...' (1000 bytes)");
    EXPECT_EQ(excerpt(std::string(1000, '1'), 4), "1111... (1000 bytes)");
    // Never cut inside a UTF-8 character: "é" is 2 bytes, the cut backs up to its start.
    EXPECT_EQ(quoted("ab\xC3\xA9" + std::string(10, 'c'), 3), "'ab...' (14 bytes)");
}

// A name read from a file (a glTF buffer URI percent-decoded to a line feed, say) keeps the
// message it is quoted in on one line.
TEST(Quoted, ControlBytesAreEscaped) {
    EXPECT_EQ(quoted("a\nb\r\tc"), "'a\\nb\\r\\tc'");
    EXPECT_EQ(vkray::quoted(std::string("\x01\x7f\0", 3)), "'\\x01\\x7f\\x00'");
    EXPECT_EQ(excerpt("1\n2"), "1\\n2");
    EXPECT_EQ(quoted("\n\n\nxyz", 2), "'\\n\\n...' (6 bytes)");
}

TEST(ReadFileBytes, SaysWhyAFileCannotBeRead) {
    std::string why;
    EXPECT_FALSE(readFileBytes("no/such/file.scene", why));
    EXPECT_EQ(why, "no such file or directory");
    EXPECT_FALSE(readFileBytes(VKRAY_SOURCE_DIR, why));
    EXPECT_EQ(why, "is a directory");
    // A device never ends: refused before reading, not read until memory runs out.
    EXPECT_FALSE(readFileBytes("/dev/zero", why));
    EXPECT_EQ(why, "is a character device, not a regular file");
}

TEST(ReadFileBytes, ReadsAPipe) {
    const fs::path fifo = fs::path(VKRAY_TEST_OUTPUT_DIR) / "input_limits.fifo";
    fs::remove(fifo);
    ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
    std::thread writer([&] { std::ofstream(fifo) << "size 3 2\n"; });
    std::string why;
    const std::optional<std::string> bytes = readFileBytes(fifo, why);
    writer.join();
    fs::remove(fifo);
    ASSERT_TRUE(bytes) << why;
    EXPECT_EQ(*bytes, "size 3 2\n");
}

TEST(SceneLines, AreAtMost64KiB) {
    const std::string longest = "#" + std::string(kMaxSceneLineBytes - 1, 'x') + "\n";
    EXPECT_NO_THROW(test::parseText(longest + kTriangle));
    const std::string message = test::parseError("size 1 1\n#" + std::string(kMaxSceneLineBytes, 'x') + "\n");
    EXPECT_EQ(message, "test.scene:2: line is 65537 bytes long, more than the 65536 a line may have");
}

TEST(TriangleLimit, EveryKindOfGeometryIsCheckedBeforeItIsMade) {
    // spheresteps 3: 24 triangles a sphere; four fit under 100, the fifth does not.
    const std::string spheres = "spheresteps 3\n" + repeat("sphere 0 0 0 1\n", 5);
    EXPECT_EQ(errorOf(spheres, inMemory({}, 100)),
              "test.scene:6:1: the scene would have 120 triangles (96 so far), past the limit of 100");
    EXPECT_EQ(errorOf("generate soup 101\n", inMemory({}, 100)),
              "test.scene:1:1: the scene would have 101 triangles (0 so far), past the limit of 100");
    EXPECT_EQ(errorOf("generate soup 60\ngenerate soup 60\n", inMemory({}, 100)),
              "test.scene:2:1: the scene would have 120 triangles (60 so far), past the limit of 100");
    EXPECT_EQ(errorOf(kTriangle + "tri 0 1 2\n", inMemory({}, 1)),
              "test.scene:5:1: the scene would have 2 triangles (1 so far), past the limit of 1");
    EXPECT_EQ(errorOf("geo m.obj\n", inMemory({{"m.obj", repeat(kObjTriangle, 3)}}, 2)),
              "test.scene:1: in 'mem/m.obj': the scene would have 3 triangles (0 so far), past the limit of 2");
    const std::string off = "OFF\n3 5 0\n0 0 0\n1 0 0\n0 1 0\n" + repeat("3 0 1 2\n", 5);
    const std::string message = errorOf("geo m.off\n", inMemory({{"m.off", off}}, 4));
    EXPECT_TRUE(message.starts_with("mem/m.off:2:3: the scene would have 5 triangles")) << message;
    EXPECT_NO_THROW(parseSceneText("geo m.off\n", "test.scene", "mem", inMemory({{"m.off", off}}, 5)));
}

TEST(TriangleLimit, TheDefaultIs2To26) {
    EXPECT_EQ(ParseOptions{}.maxTriangles, int64_t(1) << 26);
    Scene scene;
    const SceneBuilder builder(scene);
    EXPECT_EQ(builder.roomProblem(uint64_t(1) << 27).value_or(""),
              "the scene would have 134217728 triangles (0 so far), past the limit of 67108864 (2^26) a "
              "scene may have");
    EXPECT_FALSE(builder.roomProblem(uint64_t(1) << 26));
}

TEST(Transforms, ChainsThatLeaveDoublePrecisionAreErrors) {
    EXPECT_EQ(test::parseError(repeat("scale 1e30 1e30 1e30\n", 11)),
              "test.scene:11:1: the transform overflows or becomes singular in double precision (scale factors "
              "that multiply past 1e308 or below 1e-308, or axes scaled too unevenly)");
    EXPECT_NE(test::parseError(repeat("scale 1e-30 1e-30 1e-30\n", 11)).find("test.scene:11:1: the transform"),
              std::string::npos);
}

TEST(Transforms, TinyButRepresentableScalesKeepTheirNormals) {
    // 1e-120: the 3x3 determinant (1e-360) underflows, which must not make the normals NaN.
    const Scene s = test::parseText(repeat("scale 1e-30 1e-30 1e-30\n", 4) + "sphere 0 0 0 1\n");
    ASSERT_FALSE(s.normals.empty());
    for (const TriangleNormals& n : s.normals)
        for (const glm::vec3& v : {n.n0, n.n1, n.n2}) EXPECT_NEAR(glm::length(v), 1.0f, 1e-5f);
}

TEST(Transforms, PushTransformNestsAtMost1024Deep) {
    EXPECT_NO_THROW(test::parseText(repeat("pushTransform\n", int(kMaxTransformDepth))));
    EXPECT_EQ(test::parseError(repeat("pushTransform\n", int(kMaxTransformDepth) + 1)),
              "test.scene:1025:1: pushTransform nested more than 1024 deep (is a popTransform missing?)");
}

TEST(InMemoryFiles, MeshesAndMaterialsComeFromTheReader) {
    const ParseOptions options = inMemory({{"m.obj", "mtllib m.mtl\nusemtl red\n" + kObjTriangle},
                                           {"m.mtl", "newmtl red\nKd 1 0 0\n"}});
    const Scene s = parseSceneText("geo m.obj\n", "test.scene", "mem", options);
    ASSERT_EQ(s.triangles.size(), 1u);
    EXPECT_EQ(s.materials.at(s.triangles[0].material).diffuse, glm::vec3(1, 0, 0));
    EXPECT_EQ(errorOf("geo other.obj\n", options), "test.scene:1: cannot open OBJ file 'mem/other.obj': not in the test's files");
}

TEST(ObjStatements, WhatHoldsNoSurfaceIsSkipped) {
    const std::string obj = "o thing\ng group\ns 1\nvt 0 0\nl 1 2\np 3\nmg off\n" + kObjTriangle;
    EXPECT_EQ(parseSceneText("geo m.obj\n", "test.scene", "mem", inMemory({{"m.obj", obj}})).triangles.size(), 1u);
}

TEST(ObjStatements, GeometryTinyobjloaderWouldDropIsAnError) {
    const auto objError = [](const std::string& obj) { return errorOf("geo m.obj\n", inMemory({{"m.obj", obj}})); };
    EXPECT_EQ(objError(kObjTriangle + "call other.obj\n"),
              "mem/m.obj:5:1: OBJ statement 'call' is not supported (vkray reads polygons: v, vn, vt, f); its "
              "geometry would be missing (OBJ loaded at test.scene:1)");
    EXPECT_NE(objError(kObjTriangle + "  curv 0 1 1 2\n").find("m.obj:5:3: OBJ statement 'curv' is not supported"),
              std::string::npos);
    EXPECT_NE(objError("v 0 0 0\nv 1 0 0\nv 0 1 0\nfo 1 2 3\n").find("'fo' (the old spelling of 'f')"),
              std::string::npos);
    EXPECT_NE(objError("camera 0 0 5 0 0 0 0 1 0 45\n").find("m.obj:1:1: unknown OBJ statement 'camera'"),
              std::string::npos);
}

std::string polygonObj(int corners) {
    std::string obj;
    for (int i = 0; i < corners; ++i)
        obj += "v " + std::to_string(std::cos(6.283185307 * i / corners)) + " " +
               std::to_string(std::sin(6.283185307 * i / corners)) + " 0\n";
    obj += "f";
    for (int i = 1; i <= corners; ++i) obj += " " + std::to_string(i);
    return obj + "\n";
}

TEST(ObjPolygons, AtMost1024CornersAndEveryTriangleAccountedFor) {
    const Scene s = parseSceneText("geo m.obj\n", "test.scene", "mem",
                                   inMemory({{"m.obj", polygonObj(int(kMaxObjFaceCorners))}}));
    EXPECT_EQ(s.triangles.size(), kMaxObjFaceCorners - 2);
    EXPECT_EQ(errorOf("geo m.obj\n", inMemory({{"m.obj", polygonObj(int(kMaxObjFaceCorners) + 1)}})),
              "mem/m.obj:1026:1: face of 1025 vertices, more than the 1024 vkray triangulates (split the "
              "polygon) (OBJ loaded at test.scene:1)");
    // A self-overlapping pentagon: tinyobjloader's ear clipping makes no triangle of it and says nothing.
    const std::string bad = "v 3 4 0\nv 1 6 0\nv 7 2 0\nv 1 1 0\nv 0 6 0\nf 1 2 3 4 5\n";
    EXPECT_EQ(errorOf("geo m.obj\n", inMemory({{"m.obj", bad}})),
              "test.scene:1: in 'mem/m.obj': tinyobjloader triangulated the faces into 0 triangles instead of 3 (a "
              "degenerate or self-overlapping polygon); split such polygons into triangles");
}

TEST(ObjSummary, CountsTheTrianglesOfThePolygons) {
    EXPECT_EQ(checkObjText("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 1 2 4 3\n", "m.obj", "").triangles, 3u);
}

TEST(Utf16, MeshFilesAreRecognizedToo) {
    const std::string utf16(std::string("v\0 \0", 4));
    EXPECT_NE(errorOf("geo m.obj\n", inMemory({{"m.obj", utf16}})).find("m.obj:1: UTF-16 is not supported"),
              std::string::npos);
}

}  // namespace
}  // namespace vkray
