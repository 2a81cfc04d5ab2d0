#include "scene/camera.h"

#include <cmath>
#include <string>

#include "core/error.h"

namespace vkray {

CameraFrame makeCameraFrame(const Camera& cam, int width, int height) {
    if (width <= 0 || height <= 0)
        throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                    " is not positive");
    if (!(cam.fovyDegrees > 0.0f && cam.fovyDegrees < 180.0f))
        throw Error("camera fovy " + std::to_string(cam.fovyDegrees) +
                    " degrees is outside (0, 180)");
    CameraFrame f;
    f.eye = glm::dvec3(cam.eye);
    glm::dvec3 back = f.eye - glm::dvec3(cam.center);
    if (glm::length(back) == 0.0) throw Error("camera eye and look-at centre coincide");
    f.w = glm::normalize(back);
    glm::dvec3 side = glm::cross(glm::dvec3(cam.up), f.w);
    // A relative tolerance: `up` nearly parallel to the view direction leaves u undefined.
    if (glm::length(side) <= 1e-9 * glm::length(glm::dvec3(cam.up)) || glm::length(side) == 0.0)
        throw Error("camera up vector is parallel to the viewing direction");
    f.u = glm::normalize(side);
    f.v = glm::cross(f.w, f.u);
    f.tanY = std::tan(glm::radians(double(cam.fovyDegrees)) / 2.0);
    f.tanX = f.tanY * double(width) / double(height);
    f.width = width;
    f.height = height;
    return f;
}

glm::dvec3 primaryDirection(const CameraFrame& f, int i, int j) {
    const double halfW = f.width / 2.0, halfH = f.height / 2.0;
    const double a = f.tanX * ((i + 0.5) - halfW) / halfW;
    const double b = f.tanY * (halfH - (j + 0.5)) / halfH;
    return glm::normalize(a * f.u + b * f.v - f.w);
}

}  // namespace vkray
