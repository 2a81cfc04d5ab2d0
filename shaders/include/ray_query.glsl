// The `rayquery` accelerator: the device driver's own acceleration structure and traversal
// (GL_EXT_ray_query over VK_KHR_acceleration_structure; in hardware on GPUs with ray-tracing units).
// The host builds the structure over the triangle buffer in slot order (gpu/driver_structure.h), so
// a hit's primitive index is its triangle slot and the shading reads it as for any accelerator.
// The slots are in a Morton order; each triangle's identity is its GpuTriangle.original, which the
// shading reads (shading.glsl). Hit.original, which only vkray's tie rule (beats) needs, is left
// unset: the driver breaks its ties itself, and a load per ray, shadow rays included, would buy
// nothing.
// The driver's triangle test and tie rule are its own, not Woop, Benthin and Wald's watertight test
// (triangle.glsl) and beats(): where a ray grazes an edge or meets two triangles at the same t, its
// answer may differ from brute force's (docs/stability.md has the measured agreement).
#ifndef VKRAY_RAY_QUERY_GLSL
#define VKRAY_RAY_QUERY_GLSL

#include "accelerator.glsl"
#include "bindings.glsl"
#include "triangle.glsl"

layout(set = 0, binding = VKRAY_BINDING_SCENE_STRUCTURE) uniform accelerationStructureEXT sceneStructure;

// One query with `flags` over (0, tmax). The geometry is opaque, so the driver commits every
// candidate itself and rayQueryProceedEXT returns false at once: the loop has one pass.
Hit driverTrace(vec3 origin, vec3 dir, float tmax, const uint flags) {
    rayQueryEXT q;
    rayQueryInitializeEXT(q, sceneStructure, gl_RayFlagsOpaqueEXT | flags, 0xFF, origin, 0.0, dir, tmax);
    while (rayQueryProceedEXT(q)) {
    }
    Hit h = noHit(tmax);
    if (rayQueryGetIntersectionTypeEXT(q, true) == gl_RayQueryCommittedIntersectionTriangleEXT) {
        h.t = rayQueryGetIntersectionTEXT(q, true);
        h.uv = rayQueryGetIntersectionBarycentricsEXT(q, true);
        h.triangle = rayQueryGetIntersectionPrimitiveIndexEXT(q, true);
    }
    return h;
}

Hit traceClosest(vec3 origin, vec3 dir, float tmax) { return driverTrace(origin, dir, tmax, gl_RayFlagsNoneEXT); }

// Shadow rays: the first hit the driver finds ends the query.
bool traceAny(vec3 origin, vec3 dir, float tmax) {
    return driverTrace(origin, dir, tmax, gl_RayFlagsTerminateOnFirstHitEXT).triangle >= 0;
}

#endif
