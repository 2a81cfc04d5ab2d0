// Scene buffers and push constants of the render kernels; layouts from shared/gpu_layout.h.
#ifndef VKRAY_BINDINGS_GLSL
#define VKRAY_BINDINGS_GLSL

#include "shared/gpu_layout.h"

// Written by every kernel; read back only by the resumable variant (render_main.glsl).
layout(std430, set = 0, binding = VKRAY_BINDING_PIXELS) buffer Pixels {
    GpuPixel pixels[];
};
// Everything the kernels read, through texel views (gpu_layout.h, "Texel views"). Each binding is an
// array of VKRAY_TEXEL_VIEWS views. In the kernels' usual SPIR-V only view 0 is read: every array
// fits one view. An array longer than one view may be (the device's maxTexelBufferElements) is
// split over several of 2^TEXEL_VIEW_BITS texels each, read by the variant compiled with
// VKRAY_SPLIT_TEXEL_VIEWS defined, whose every fetch first chooses its view: a variant of its own
// because that choice, inlined at every fetch, nearly doubles the SPIR-V that the driver must
// translate before a specialization constant could fold it away.
//
// VKRAY_TEXEL_ARRAY(name, slot) declares binding `slot` as the views name##Views, name##Texel(i),
// its texel i, and name##FloatTexel(i), the same as four floats. The views are textures without a
// sampler (utextureBuffer): texelFetch needs none, and SPIR-V 1.6 deprecates a sampled image of a
// buffer (the validation layer warns of one on a Vulkan 1.4 device). The split variant chooses the
// view by a switch with constant indices: no descriptor indexing is needed from the device, and no
// loop spends lavapipe's budget.
#ifdef VKRAY_SPLIT_TEXEL_VIEWS
layout(constant_id = VKRAY_SPEC_TEXEL_VIEW_BITS) const int TEXEL_VIEW_BITS = 27;
#if VKRAY_TEXEL_VIEWS != 8
#error "the switch below names each of the 8 views"
#endif
#define VKRAY_TEXEL_FETCH(name)                                                                   \
    uvec4 name##Texel(int i) {                                                                    \
        const int at = i & ((1 << TEXEL_VIEW_BITS) - 1);                                          \
        switch (i >> TEXEL_VIEW_BITS) {                                                           \
            case 0: return texelFetch(name##Views[0], at);                                        \
            case 1: return texelFetch(name##Views[1], at);                                        \
            case 2: return texelFetch(name##Views[2], at);                                        \
            case 3: return texelFetch(name##Views[3], at);                                        \
            case 4: return texelFetch(name##Views[4], at);                                        \
            case 5: return texelFetch(name##Views[5], at);                                        \
            case 6: return texelFetch(name##Views[6], at);                                        \
            default: return texelFetch(name##Views[7], at);                                       \
        }                                                                                         \
    }
#else
#define VKRAY_TEXEL_FETCH(name) \
    uvec4 name##Texel(int i) { return texelFetch(name##Views[0], i); }
#endif
#define VKRAY_TEXEL_ARRAY(name, slot)                                                       \
    layout(set = 0, binding = slot) uniform utextureBuffer name##Views[VKRAY_TEXEL_VIEWS]; \
    VKRAY_TEXEL_FETCH(name)                                                                 \
    vec4 name##FloatTexel(int i) { return uintBitsToFloat(name##Texel(i)); }
VKRAY_TEXEL_ARRAY(triangle, VKRAY_BINDING_TRIANGLE_TEXELS)
VKRAY_TEXEL_ARRAY(node, VKRAY_BINDING_NODE_TEXELS)
VKRAY_TEXEL_ARRAY(index, VKRAY_BINDING_INDEX_TEXELS)
VKRAY_TEXEL_ARRAY(extra, VKRAY_BINDING_EXTRA_TEXELS)
VKRAY_TEXEL_ARRAY(normal, VKRAY_BINDING_NORMAL_TEXELS)
VKRAY_TEXEL_ARRAY(material, VKRAY_BINDING_MATERIAL_TEXELS)
VKRAY_TEXEL_ARRAY(light, VKRAY_BINDING_LIGHT_TEXELS)

// Triangle `slot` of the triangle buffer.
GpuTriangle loadTriangle(uint slot) {
    const int k = int(uint(VKRAY_TRIANGLE_TEXELS) * slot);
    const uvec4 a = triangleTexel(k), b = triangleTexel(k + 1), c = triangleTexel(k + 2);
    return GpuTriangle(uintBitsToFloat(a.xyz), a.w, uintBitsToFloat(b.xyz), b.w, uintBitsToFloat(c.xyz), c.w);
}

// The vertex normals of triangle `slot` (same slots as the triangles).
GpuTriangleNormals loadNormals(uint slot) {
    const int k = int(uint(VKRAY_NORMAL_TEXELS) * slot);
    return GpuTriangleNormals(normalFloatTexel(k), normalFloatTexel(k + 1), normalFloatTexel(k + 2));
}

GpuMaterial loadMaterial(uint index) {
    const int k = int(uint(VKRAY_MATERIAL_TEXELS) * index);
    const vec4 a = materialFloatTexel(k), b = materialFloatTexel(k + 1);
    return GpuMaterial(a.xyz, a.w, b.xyz, b.w, materialFloatTexel(k + 2), materialFloatTexel(k + 3),
                       materialFloatTexel(k + 4), materialFloatTexel(k + 5));
}

GpuLight loadLight(uint index) {
    const int k = int(uint(VKRAY_LIGHT_TEXELS) * index);
    const uvec4 a = lightTexel(k);
    return GpuLight(uintBitsToFloat(a.xyz), a.w, lightFloatTexel(k + 1).xyz, 0.0);
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
