// The warning for a scene whose lights light nothing (render/scene_checks.h).
#include <gtest/gtest.h>

#include "render/scene_checks.h"
#include "scene/scene_parser.h"

namespace vkray::render {
namespace {

Scene parse(const std::string& text) { return parseSceneText(text, "t.scene", "."); }

const char* kTriangle = "camera 0 0 5 0 0 0 0 1 0 45\nvertex -1 -1 0\nvertex 1 -1 0\nvertex 0 1 0\n";

TEST(UnlitMaterials, LightsOverBlackDiffuseAreWarnedOnce) {
    const Scene dark = parse(std::string(kTriangle) + "point 0 0 3 1 1 1\ntri 0 1 2\n");
    const auto w = unlitMaterialsWarning(dark, "t.scene");
    ASSERT_TRUE(w.has_value());
    EXPECT_NE(w->find("in 't.scene': no material of the scene's triangles has a diffuse or specular colour"),
              std::string::npos)
        << *w;
    EXPECT_NE(w->find("its 1 light(s) light nothing"), std::string::npos) << *w;
}

TEST(UnlitMaterials, AnyLitMaterialOrNoLightIsNoWarning) {
    for (const char* material : {"diffuse 0.5 0.5 0.5\n", "specular 0.2 0.2 0.2\n"})
        EXPECT_FALSE(unlitMaterialsWarning(parse(std::string(kTriangle) + "point 0 0 3 1 1 1\n" + material + "tri 0 1 2\n"),
                                           "t.scene"))
            << material;
    // A lit material that no triangle uses does not count.
    EXPECT_TRUE(unlitMaterialsWarning(parse(std::string(kTriangle) + "point 0 0 3 1 1 1\ntri 0 1 2\ndiffuse 1 1 1\n"),
                                      "t.scene"));
    EXPECT_FALSE(unlitMaterialsWarning(parse(std::string(kTriangle) + "emission 1 0 0\ntri 0 1 2\n"), "t.scene"));
}

}  // namespace
}  // namespace vkray::render
