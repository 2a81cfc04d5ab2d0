// The checks of a loaded scene before anything is built for it. A scene is checked once: here that
// it can be rendered at all; on the device that its arrays fit (gpu::checkSceneFits), once the
// device is open.
#pragma once

#include <optional>
#include <string>

#include "scene/scene.h"

namespace vkray::render {

// Refuses a scene that has nothing to render: no camera, or no triangles.
void checkRenderable(const Scene& scene, const std::string& file);

// Why the scene's lights light nothing, for one warning: it has lights, and no triangle's material
// has a diffuse or specular colour, a mirror or a refraction (CSE167's default material is black
// diffuse, so an OBJ without colours under `geo` renders a flat silhouette). Nothing otherwise.
std::optional<std::string> unlitMaterialsWarning(const Scene& scene, const std::string& file);

}  // namespace vkray::render
