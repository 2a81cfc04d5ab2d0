// The one definition of every buffer layout, binding number and specialization constant shared by
// the host (C++) and the kernels (GLSL), after nvpro-samples' vk_mini_path_tracer `common.h`.
// Every struct is made of 16-byte slots (vec4, or vec3 + one 4-byte scalar), so std430 and C++ agree
// without hand padding;
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
#define VKRAY_BINDING_PIXELS 0       // GpuPixel[] or GpuPixelColor[] + GpuTileCounts[], one batch of tiles
// The resumable variant's saved pixels (VKRAY_SPEC_RESUMABLE; a one-element dummy otherwise):
#define VKRAY_BINDING_RESUME 1       // GpuPixelResume[], one per pixel of the dispatch
#define VKRAY_BINDING_RESUME_RAYS 2  // GpuPendingRay[], MAX_DEPTH per pixel: the pending-ray stacks
#define VKRAY_STORAGE_BINDING_COUNT 3  // bindings 0-2 are storage buffers, the rest texel views
// Texel views: everything the kernels read, as uniform texel buffers. On llvmpipe (Mesa 22) a
// storage-buffer load at a per-invocation address is a loop over the SIMD lanes with a
// bounds-checked branch per 32-bit word, while a texel fetch loads one 16-byte texel per lane and
// transposes (docs/performance.md, "What lavapipe charges for").
// Being read only through views, an array is bounded by maxTexelBufferElements texels per view (128
// Mi on lavapipe and most GPUs: 2 GiB of 16-byte texels), not by maxStorageBufferRange (128 MiB on
// lavapipe), and each binding is an array of VKRAY_TEXEL_VIEWS views, each its own buffer, over
// which a longer array is split (VKRAY_SPEC_TEXEL_VIEW_BITS): up to 16 GiB of 16-byte texels.
#define VKRAY_TEXEL_VIEWS 8
#define VKRAY_BINDING_TRIANGLE_TEXELS 3  // the triangles as RGBA32UI: texels 3k..3k+2 = GpuTriangle k
// The acceleration structure, in the layout its own header defines (shared/bvh_layout.h,
// shared/kd_layout.h); a view the structure does not use holds a one-texel dummy.
#define VKRAY_BINDING_NODE_TEXELS 4      // the accelerator's nodes (GpuAccelData::nodeTexelBytes a texel)
#define VKRAY_BINDING_INDEX_TEXELS 5     // the accelerator's triangle indices as R32UI
#define VKRAY_BINDING_EXTRA_TEXELS 6     // the accelerator's extra data as RGBA32UI (kd-backtrack: parent links and node boxes)
#define VKRAY_BINDING_NORMAL_TEXELS 7    // GpuTriangleNormals[] as RGBA32UI, 3 texels each (one dummy without smooth normals)
#define VKRAY_BINDING_MATERIAL_TEXELS 8  // GpuMaterial[] as RGBA32UI, 6 texels each
#define VKRAY_BINDING_LIGHT_TEXELS 9     // GpuLight[] as RGBA32UI, 2 texels each (one dummy without lights)
#define VKRAY_BINDING_COUNT 10
// The rayquery kernel's alone, after the others: the driver's top-level acceleration structure
// (gpu/driver_structure.h). The other kernels do not declare it, so they need no ray tracing.
#define VKRAY_BINDING_SCENE_STRUCTURE 10
// Texels (16 bytes) per element of the texel views of the scene's structs below.
#define VKRAY_TRIANGLE_TEXELS 3
#define VKRAY_NORMAL_TEXELS 3
#define VKRAY_MATERIAL_TEXELS 6
#define VKRAY_LIGHT_TEXELS 2

// ---- Specialization constants: what the scene does not need is compiled out --------------------
#define VKRAY_SPEC_MAX_DEPTH 0              // int: maxdepth; also sizes the ray stack
#define VKRAY_SPEC_HAS_REFLECTION 1         // bool: some material reflects (or refracts: Fresnel)
#define VKRAY_SPEC_HAS_REFRACTION 2         // bool: some material transmits
#define VKRAY_SPEC_HAS_POINT_LIGHTS 3       // bool
#define VKRAY_SPEC_HAS_DIRECTIONAL_LIGHTS 4 // bool
#define VKRAY_SPEC_HAS_SMOOTH_NORMALS 5     // bool
// bool: count nodes, leaves and triangle tests per pixel (GpuPixel) — the statistics variant; off,
// the counting is compiled out so timing runs pay nothing for it.
#define VKRAY_SPEC_COUNT_TRAVERSAL 6
// uint: triangles the resumable variant's leaf loop tests per iteration, 1 or 4 (leaf_triangles.glsl;
// the plain kernel always tests 1): 1 unless the structure has a leaf of more than
// VKRAY_SINGLE_SLOT_LEAF_LIMIT triangles.
#define VKRAY_SPEC_LEAF_SLOTS 7
// (Not a specialization constant: the resumable variant of render_main.glsl, "Resumable pixels", in
// which a pixel whose loops run out of the driver's loop budget saves where it is
// (VKRAY_BINDING_RESUME, _RESUME_RAYS) and goes on in the next dispatch, is a SPIR-V of its own,
// compiled with VKRAY_RESUMABLE_KERNEL defined. In the plain one such a pixel is flagged
// VKRAY_PIXEL_CUT_SHORT.)
// The resumable variant's own loop budget: passes of a subgroup through its loops' headers per
// dispatch, below llvmpipe's 65535 to leave room for the few fixed-count loops it does not count.
#define VKRAY_RESUMABLE_LOOP_BUDGET 60000u
// bool: write the primary hit's depth, normal and triangle identity (GpuPixel); off when nothing
// reads them (a render that saves no AOV, a timing run), so the kernel stores 7 words a pixel, not 16.
#define VKRAY_SPEC_PRIMARY_AOVS 8
// int: kd-shortstack's stack entries (kd_stack.glsl; tuning option kd-short-stack, default VKRAY_KD_SHORT_STACK_SIZE).
#define VKRAY_SPEC_KD_SHORT_STACK 9
// int: log2 of the texels of one view when texel arrays are split over several views of a binding
// (VKRAY_TEXEL_VIEWS; read by the kernels' VKRAY_SPLIT_TEXEL_VIEWS variant, bindings.glsl); 0 when
// every array fits one view (the usual variant).
#define VKRAY_SPEC_TEXEL_VIEW_BITS 10
// uint: pixels an invocation of the plain kernel renders, one in each of as many bands of a tile's
// 8x8 block rows (render_main.glsl, "Pixels per invocation"), 1 to VKRAY_MAX_PIXELS_PER_INVOCATION: more than one
// on CPU devices only. The host dispatches that many times fewer workgroup rows; the resumable
// variant renders one.
#define VKRAY_SPEC_PIXELS_PER_INVOCATION 11
#define VKRAY_MAX_PIXELS_PER_INVOCATION 4
#define VKRAY_SPEC_COUNT 12
#define VKRAY_SINGLE_SLOT_LEAF_LIMIT 128

// ---- GpuPixel.flags ------------------------------------------------------------------------------
// A loop of the kernel ended before its bound: the driver cut it short (llvmpipe/lavapipe stops
// every loop of an invocation once all its loops together ran 65535 iterations), or the
// per-pixel ray cap was reached. The pixel is wrong; the host reports it instead of writing it.
#define VKRAY_PIXEL_CUT_SHORT 1u
// Resumable variant: the pixel ran out of loop budget and saved where it is; dispatch it again.
#define VKRAY_PIXEL_UNFINISHED 2u

// ---- GpuPixelResume.stage -------------------------------------------------------------------------
#define VKRAY_RESUME_FRESH 0u   // nothing done yet (the host zero-fills the records)
#define VKRAY_RESUME_RAYS 1u    // the pending rays are saved; the top one is traced next
#define VKRAY_RESUME_LIGHTS 2u  // the ray at stack[stackTop] hit; its lights from `light` on are next
#define VKRAY_RESUME_DONE 3u    // the pixel's GpuPixel is final

// ---- Light types (GpuLight.type) -------------------------------------------------------
#define VKRAY_LIGHT_POINT 0
#define VKRAY_LIGHT_DIRECTIONAL 1

// Integers get integer slots (vec3 + uint), never float bit patterns: a small int stored in a
// float's bits is a denormal, and a driver that flushes denormals (seen on lavapipe) turns it to 0.
#ifdef __cplusplus
namespace vkray::gpu {
using vec3 = glm::vec3;
using uint = uint32_t;
#define VKRAY_STRUCT(name) struct alignas(16) name
#else
#define VKRAY_STRUCT(name) struct name
#endif

VKRAY_STRUCT(GpuTriangle) {  // 48 bytes
    vec3 p0;
    uint material;  // index into the materials buffer
    vec3 p1;
    uint original;  // triangle identity (docs/scene-format.md) for AOVs and statistics
    vec3 p2;
    uint pad0;
};

VKRAY_STRUCT(GpuTriangleNormals) {  // 48 bytes: unit vertex normals, w unused
    vec4 n0;
    vec4 n1;
    vec4 n2;
};

VKRAY_STRUCT(GpuMaterial) {  // 96 bytes
    vec3 ambient;
    float shininess;
    vec3 diffuse;
    float ior;        // index of refraction of the inside
    vec4 specular;    // rgb, w unused
    vec4 emission;    // rgb, w unused
    vec4 reflect;     // rgb mirror weight, w unused
    vec4 transmit;    // rgb transmitted weight, w unused
};

VKRAY_STRUCT(GpuLight) {  // 32 bytes
    vec3 vector;  // position (point) or direction towards the light (directional)
    uint type;    // VKRAY_LIGHT_POINT or VKRAY_LIGHT_DIRECTIONAL
    vec3 color;
    float pad0;
};

// Where a pixel of the resumable variant stopped (render_main.glsl, "Resumable pixels").
VKRAY_STRUCT(GpuPixelResume) {  // 80 bytes
    vec3 color;         // stage LIGHTS: the interrupted hit's shading so far
    uint stage;         // VKRAY_RESUME_*
    vec3 hitTuv;        // stage LIGHTS: the hit (t, u, v) being shaded
    int hitTriangle;
    vec3 walkTuv;       // the interrupted traversal (brute force, BVH): its best hit so far
    int walkTriangle;
    uint stackTop;      // pending rays (GpuPendingRay, VKRAY_BINDING_RESUME_RAYS)
    uint rays;          // closest-hit rays traced so far
    uint light;         // stage LIGHTS: the next light
    uint walkSlot;      // where it goes on (brute force: next triangle; BVH: bvhResumeWord); 0 = none
    uint walkOriginal;
    uint hitOriginal;
    uint walkSteps;     // BVH: its node steps so far, against VKRAY_BVH_MAX_ITERATIONS
    uint pad0;
};

VKRAY_STRUCT(GpuPendingRay) {  // 48 bytes
    vec3 origin;
    int depth;  // primary rays have depth 1
    vec3 dir;
    float pad0;
    vec3 weight;  // product of the weights along the path
    float pad1;
};

VKRAY_STRUCT(GpuPixel) {  // 64 bytes
    vec3 color;   // radiance
    float depth;  // primary-hit t, +inf on a miss
    vec3 normal;  // primary shading normal, 0 on a miss
    int primId;   // triangle identity of the primary hit, -1 on a miss
    // depth, normal and primId are written only when VKRAY_SPEC_PRIMARY_AOVS is on
    uint flags;   // VKRAY_PIXEL_* bits
    uint rays;    // closest-hit rays traced for this pixel (camera and secondary)
    uint shadowRays;  // any-hit rays traced for this pixel
    // Traversal work of all the pixel's rays; 0 unless VKRAY_SPEC_COUNT_TRAVERSAL is on.
    uint nodes;      // nodes visited
    uint leaves;     // leaves visited
    uint triangles;  // ray-triangle tests
    // The walk's own count: kd-restart's restarts and kd-backtrack's climbs; for the packet walks
    // (bvh-packet, kd-packet), the lane's idle steps: steps its packet took that its ray sat out.
    uint walkEvents;
    uint capped;     // rays ended by a traversal's iteration cap (reported, never hidden)
};

// The compact record (render_main.glsl, "Pixel records"): what the plain kernel writes where the host
// reads neither AOVs nor traversal counters, four pixels to a 64-byte cache line instead of one. A
// batch holds its tiles' GpuPixelColor records at the indices their GpuPixel records would have,
// in 16-byte units (so the first quarter of the buffer), then one GpuTileCounts a tile: the ray
// counts the full records carry per pixel, summed over the tile by the kernel. The sums are 64-bit,
// low and high words (a tile's shadow rays can pass 2^32: 65,536 pixels, each up to 65,536 rays
// and a shadow ray a light for each).
VKRAY_STRUCT(GpuPixelColor) {  // 16 bytes
    vec3 color;
    uint flags;  // VKRAY_PIXEL_* bits
};
VKRAY_STRUCT(GpuTileCounts) {  // 32 bytes, two 16-byte units; the host zeroes it before the tile's dispatch
    uint raysLow, raysHigh;
    uint shadowRaysLow, shadowRaysHigh;
    uint cappedLow, cappedHigh;
    uint unused0, unused1;
};

// Push constants: 128 bytes, the most every Vulkan device guarantees.
VKRAY_STRUCT(GpuFrameParams) {
    vec4 eye;          // xyz eye, w = the camera ray's x within its pixel (0.5: the centre)
    vec4 u;            // xyz camera u, w = tanX
    vec4 v;            // xyz camera v, w = tanY
    vec4 w;            // xyz camera w (points backwards), w = the camera ray's y within its pixel
    vec4 attenuation;  // xyz = constant, linear, quadratic
    uvec4 imageTile;   // x, y = image width, height; z, w = this tile's origin in pixels
    uvec4 counts;      // x = triangles, y = lights, z = first GpuPixel of this tile, w = tile row pitch
    vec3 background;   // the radiance of a ray that hits nothing
    uint tileCounts;   // compact records: this tile's GpuTileCounts (an index of GpuTileCounts[] over the pixel buffer)
};

#ifdef __cplusplus
static_assert(sizeof(GpuTriangle) == 48 && offsetof(GpuTriangle, material) == 12 &&
              offsetof(GpuTriangle, p1) == 16 && offsetof(GpuTriangle, original) == 28 &&
              offsetof(GpuTriangle, p2) == 32);
static_assert(sizeof(GpuTriangleNormals) == 48);
static_assert(sizeof(GpuMaterial) == 96 && offsetof(GpuMaterial, shininess) == 12 &&
              offsetof(GpuMaterial, diffuse) == 16 && offsetof(GpuMaterial, ior) == 28 &&
              offsetof(GpuMaterial, specular) == 32 && offsetof(GpuMaterial, transmit) == 80);
static_assert(sizeof(GpuLight) == 32 && offsetof(GpuLight, type) == 12 && offsetof(GpuLight, color) == 16);
static_assert(sizeof(GpuTriangle) == 16 * VKRAY_TRIANGLE_TEXELS && sizeof(GpuTriangleNormals) == 16 * VKRAY_NORMAL_TEXELS &&
              sizeof(GpuMaterial) == 16 * VKRAY_MATERIAL_TEXELS && sizeof(GpuLight) == 16 * VKRAY_LIGHT_TEXELS,
              "the texel views read these structs as whole RGBA32UI texels");
static_assert(sizeof(GpuPixel) == 64 && offsetof(GpuPixel, depth) == 12 &&
              offsetof(GpuPixel, normal) == 16 && offsetof(GpuPixel, primId) == 28 &&
              offsetof(GpuPixel, flags) == 32 && offsetof(GpuPixel, shadowRays) == 40 &&
              offsetof(GpuPixel, nodes) == 44 && offsetof(GpuPixel, capped) == 60);
static_assert(sizeof(GpuPixelColor) == 16 && offsetof(GpuPixelColor, flags) == 12 && sizeof(GpuTileCounts) == 32 &&
                  offsetof(GpuTileCounts, shadowRaysLow) == 8 && offsetof(GpuTileCounts, cappedLow) == 16,
              "compact records and tile counts share the pixel buffer's 16-byte units");
static_assert(sizeof(GpuPixelResume) == 80 && offsetof(GpuPixelResume, stage) == 12 &&
              offsetof(GpuPixelResume, hitTriangle) == 28 && offsetof(GpuPixelResume, walkTriangle) == 44 &&
              offsetof(GpuPixelResume, stackTop) == 48 && offsetof(GpuPixelResume, walkSlot) == 60 &&
              offsetof(GpuPixelResume, walkOriginal) == 64);
static_assert(sizeof(GpuPendingRay) == 48 && offsetof(GpuPendingRay, depth) == 12 &&
              offsetof(GpuPendingRay, dir) == 16 && offsetof(GpuPendingRay, weight) == 32);
static_assert(sizeof(GpuFrameParams) == 128 && offsetof(GpuFrameParams, imageTile) == 80 &&
              offsetof(GpuFrameParams, counts) == 96 && offsetof(GpuFrameParams, background) == 112 &&
              offsetof(GpuFrameParams, tileCounts) == 124);
}  // namespace vkray::gpu
#endif
#undef VKRAY_STRUCT

#endif  // VKRAY_GPU_LAYOUT_H
