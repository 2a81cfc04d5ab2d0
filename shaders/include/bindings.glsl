// Scene buffers and push constants of the render kernels; layouts from shared/gpu_layout.h.
#ifndef VKRAY_BINDINGS_GLSL
#define VKRAY_BINDINGS_GLSL

#include "shared/gpu_layout.h"

// Written by every kernel; read back only by the resumable variant (render_main.glsl).
layout(std430, set = 0, binding = VKRAY_BINDING_PIXELS) buffer Pixels {
    GpuPixel pixels[];
};
// Everything the kernels read, through texel views (gpu_layout.h, "Texel views").
layout(set = 0, binding = VKRAY_BINDING_TRIANGLE_TEXELS) uniform usamplerBuffer triangleTexels;
layout(set = 0, binding = VKRAY_BINDING_NODE_TEXELS) uniform usamplerBuffer nodeTexels;
layout(set = 0, binding = VKRAY_BINDING_INDEX_TEXELS) uniform usamplerBuffer indexTexels;
layout(set = 0, binding = VKRAY_BINDING_EXTRA_TEXELS) uniform usamplerBuffer extraTexels;
layout(set = 0, binding = VKRAY_BINDING_NORMAL_TEXELS) uniform usamplerBuffer normalTexels;
layout(set = 0, binding = VKRAY_BINDING_MATERIAL_TEXELS) uniform usamplerBuffer materialTexels;
layout(set = 0, binding = VKRAY_BINDING_LIGHT_TEXELS) uniform usamplerBuffer lightTexels;

// Texel i of a view as four floats.
vec4 floatTexel(usamplerBuffer view, int i) { return uintBitsToFloat(texelFetch(view, i)); }

// Triangle `slot` of the triangle buffer.
GpuTriangle loadTriangle(uint slot) {
    const int k = int(uint(VKRAY_TRIANGLE_TEXELS) * slot);
    const uvec4 a = texelFetch(triangleTexels, k), b = texelFetch(triangleTexels, k + 1),
                c = texelFetch(triangleTexels, k + 2);
    return GpuTriangle(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w, uintBitsToFloat(c.xyz), c.w);
}

// The vertex normals of triangle `slot` (same slots as the triangles).
GpuTriangleNormals loadNormals(uint slot) {
    const int k = int(uint(VKRAY_NORMAL_TEXELS) * slot);
    return GpuTriangleNormals(floatTexel(normalTexels, k), floatTexel(normalTexels, k + 1),
                              floatTexel(normalTexels, k + 2));
}

GpuMaterial loadMaterial(uint index) {
    const int k = int(uint(VKRAY_MATERIAL_TEXELS) * index);
    const vec4 a = floatTexel(materialTexels, k), b = floatTexel(materialTexels, k + 1);
    return GpuMaterial(a.xyz, a.w, b.xyz, b.w, floatTexel(materialTexels, k + 2), floatTexel(materialTexels, k + 3),
                       floatTexel(materialTexels, k + 4), floatTexel(materialTexels, k + 5));
}

GpuLight loadLight(uint index) {
    const int k = int(uint(VKRAY_LIGHT_TEXELS) * index);
    const uvec4 a = texelFetch(lightTexels, k);
    return GpuLight(uintBitsToFloat(a.xyz), a.w, floatTexel(lightTexels, k + 1).xyz, 0.0);
}

layout(push_constant) uniform Push {
    GpuFrameParams params;
};

// What the scene needs; the host specialises these so unused code is compiled out.
layout(constant_id = VKRAY_SPEC_MAX_DEPTH) const int MAX_DEPTH = 5;
layout(constant_id = VKRAY_SPEC_HAS_REFLECTION) const bool HAS_REFLECTION = true;
layout(constant_id = VKRAY_SPEC_HAS_REFRACTION) const bool HAS_REFRACTION = true;
layout(constant_id = VKRAY_SPEC_HAS_POINT_LIGHTS) const bool HAS_POINT_LIGHTS = true;
layout(constant_id = VKRAY_SPEC_HAS_DIRECTIONAL_LIGHTS) const bool HAS_DIRECTIONAL_LIGHTS = true;
layout(constant_id = VKRAY_SPEC_HAS_SMOOTH_NORMALS) const bool HAS_SMOOTH_NORMALS = true;
layout(constant_id = VKRAY_SPEC_PRIMARY_AOVS) const bool PRIMARY_AOVS = true;

#endif
