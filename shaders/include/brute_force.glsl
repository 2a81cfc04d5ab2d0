// The `brute` accelerator: every ray is tested against every triangle. The reference the other
// traversals are measured against, usable for small scenes and tests.
#ifndef VKRAY_BRUTE_FORCE_GLSL
#define VKRAY_BRUTE_FORCE_GLSL

#include "triangle.glsl"

// Closest hit in (0, tmax). Ties in t go to the lowest triangle index (strict <), as on the CPU.
Hit traceClosest(vec3 origin, vec3 dir, float tmax) {
    Hit best;
    best.t = tmax;
    best.triangle = -1;
    const uint count = params.counts.x;
    for (uint i = 0; i < count; ++i) {
        float t;
        vec2 uv;
        if (intersectTriangle(origin, dir, triangles[i], best.t, t, uv)) {
            best.t = t;
            best.uv = uv;
            best.triangle = int(i);
        }
    }
    return best;
}

// Any hit in (0, tmax): shadow rays stop at the first occluder.
bool traceAny(vec3 origin, vec3 dir, float tmax) {
    const uint count = params.counts.x;
    for (uint i = 0; i < count; ++i) {
        float t;
        vec2 uv;
        if (intersectTriangle(origin, dir, triangles[i], tmax, t, uv)) return true;
    }
    return false;
}

#endif
