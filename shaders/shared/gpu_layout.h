// The one definition of every buffer layout, binding number and specialization constant shared by
// the host (C++) and the kernels (GLSL), after nvpro-samples' vk_mini_path_tracer `common.h`.
// Every struct is made of 16-byte slots (vec4/uvec4), so std430 and C++ agree without hand padding;
// the C++ half checks sizes and offsets with static_assert.
#ifndef VKRAY_GPU_LAYOUT_H
#define VKRAY_GPU_LAYOUT_H

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
namespace vkray::gpu {
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
}  // namespace vkray::gpu
#endif

// Plain macros, because GLSL layout qualifiers (binding, constant_id, local_size) take only
// literal-valued constant expressions after preprocessing.

// ---- Workgroup and tiling -------------------------------------------------------------------
#define VKRAY_WORKGROUP_X 8
#define VKRAY_WORKGROUP_Y 8
// One dispatch covers at most one tile, so no single dispatch runs long enough to trip a desktop
// GPU's watchdog (about 2 s on some drivers) even on large scenes.
#define VKRAY_TILE_SIZE 256

// ---- Descriptor bindings (set 0) -------------------------------------------------------------
#define VKRAY_BINDING_TRIANGLES 0  // GpuTriangle[]
#define VKRAY_BINDING_NORMALS 1    // GpuTriangleNormals[] (one dummy entry without smooth normals)
#define VKRAY_BINDING_MATERIALS 2  // GpuMaterial[]
#define VKRAY_BINDING_LIGHTS 3     // GpuLight[] (one dummy entry without lights)
#define VKRAY_BINDING_PIXELS 4     // GpuPixel[], one batch of tiles
#define VKRAY_BINDING_COUNT 5

// ---- Specialization constants: what the scene does not need is compiled out --------------------
#define VKRAY_SPEC_MAX_DEPTH 0              // int: maxdepth; also sizes the ray stack
#define VKRAY_SPEC_HAS_REFLECTION 1         // bool: some material reflects (or refracts: Fresnel)
#define VKRAY_SPEC_HAS_REFRACTION 2         // bool: some material transmits
#define VKRAY_SPEC_HAS_POINT_LIGHTS 3       // bool
#define VKRAY_SPEC_HAS_DIRECTIONAL_LIGHTS 4 // bool
#define VKRAY_SPEC_HAS_SMOOTH_NORMALS 5     // bool
#define VKRAY_SPEC_COUNT 6

// ---- Light types (GpuLight.vectorType.w) -------------------------------------------------------
#define VKRAY_LIGHT_POINT 0
#define VKRAY_LIGHT_DIRECTIONAL 1

#ifdef __cplusplus
namespace vkray::gpu {
struct GpuTriangle {    // 48 bytes
    vec4 p0Material;    // xyz = p0, w = material index (uintBitsToFloat)
    vec4 p1Original;    // xyz = p1, w = original triangle index (uintBitsToFloat)
    vec4 p2;            // xyz = p2, w unused
};
struct GpuTriangleNormals {  // 48 bytes: unit vertex normals, w unused
    vec4 n0, n1, n2;
};
struct GpuMaterial {        // 96 bytes
    vec4 ambientShininess;  // rgb = ambient, w = shininess
    vec4 diffuseIor;        // rgb = diffuse, w = index of refraction
    vec4 specular;          // rgb, w unused
    vec4 emission;          // rgb, w unused
    vec4 reflect;           // rgb mirror weight, w unused
    vec4 transmit;          // rgb transmission weight, w unused
};
struct GpuLight {           // 32 bytes
    vec4 vectorType;        // xyz = position (point) or direction towards the light; w = type
    vec4 color;             // rgb, w unused
};
struct GpuPixel {           // 32 bytes
    vec4 colorDepth;        // rgb = radiance, w = primary-hit t (+inf on a miss)
    vec4 normalPrim;        // xyz = primary shading normal, w = triangle index (intBitsToFloat), -1 = miss
};
// Push constants: 112 bytes, under the 128 every Vulkan device guarantees.
struct GpuFrameParams {
    vec4 eye;          // xyz eye, w unused
    vec4 u;            // xyz camera u, w = tanX
    vec4 v;            // xyz camera v, w = tanY
    vec4 w;            // xyz camera w (points backwards), w unused
    vec4 attenuation;  // xyz = constant, linear, quadratic
    uvec4 imageTile;   // x, y = image width, height; z, w = this tile's origin in pixels
    uvec4 counts;      // x = triangles, y = lights, z = first GpuPixel of this tile, w = tile width
};

static_assert(sizeof(GpuTriangle) == 48 && offsetof(GpuTriangle, p2) == 32);
static_assert(sizeof(GpuTriangleNormals) == 48);
static_assert(sizeof(GpuMaterial) == 96 && offsetof(GpuMaterial, transmit) == 80);
static_assert(sizeof(GpuLight) == 32 && offsetof(GpuLight, color) == 16);
static_assert(sizeof(GpuPixel) == 32 && offsetof(GpuPixel, normalPrim) == 16);
static_assert(sizeof(GpuFrameParams) == 112 && offsetof(GpuFrameParams, imageTile) == 80 &&
              offsetof(GpuFrameParams, counts) == 96);
}  // namespace vkray::gpu

#else  // GLSL

struct GpuTriangle { vec4 p0Material; vec4 p1Original; vec4 p2; };
struct GpuTriangleNormals { vec4 n0; vec4 n1; vec4 n2; };
struct GpuMaterial {
    vec4 ambientShininess; vec4 diffuseIor; vec4 specular; vec4 emission; vec4 reflect; vec4 transmit;
};
struct GpuLight { vec4 vectorType; vec4 color; };
struct GpuPixel { vec4 colorDepth; vec4 normalPrim; };
struct GpuFrameParams {
    vec4 eye; vec4 u; vec4 v; vec4 w; vec4 attenuation; uvec4 imageTile; uvec4 counts;
};

#endif
#endif  // VKRAY_GPU_LAYOUT_H
