// Watertight ray-triangle intersection in float: Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013. A ray through an edge or vertex shared by two triangles hits at
// least one of them (the CPU reference uses the same test in double), which Moeller-Trumbore does
// not guarantee: it lets rays leak through the seams of closed meshes and Cornell-box corners.
#ifndef VKRAY_TRIANGLE_GLSL
#define VKRAY_TRIANGLE_GLSL

#include "bindings.glsl"

struct Hit {
    float t;
    vec2 uv;       // barycentric weights of p1 and p2; p0 gets 1 - u - v
    int triangle;  // index into the triangle buffer; -1 = miss
};

// Per-ray constants of the test (section 3 of the paper): the axis where the direction is largest
// becomes z, and the shear that maps the ray onto +z.
struct WatertightRay {
    vec3 origin;
    ivec3 k;   // (kx, ky, kz)
    vec3 shear;  // (Sx, Sy, Sz)
};

WatertightRay makeWatertightRay(vec3 origin, vec3 dir) {
    const vec3 a = abs(dir);
    const int kz = a.x >= a.y ? (a.x >= a.z ? 0 : 2) : (a.y >= a.z ? 1 : 2);
    int kx = kz == 2 ? 0 : kz + 1;
    int ky = kx == 2 ? 0 : kx + 1;
    if (dir[kz] < 0.0) {  // keep the winding: swap kx and ky
        const int tmp = kx;
        kx = ky;
        ky = tmp;
    }
    WatertightRay r;
    r.origin = origin;
    r.k = ivec3(kx, ky, kz);
    r.shear = vec3(dir[kx] / dir[kz], dir[ky] / dir[kz], 1.0 / dir[kz]);
    return r;
}

vec3 permuted(vec3 v, ivec3 k) { return vec3(v[k.x], v[k.y], v[k.z]); }

// Hit with t in (0, tmax)? `precise` stops the compiler from fusing the edge functions into FMAs:
// the shared edge of two triangles must give exactly opposite values in both, or rays leak.
bool intersectTriangle(WatertightRay r, GpuTriangle tri, float tmax, out float t, out vec2 uv) {
    const vec3 A = permuted(tri.p0 - r.origin, r.k);
    const vec3 B = permuted(tri.p1 - r.origin, r.k);
    const vec3 C = permuted(tri.p2 - r.origin, r.k);
    precise const float ax = A.x - r.shear.x * A.z, ay = A.y - r.shear.y * A.z;
    precise const float bx = B.x - r.shear.x * B.z, by = B.y - r.shear.y * B.z;
    precise const float cx = C.x - r.shear.x * C.z, cy = C.y - r.shear.y * C.z;
    precise const float U = cx * by - cy * bx;  // edge p1-p2: weight of p0
    precise const float V = ax * cy - ay * cx;  // edge p2-p0: weight of p1
    precise const float W = bx * ay - by * ax;  // edge p0-p1: weight of p2
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    const float det = U + V + W;
    if (det == 0.0) return false;  // degenerate triangle, or the ray lies in its plane
    const float T = U * (r.shear.z * A.z) + V * (r.shear.z * B.z) + W * (r.shear.z * C.z);
    // t = T / det in (0, tmax), tested without the division; det may be negative (back face).
    if (det > 0.0 ? (T <= 0.0 || T >= tmax * det) : (T >= 0.0 || T <= tmax * det)) return false;
    const float inv = 1.0 / det;
    t = T * inv;
    uv = vec2(V * inv, W * inv);
    return true;
}

// Slot i of the triangle buffer, when below `end` (loops test several slots per iteration, the
// last batch partly past the end): the closest-hit update, and the any-hit test.
void closestInSlot(uint i, uint end, WatertightRay ray, inout Hit best) {
    float t;
    vec2 uv;
    if (i < end && intersectTriangle(ray, triangles[i], best.t, t, uv)) {
        best.t = t;
        best.uv = uv;
        best.triangle = int(i);
    }
}

bool occludesInSlot(uint i, uint end, WatertightRay ray, float tmax) {
    float t;
    vec2 uv;
    return i < end && intersectTriangle(ray, triangles[i], tmax, t, uv);
}

#endif
