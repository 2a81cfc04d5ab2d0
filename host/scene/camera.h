// Camera rays by the convention of docs/scene-format.md ("Camera rays"), in double precision for the
// CPU reference renderer and the tests. The GPU kernel computes the same formula in float
// (shaders/include/camera.glsl) from the basis this header builds.
#pragma once

#include <string>

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

// Unit direction through pixel (i, j) at `offset` within it ((0.5, 0.5): its centre); i = column
// from the left, j = row from the top.
glm::dvec3 primaryDirection(const CameraFrame& f, int i, int j, glm::vec2 offset = glm::vec2(0.5f));

// Where in its pixel sample s (0, 1, ...) of --spp goes: sample 0 at the centre, then Roberts's R2
// sequence from there, x_s = fract(1/2 + s / g), y_s = fract(1/2 + s / g^2) with g the plastic
// number (M. Roberts, "The Unreasonable Effectiveness of Quasirandom Sequences", 2018): every
// prefix is spread evenly over the pixel, so any sample count is stratified and --spp 1 is the
// centre ray. In float, as the GPU kernel gets it, so the CPU reference traces the same rays.
glm::vec2 pixelSampleOffset(int s);

// A camera that sees all of the scene's triangles: looking from `view`'s direction (eye minus
// centre) at the centre of the triangles' bounds, with `view`'s up and fovy, as near as the sphere
// around the bounds still fits in the field of view, with a margin of a twentieth. The field is the
// vertical one of `view`'s fovy, or the horizontal one where scene.width / scene.height makes it
// narrower (a portrait image), so the whole object is in any landscape image. `view` unchanged
// when the scene has no triangles. Throws vkray::Error for a degenerate `view`.
Camera fitCamera(const Scene& scene, const Camera& view);

// The camera of a view other than the scene's own (`vkray render --view`, `vkray bench --view`):
//   "scene"                      the scene's camera, unchanged;
//   "fit"                        fitCamera from the scene camera's direction: all of the scene in view;
//   "close"                      a close-up where most camera rays hit: looking at the centre of the
//                                triangles' bounds from the scene camera's direction, near enough
//                                that the vertical field of view spans half the bounds' diagonal
//                                (never nearer than that diagonal's half from the centre);
//   "EX,EY,EZ,CX,CY,CZ[,FOVY]"   eye, look-at centre and optionally fovy in degrees, the scene's up;
//   "EX,EY,EZ,CX,CY,CZ,UX,UY,UZ,FOVY"  all of a scene file's camera line (eye, centre, up, fovy).
// Positions are world coordinates, like the scene file's.
// Throws vkray::Error naming `option` for any other text, a non-finite number or a degenerate camera.
Camera viewCamera(const Scene& scene, const std::string& view, const std::string& option = "--view");

}  // namespace vkray
