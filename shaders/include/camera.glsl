// Primary rays by the convention of DESIGN.md ("Camera rays"); the basis comes from the host.
#ifndef VKRAY_CAMERA_GLSL
#define VKRAY_CAMERA_GLSL

vec3 primaryDirection(uvec2 pixel, uvec2 imageSize) {
    const vec2 half_ = vec2(imageSize) * 0.5;
    const float a = params.u.w * ((float(pixel.x) + 0.5) - half_.x) / half_.x;
    const float b = params.v.w * (half_.y - (float(pixel.y) + 0.5)) / half_.y;
    return normalize(a * params.u.xyz + b * params.v.xyz - params.w.xyz);
}

#endif
