#include "render/scene_checks.h"

#include <vector>

#include "core/error.h"

namespace vkray::render {

void checkRenderable(const Scene& scene, const std::string& file) {
    if (!scene.hasCamera) throw Error(FileLoc{file}, "the scene has no 'camera' line");
    if (scene.triangles.empty()) throw Error(FileLoc{file}, "the scene has no triangles (nothing to render)");
}

std::optional<std::string> unlitMaterialsWarning(const Scene& scene, const std::string& file) {
    if (scene.lights.empty()) return std::nullopt;
    std::vector<bool> used(scene.materials.size(), false);
    for (const Triangle& t : scene.triangles)
        if (t.material < used.size()) used[t.material] = true;
    const glm::vec3 zero(0.0f);
    for (size_t i = 0; i < used.size(); ++i) {
        const Material& m = scene.materials[i];
        if (used[i] && (m.diffuse != zero || m.specular != zero || m.reflects() || m.refracts())) return std::nullopt;
    }
    return "in '" + file + "': no material of the scene's triangles has a diffuse or specular colour, a mirror or "
           "a refraction, so its " + std::to_string(scene.lights.size()) +
           " light(s) light nothing (set 'diffuse' before the geometry)";
}

}  // namespace vkray::render
