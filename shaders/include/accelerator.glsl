// The two queries every accelerator include (brute_force.glsl, bvh_traversal.glsl, kd_stack.glsl,
// kd_restart.glsl, kd_backtrack.glsl) defines, declared here so that the kernel body and the
// shading can call them whatever the order of the includes. A kernel includes exactly one
// accelerator; both queries take t in (0, tmax).
#ifndef VKRAY_ACCELERATOR_GLSL
#define VKRAY_ACCELERATOR_GLSL

#include "trace_status.glsl"
#include "triangle.glsl"

// Closest hit in (0, tmax); ties in t go to the lowest triangle identity (beats(), triangle.glsl).
Hit traceClosest(vec3 origin, vec3 dir, float tmax);

// Whether anything lies on the ray in (0, tmax): shadow rays.
bool traceAny(vec3 origin, vec3 dir, float tmax);

// The closest hit of a pixel's ray: traceCamera for its camera ray where the kernel defines
// VKRAY_OWN_CAMERA_TRACE and one (the packet walks, whose packets pay only for rays that travel
// together), traceClosest otherwise. The lanes of a subgroup start their pixels together
// (render_main.glsl), so their camera rays reach traceCamera together. The resumable variant
// saves no packet's state between its dispatches: its camera rays walk as its other rays.
#ifdef VKRAY_OWN_CAMERA_TRACE
Hit traceCamera(vec3 origin, vec3 dir, float tmax);
Hit tracePixelRay(bool camera, vec3 origin, vec3 dir, float tmax) {
    return camera && !RESUMABLE ? traceCamera(origin, dir, tmax) : traceClosest(origin, dir, tmax);
}
#else
Hit tracePixelRay(bool camera, vec3 origin, vec3 dir, float tmax) { return traceClosest(origin, dir, tmax); }
#endif

#endif
