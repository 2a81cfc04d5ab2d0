// The large scenes of scenes/: the real meshes (fetched by scripts/fetch-scenes.sh into
// scenes/meshes/, skipped with a note when absent) and the procedural scaling scenes of
// scenes/scaling/. Each loads with the triangle count docs/scenes.md quotes, stands on its floor
// and is framed by its camera. Loading only: rendering them needs an acceleration structure.
#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "scene/camera.h"
#include "scene/generators.h"
#include "scene/scene_parser.h"
#include "scene_test_util.h"

namespace vkray {
namespace {

namespace fs = std::filesystem;
using test::Box;
using test::expectFramed;

fs::path scenesDir() { return fs::path(VKRAY_SOURCE_DIR) / "scenes"; }

// The triangles after the first two (the floor) make the object.
Box objectBox(const Scene& s) {
    Box box;
    for (size_t i = 2; i < s.triangles.size(); ++i)
        for (const glm::vec3& p : {s.triangles[i].p0, s.triangles[i].p1, s.triangles[i].p2}) box.add(p);
    return box;
}

struct MeshScene {
    const char* scene;
    const char* mesh;  // in scenes/meshes/
    size_t meshTriangles;
};

// The counts of docs/scenes.md.
const MeshScene kMeshScenes[] = {
    {"bunny", "bunny.obj", 69666},
    {"armadillo", "armadillo.off", 52000},
    {"dragon", "ChineseDragon-10kv.off", 19994},
    {"elephant", "elephant.off", 5558},
    {"refined-elephant", "refined_elephant.off", 88928},
    {"diplodocus", "diplodocus.off", 47960},
};

TEST(MeshScenes, LoadStandOnTheFloorAndAreFramed) {
    for (const MeshScene& m : kMeshScenes) {
        SCOPED_TRACE(m.scene);
        if (!fs::exists(scenesDir() / "meshes" / m.mesh))
            GTEST_SKIP() << "scenes/meshes/" << m.mesh << " absent: run scripts/fetch-scenes.sh";
        const Scene s = loadScene(scenesDir() / (std::string(m.scene) + ".scene"));
        ASSERT_EQ(s.triangles.size(), m.meshTriangles + 2);  // + the floor
        EXPECT_TRUE(s.hasCamera);
        EXPECT_GE(s.lights.size(), 2u);
        const Box box = objectBox(s);
        EXPECT_NEAR(box.lo.y, 0.0, 1e-3) << "the mesh should stand on the floor (y = 0)";
        EXPECT_GT(box.hi.y - box.lo.y, 0.5);
        EXPECT_LT(box.hi.y - box.lo.y, 1.5);
        expectFramed(s, box);
    }
}

TEST(ScalingScenes, LoadWithTheGeneratorsCountsAndAreFramed) {
    int found = 0;
    for (const auto& entry : fs::directory_iterator(scenesDir() / "scaling")) {
        if (entry.path().extension() != ".scene") continue;
        SCOPED_TRACE(entry.path().filename().string());
        ++found;
        const Scene s = loadScene(entry.path());
        // name = KIND-COUNT, e.g. terrain-100k; the count is what generatedTriangleCount makes of it.
        const std::string stem = entry.path().stem().string();
        const auto kind = generatorKindFromName(stem.substr(0, stem.find('-')));
        ASSERT_TRUE(kind);
        const std::string count = stem.substr(stem.find('-') + 1);
        const int64_t asked = std::stoll(count) * (count.back() == 'k' ? 1000 : count.back() == 'm' ? 1000000 : 1);
        EXPECT_EQ(int64_t(s.triangles.size()), generatedTriangleCount({*kind, asked, 1}) + 2);
        expectFramed(s, objectBox(s));
    }
    EXPECT_EQ(found, 18);  // spheres, soup, terrain x 10k, 100k, 1m, 2m, 4m, 16m
}

}  // namespace
}  // namespace vkray
