// Camera rays by the convention of docs/scene-format.md ("Camera rays"), in double precision for the
// CPU reference renderer and the tests. The GPU kernel computes the same formula in float
// (shaders/include/camera.glsl) from the basis this header builds.
#pragma once

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace vkray {

struct CameraFrame {
    glm::dvec3 eye;
    glm::dvec3 u, v, w;  // w = normalize(eye - centre), u = normalize(cross(up, w)), v = cross(w, u)
    double tanX = 0.0, tanY = 0.0;
    int width = 0, height = 0;
};

// Throws vkray::Error when the camera is degenerate (eye == centre, up parallel to the view
// direction, fovy outside (0, 180)) or the image size is not positive.
CameraFrame makeCameraFrame(const Camera& cam, int width, int height);

// Unit direction through the centre of pixel (i, j); i = column from the left, j = row from the top.
glm::dvec3 primaryDirection(const CameraFrame& f, int i, int j);

}  // namespace vkray
