// Primary rays of the `camera` line of a scene (docs/scene-format.md): through a point of the pixel
// (its centre, or this pass's sample, eye.w and w.w), x to the right and y down the image, the
// vertical field of view spanning the image height. The host supplies the orthonormal basis u, v, w
// (w points from the look-at centre back to the eye) and the tangents of the half fields of view in
// u.w and v.w. The divisions are IEEE-rounded (division.glsl), so that a device's approximate
// division does not move the ray: on grazing rays that decides hits (measured on an NVIDIA H200).
#ifndef VKRAY_CAMERA_GLSL
#define VKRAY_CAMERA_GLSL

#include "bindings.glsl"
#include "division.glsl"

vec3 primaryDirection(uvec2 pixel, uvec2 imageSize) {
    const vec2 half_ = vec2(imageSize) * 0.5;
    const float a = quotient(params.u.w * ((float(pixel.x) + params.eye.w) - half_.x), half_.x);
    const float b = quotient(params.v.w * (half_.y - (float(pixel.y) + params.w.w)), half_.y);
    return normalize(a * params.u.xyz + b * params.v.xyz - params.w.xyz);
}

#endif
