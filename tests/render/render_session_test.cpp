// The render session (render/render_session.h) end to end: a GPU render through it against the CPU
// reference through it, a structure written by one session and read by another, the pipelines
// shared by the scenes of a session, and the checks that refuse a scene before any work.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "../gpu/gpu_test_util.h"
#include "core/error.h"
#include "image/compare.h"
#include "render/render_session.h"
#include "scene/camera.h"
#include "scene/scene_parser.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;

const fs::path kScenes = fs::path(VKRAY_SOURCE_DIR) / "scenes";
const fs::path kCliData = fs::path(VKRAY_SOURCE_DIR) / "tests" / "cli" / "data";

fs::path outputDir() {
    const fs::path dir = fs::path(VKRAY_TEST_OUTPUT_DIR) / "render_session";
    fs::create_directories(dir);
    return dir;
}

// A request for `accel` whose scenes are rendered at width x height with their AOVs into `output`
// (named after the scene file when empty).
render::RenderRequest request(const std::string& accel, int width, int height, const fs::path& output = {}) {
    render::RenderRequest r;
    r.accel = accel::resolveAccel(accel);
    r.settings = [=](const std::string& file, const Scene& scene) {
        render::SceneSettings s;
        s.options = RenderOptions{.width = width, .height = height, .maxDepth = scene.maxDepth, .primaryAovs = true};
        s.output = !output.empty() ? output : outputDir() / (fs::path(file).stem().string() + "-" + accel + ".png");
        return s;
    };
    return r;
}

std::string fileBytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The same tolerances as the GPU layer's own test against the reference (tests/gpu/gpu_vs_cpu_test.cpp).
TEST(RenderSession, GpuRenderMatchesTheCpuReference) {
    const std::string scene = (kScenes / "cornell.scene").string();
    render::RenderRequest cpu = request("bvh", 128, 128, outputDir() / "cornell-cpu.png");
    cpu.cpu = true;
    const render::SceneRender reference = render::RenderSession(std::move(cpu)).render(scene);
    const render::SceneRender gpu =
        render::RenderSession(request("bvh", 128, 128, outputDir() / "cornell-gpu.png")).render(scene);
    ASSERT_TRUE(gpu.report.gpu);
    EXPECT_FALSE(reference.report.gpu);
    EXPECT_EQ(reference.report.device, "CPU reference (double precision)");
    EXPECT_EQ(gpu.report.gpu->pixelsCutShort, 0u);

    Scene loaded = loadScene(scene);
    loaded.camera = viewCamera(loaded, "scene");
    const test::PrimIdAgreement hits = test::comparePrimaryHits(loaded, gpu.frame, reference.frame);
    EXPECT_GE(hits.fraction(), 0.999) << hits.same << " same, " << hits.ties << " ties of " << hits.pixels;
    const CompareStats stats =
        compareImages(test::quantisedColor(gpu.frame), test::quantisedColor(reference.frame), 8.0 / 255.0);
    EXPECT_LE(stats.rmse, 0.025);
    EXPECT_LE(stats.badFraction, 0.01) << stats.badPixels << " pixels differ by more than 8/255";
    EXPECT_TRUE(fs::is_regular_file(reference.report.output));
    EXPECT_TRUE(fs::is_regular_file(gpu.report.output));
}

// A structure file written by one session and read by another gives the same image, byte for byte,
// without a build.
TEST(RenderSession, SavedStructureRendersTheSameImage) {
    const std::string scene = (kScenes / "objects.scene").string();
    for (const char* accel : {"bvh", "kd-restart"}) {
        SCOPED_TRACE(accel);
        const fs::path file = outputDir() / (std::string(accel) + ".vkacc");
        const fs::path built = outputDir() / (std::string("objects-built-") + accel + ".png");
        const fs::path loaded = outputDir() / (std::string("objects-loaded-") + accel + ".png");
        render::RenderRequest save = request(accel, 64, 48, built);
        save.saveAccel = file;
        const render::RenderReport saved = render::RenderSession(std::move(save)).render(scene).report;
        ASSERT_TRUE(saved.accelFile);
        EXPECT_FALSE(saved.accelFile->loaded);
        render::RenderRequest load = request(accel, 64, 48, loaded);
        load.loadAccel = file;
        const render::RenderReport read = render::RenderSession(std::move(load)).render(scene).report;
        ASSERT_TRUE(read.accelFile);
        EXPECT_TRUE(read.accelFile->loaded);
        EXPECT_EQ(read.buildMs, 0.0) << "nothing built";
        const std::string a = fileBytes(built), b = fileBytes(loaded);
        EXPECT_FALSE(a.empty());
        EXPECT_EQ(a, b);
    }
}

// The scenes of one session share the device's pipelines: a second scene that needs the same
// kernel with the same features creates none, and renders the same image.
TEST(RenderSession, ScenesShareThePipelines) {
    const fs::path copy = outputDir() / "cornell-again.scene";
    fs::copy_file(kScenes / "cornell.scene", copy, fs::copy_options::overwrite_existing);
    render::RenderSession session(request("bvh", 48, 32));
    const render::SceneRender first = session.render((kScenes / "cornell.scene").string());
    const render::SceneRender second = session.render(copy.string());
    ASSERT_TRUE(first.report.gpu && second.report.gpu);
    EXPECT_GT(first.report.gpu->pipelinesCreated, 0u);
    EXPECT_EQ(second.report.gpu->pipelinesCreated, 0u);
    EXPECT_EQ(first.frame.color, second.frame.color);
    // Two scenes of a session never write the same image.
    EXPECT_THROW(session.render((kScenes / "cornell.scene").string()), Error);
}

void expectRefused(const fs::path& scene, const std::string& cause) {
    SCOPED_TRACE(scene.string());
    render::RenderSession session(request("bvh", 16, 16));
    try {
        session.render(scene.string());
        ADD_FAILURE() << "rendered";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(cause), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find(scene.filename().string()), std::string::npos) << e.what();
    }
}

TEST(RenderSession, RefusesAnUnrenderableScene) {
    expectRefused(kCliData / "no_camera.scene", "the scene has no 'camera' line");
    expectRefused(kCliData / "no_triangles.scene", "the scene has no triangles (nothing to render)");
}

// A structure file is checked against the spec when the session starts, before any scene loads.
TEST(RenderSession, RefusesAStructureFileForAnotherAccelerator) {
    const fs::path file = outputDir() / "one-triangle-bvh.vkacc";
    render::RenderRequest save = request("bvh", 16, 16, outputDir() / "one-triangle.png");
    save.saveAccel = file;
    save.buildOnly = true;
    const render::SceneRender built = render::RenderSession(std::move(save)).render((kCliData / "one_triangle.scene").string());
    EXPECT_TRUE(built.report.buildOnly);
    EXPECT_TRUE(built.frame.color.empty());
    render::RenderRequest load = request("kd-stack", 16, 16);
    load.loadAccel = file;
    EXPECT_THROW(render::RenderSession(std::move(load)), Error);
}

}  // namespace
}  // namespace vkray
