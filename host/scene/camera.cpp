#include "scene/camera.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "scene/text_input.h"

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

glm::dvec3 primaryDirection(const CameraFrame& f, int i, int j, glm::vec2 offset) {
    const double halfW = f.width / 2.0, halfH = f.height / 2.0;
    const double a = f.tanX * ((i + double(offset.x)) - halfW) / halfW;
    const double b = f.tanY * (halfH - (j + double(offset.y))) / halfH;
    return glm::normalize(a * f.u + b * f.v - f.w);
}

glm::vec2 pixelSampleOffset(int s) {
    constexpr double g = 1.32471795724474602596;  // the plastic number: g^3 = g + 1
    const double x = 0.5 + double(s) / g, y = 0.5 + double(s) / (g * g);
    return glm::vec2(float(x - std::floor(x)), float(y - std::floor(y)));
}

namespace {

struct Bounds {
    glm::dvec3 centre;
    double radius;  // half the diagonal: the sphere around the box
};

std::optional<Bounds> triangleBounds(const Scene& scene) {
    if (scene.triangles.empty()) return std::nullopt;
    glm::vec3 lo(std::numeric_limits<float>::infinity()), hi(-std::numeric_limits<float>::infinity());
    for (const Triangle& t : scene.triangles)
        for (const glm::vec3& p : {t.p0, t.p1, t.p2}) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
    return Bounds{0.5 * (glm::dvec3(lo) + glm::dvec3(hi)), 0.5 * glm::length(glm::dvec3(hi) - glm::dvec3(lo))};
}

// `view` moved to look at `b`'s centre from `distance`, along its own direction.
Camera lookingAt(const Camera& view, const Bounds& b, double distance) {
    const CameraFrame f = makeCameraFrame(view, 1, 1);  // validates the camera
    Camera c = view;
    c.center = glm::vec3(b.centre);
    c.eye = glm::vec3(b.centre + f.w * std::max(distance, 1e-6));
    return c;
}

Camera closeUpCamera(const Scene& scene) {
    const std::optional<Bounds> b = triangleBounds(scene);
    if (!b) return scene.camera;
    const double tanY = makeCameraFrame(scene.camera, 1, 1).tanY;
    return lookingAt(scene.camera, *b, std::max(0.5 * b->radius / tanY, b->radius));
}

Camera explicitCamera(const Scene& scene, const std::string& text, const std::string& option) {
    const std::string usage =
        option + " '" + text + "': expected scene, close, fit, EX,EY,EZ,CX,CY,CZ[,FOVY] or EX,EY,EZ,CX,CY,CZ,UX,UY,UZ,FOVY";
    const std::optional<std::vector<double>> numbers = parseRealList(text);
    if (!numbers) throw Error(usage);
    const std::vector<double>& v = *numbers;
    if (v.size() != 6 && v.size() != 7 && v.size() != 10) throw Error(usage);
    // Eye and centre are world positions, like the scene file's: into its local frame in double.
    Camera c = scene.camera;
    c.eye = glm::vec3(glm::dvec3(v[0], v[1], v[2]) - scene.origin);
    c.center = glm::vec3(glm::dvec3(v[3], v[4], v[5]) - scene.origin);
    if (v.size() == 7) c.fovyDegrees = float(v[6]);
    if (v.size() == 10) {  // the scene file's camera line: up too
        c.up = glm::vec3(float(v[6]), float(v[7]), float(v[8]));
        c.fovyDegrees = float(v[9]);
    }
    try {
        makeCameraFrame(c, 1, 1);
    } catch (const Error& e) {
        throw Error(option + " '" + text + "': " + e.what());
    }
    return c;
}

}  // namespace

Camera fitCamera(const Scene& scene, const Camera& view) {
    const std::optional<Bounds> b = triangleBounds(scene);
    if (!b) return view;
    const double tanY = makeCameraFrame(view, 1, 1).tanY;
    const double aspect = scene.height > 0 ? double(scene.width) / double(scene.height) : 1.0;
    const double halfAngle = std::atan(tanY * std::min(aspect, 1.0));
    // The sphere touches the cone of halfAngle at distance radius / sin(halfAngle) from its centre.
    constexpr double kMargin = 1.05;
    return lookingAt(view, *b, kMargin * b->radius / std::sin(halfAngle));
}

Camera viewCamera(const Scene& scene, const std::string& view, const std::string& option) {
    if (view == "scene") return scene.camera;
    if (view == "fit") return fitCamera(scene, scene.camera);
    if (view == "close") return closeUpCamera(scene);
    return explicitCamera(scene, view, option);
}

}  // namespace vkray
