// Scene buffers and push constants of the render kernels; layouts from shared/gpu_layout.h.
#ifndef VKRAY_BINDINGS_GLSL
#define VKRAY_BINDINGS_GLSL

#include "shared/gpu_layout.h"

// The triangles (VKRAY_BINDING_TRIANGLES) are read only through their texel view: loadTriangle().
layout(std430, set = 0, binding = VKRAY_BINDING_NORMALS) readonly buffer Normals {
    GpuTriangleNormals triangleNormals[];
};
layout(std430, set = 0, binding = VKRAY_BINDING_MATERIALS) readonly buffer Materials {
    GpuMaterial materials[];
};
layout(std430, set = 0, binding = VKRAY_BINDING_LIGHTS) readonly buffer Lights {
    GpuLight lights[];
};
layout(std430, set = 0, binding = VKRAY_BINDING_PIXELS) writeonly buffer Pixels {
    GpuPixel pixels[];
};
// The same data as texel views, for the reads of every traversal step (gpu_layout.h, "Texel views").
layout(set = 0, binding = VKRAY_BINDING_TRIANGLE_TEXELS) uniform usamplerBuffer triangleTexels;
layout(set = 0, binding = VKRAY_BINDING_NODE_TEXELS) uniform usamplerBuffer nodeTexels;
layout(set = 0, binding = VKRAY_BINDING_INDEX_TEXELS) uniform usamplerBuffer indexTexels;
layout(set = 0, binding = VKRAY_BINDING_EXTRA_TEXELS) uniform usamplerBuffer extraTexels;

// Triangle `slot` of the triangle buffer, through its texel view.
GpuTriangle loadTriangle(uint slot) {
    const int k = int(3u * slot);
    const uvec4 a = texelFetch(triangleTexels, k), b = texelFetch(triangleTexels, k + 1),
                c = texelFetch(triangleTexels, k + 2);
    return GpuTriangle(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w, uintBitsToFloat(c.xyz), c.w);
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

#endif
