// The checks of a loaded scene before anything is built for it. A scene is checked once: here that
// it can be rendered at all; on the device that its arrays fit (gpu::checkSceneFits), once the
// device is open.
#pragma once

#include <string>

#include "scene/scene.h"

namespace vkray::render {

// Refuses a scene that has nothing to render: no camera, or no triangles.
void checkRenderable(const Scene& scene, const std::string& file);

}  // namespace vkray::render
