// A mesh written as PLY (binary and ASCII) and as glTF (GLB) from the triangles vkray loaded from
// another source renders exactly as that source does: the same image, depth and primid on the CPU reference,
// pixel for pixel. With a generated mesh always, and with the Stanford bunny of scenes/bunny.scene
// (its OBJ) when scripts/fetch-scenes.sh has fetched it.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "accel/accel.h"
#include "accel/accel_spec.h"
#include "cpu/reference_renderer.h"
#include "scene/scene_parser.h"
#include "support/gltf_writer.h"
#include "support/ply_writer.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;
using test::PlyEncoding;

fs::path outputDir() {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "mesh_formats";
    fs::create_directories(dir);
    return dir;
}

Scene parse(const std::string& text, const fs::path& baseDir) {
    std::istringstream in(text);
    return parseScene(in, "test.scene", baseDir);
}

// The CPU reference's frame of `scene` at 128 x 96 with its AOVs, traced through a BVH (the same
// answers as brute force: geometry/tracer.h) so that a mesh of 70k triangles takes a moment.
Frame render(const Scene& scene) {
    const std::unique_ptr<accel::BuiltAccel> bvh = accel::buildAccel(scene, accel::resolveAccel("bvh"));
    const std::unique_ptr<geometry::Tracer> tracer = bvh->makeTracer(scene);
    RenderOptions options;
    options.width = 128;
    options.height = 96;
    options.maxDepth = scene.maxDepth;
    options.threads = 2;
    options.primaryAovs = true;
    return renderReference(scene, options, *tracer);
}

void expectSameFrame(const Frame& a, const Frame& b) {
    ASSERT_EQ(a.color.size(), b.color.size());
    size_t differing = 0, hits = 0;
    for (size_t i = 0; i < a.color.size(); ++i) {
        if (a.color[i] != b.color[i] || a.primId[i] != b.primId[i] ||
            std::memcmp(&a.depth[i], &b.depth[i], sizeof(float)) != 0)
            ++differing;
        hits += a.primId[i] >= 0;
    }
    EXPECT_EQ(differing, 0u) << "pixels that differ in colour, primid or depth";
    EXPECT_GT(hits, a.color.size() / 10) << "the mesh should be in view";
}

// The mesh as a GLB: one node, one indexed triangle list, no material.
std::string glbOf(const test::PlyMesh& mesh) {
    test::GltfWriter w;
    std::vector<float> positions;
    for (const glm::vec3& p : mesh.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    std::vector<uint32_t> indices;
    for (const std::vector<uint32_t>& f : mesh.faces) indices.insert(indices.end(), f.begin(), f.end());
    const int p = w.vec3(positions), i = w.indices32(indices);
    return w.glb("\"meshes\": [{\"primitives\": [{\"attributes\": {\"POSITION\": " + std::to_string(p) +
                 "}, \"indices\": " + std::to_string(i) + "}]}], \"nodes\": [{\"mesh\": 0}]");
}

// `scene` (the scene text that loads the mesh with `geoLine`) rendered with the mesh as it is and
// as PLY and glTF files written from its triangles (loaded alone by `geoLine`, identity transform).
void expectConvertedRendersTheSame(const std::string& sceneText, const std::string& geoLine, const fs::path& baseDir,
                             const std::string& name) {
    const Scene alone = parse(geoLine + "\n", baseDir);
    ASSERT_EQ(alone.origin, glm::dvec3(0.0)) << "the mesh's floats are its world positions";
    const test::PlyMesh mesh = test::plyMeshOf(alone);
    const size_t at = sceneText.find(geoLine);
    ASSERT_NE(at, std::string::npos);
    const Frame reference = render(parse(sceneText, baseDir));
    const std::pair<std::string, std::string> files[] = {
        {name + "-binary.ply", test::writePly(mesh, PlyEncoding::LittleEndian)},
        {name + "-ascii.ply", test::writePly(mesh, PlyEncoding::Ascii)},
        {name + ".glb", glbOf(mesh)},
    };
    for (const auto& [file, bytes] : files) {
        SCOPED_TRACE(file);
        std::ofstream(outputDir() / file, std::ios::binary) << bytes;
        std::string text = sceneText;
        text.replace(at, geoLine.size(), "geo " + (outputDir() / file).string());
        const Scene converted = parse(text, baseDir);
        ASSERT_EQ(converted.triangles.size(), parse(sceneText, baseDir).triangles.size());
        expectSameFrame(reference, render(converted));
    }
}

TEST(MeshFormats, AGeneratedMeshRendersTheSameAsPlyAndGltf) {
    const std::string scene = "size 128 96\nmaxdepth 3\ncamera 0 1.6 2.6 0 0.3 0 0 1 0 40\n"
                              "point -2 3 2 0.8 0.8 0.8\ndirectional 1 1 0 0.3 0.3 0.3\n"
                              "diffuse 0.6 0.5 0.4\nspecular 0.3 0.3 0.3\nshininess 20\n"
                              "generate terrain 4000 7\n";
    expectConvertedRendersTheSame(scene, "generate terrain 4000 7", outputDir(), "terrain");
}

TEST(MeshFormats, TheBunnyRendersTheSameAsObjPlyAndGltf) {
    const fs::path scenes = fs::path(VKRAY_SOURCE_DIR) / "scenes";
    if (!fs::exists(scenes / "meshes" / "bunny.obj"))
        GTEST_SKIP() << "scenes/meshes/bunny.obj absent: run scripts/fetch-scenes.sh";
    std::ifstream in(scenes / "bunny.scene");
    const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    expectConvertedRendersTheSame(text, "geo meshes/bunny.obj", scenes, "bunny");
}

}  // namespace
}  // namespace vkray
