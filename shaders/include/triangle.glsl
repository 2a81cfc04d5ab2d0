// Watertight ray-triangle intersection in float: Woop, Benthin and Wald, "Watertight Ray/Triangle
// Intersection", JCGT 2(1), 2013. A ray through an edge or vertex shared by two triangles hits at
// least one of them (the CPU reference uses the same test in double), which Moeller-Trumbore does
// not guarantee: it lets rays leak through the seams of closed meshes and Cornell-box corners.
#ifndef VKRAY_TRIANGLE_GLSL
#define VKRAY_TRIANGLE_GLSL

#include "bindings.glsl"
#include "min_max.glsl"

struct Hit {
    float t;
    vec2 uv;        // barycentric weights of p1 and p2; p0 gets 1 - u - v
    int triangle;   // index into the triangle buffer; -1 = miss
    uint original;  // that triangle's GpuTriangle.original, for the tie rule (beats)
};

// No hit yet: t = the ray's tmax, which no hit may equal (hits need t < tmax; beats()).
Hit noHit(float tmax) {
    Hit h;
    h.t = tmax;
    h.uv = vec2(0.0);
    h.triangle = -1;
    h.original = 0u;
    return h;
}

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

// 16u, u = 2^-24 the unit roundoff of float: see hitTriangle.
const float kEdgeNoise = 1.0 / 1048576.0;
const float kTNoise = 1.0 / 1048576.0;

// The hit at t > 0, if the ray meets the triangle (no upper bound: the callers compare t, so that
// every kernel ranks hits by the same float value). No test against the best hit before the
// division: llvmpipe runs every lane through it anyway, and such a test was measured to add
// instructions (docs/stability.md, "Cost"). `precise` stops the compiler from fusing the edge
// functions into FMAs: the shared edge of two triangles must give exactly opposite values in both,
// or rays leak; and it keeps T and t the same expression in every kernel (an FMA contracted in one
// kernel and not in another would make exact ties differ between accelerators).
bool hitTriangle(WatertightRay r, GpuTriangle tri, out float t, out vec2 uv) {
    const vec3 A = permuted(tri.p0 - r.origin, r.k);
    const vec3 B = permuted(tri.p1 - r.origin, r.k);
    const vec3 C = permuted(tri.p2 - r.origin, r.k);
    precise const float ax = A.x - r.shear.x * A.z, ay = A.y - r.shear.y * A.z;
    precise const float bx = B.x - r.shear.x * B.z, by = B.y - r.shear.y * B.z;
    precise const float cx = C.x - r.shear.x * C.z, cy = C.y - r.shear.y * C.z;
    precise const float u0 = cx * by, v0 = ax * cy, w0 = bx * ay, u1 = cy * bx, v1 = ay * cx, w1 = by * ax;
    precise const float U = u0 - u1;  // edge p1-p2: weight of p0
    precise const float V = v0 - v1;  // edge p2-p0: weight of p1
    precise const float W = w0 - w1;  // edge p0-p1: weight of p2
    if ((U < 0.0 || V < 0.0 || W < 0.0) && (U > 0.0 || V > 0.0 || W > 0.0)) return false;
    const float det = U + V + W;
    // det, twice the projected area, must stand above the rounding of the edge functions: each is
    // off by at most 2u (|first product| + |second product|), u = 2^-24 (Higham, "Accuracy and
    // Stability of Numerical Algorithms", 2nd ed., 3.1), so when |det| is within that of all of
    // them, U, V and W may all be rounding noise and their agreeing signs mean nothing. That is a
    // triangle smaller than the rounding of its distance to the ray: measured on
    // scenes/stress/kd-zeno.scene, triangles 1e-7 across were "hit" by rays passing a unit away
    // (99 of 2304 camera rays of the brute-force kernel; an accelerator's boxes hid them). An edge
    // function that is all noise has two products of about the same size, so the first product of
    // each stands for both (16u |u0| for 8u (|u0| + |u1|)): half the work. It also covers
    // det == 0: a degenerate triangle, or a ray lying in the triangle's plane.
    if (abs(det) <= (abs(u0) + abs(v0) + abs(w0)) * kEdgeNoise) return false;
    precise const float za = r.shear.z * A.z, zb = r.shear.z * B.z, zc = r.shear.z * C.z;
    precise const float T = U * za + V * zb + W * zc;
    // t = T / det > 0 needs T of det's sign (det may be negative: a back face).
    if (det > 0.0 ? T <= 0.0 : T >= 0.0) return false;
    const float inv = 1.0 / det;
    precise const float tHit = T * inv;
    t = tHit;
    uv = vec2(V * inv, W * inv);
    // t must stand above its own rounding, a few u times the vertices' distances along the ray
    // (the deltaZ term of Pharr, Jakob and Humphreys, "Physically Based Rendering", 3rd ed., 3.9.6):
    // a ray starting on or a rounding away from a triangle's plane may otherwise "hit" it at a t of
    // pure rounding. Measured on scenes/stress/closed-cube-inside.scene: shadow rays from points on
    // a concave edge, pushed off one face and so still in the plane of the other, darkened the edge.
    return tHit > kTNoise * maxOf(abs(za), maxOf(abs(zb), abs(zc)));
}

// Whether a hit at t on a triangle of identity `original` beats `best` in the closest-hit order that
// every kernel and the CPU share (docs/shading.md): smaller t, and on exactly equal t the lower
// original triangle index (triangle identity, the load order: docs/scene-format.md). The BVH
// reorders the triangle buffer and the kd-tree lists a triangle in several leaves, so the order a
// traversal meets triangles must not decide ties: brute force, walking slots in index order with a
// strict `<`, would agree with itself but not with them: without this rule the kernels name
// another triangle than the brute-force kernel wherever scenes/stress/ has exact ties
// (docs/stability.md). With no hit yet, best.original is 0, which no index is below:
// a hit at exactly the ray's tmax never wins.
bool beats(float t, uint original, Hit best) {
    return t < best.t || (t == best.t && original < best.original);
}

// Tests the triangle in `slot` of the triangle buffer and keeps its hit if it beats `best`.
void closestTriangle(uint slot, WatertightRay ray, inout Hit best) {
    const GpuTriangle tri = loadTriangle(slot);
    float t;
    vec2 uv;
    if (hitTriangle(ray, tri, t, uv) && beats(t, tri.original, best)) {
        best.t = t;
        best.uv = uv;
        best.triangle = int(slot);
        best.original = tri.original;
    }
}

// Any hit asks only whether: it records the triangle in `best` and keeps best.t, the ray's tmax, so
// it neither loads the triangle's identity nor computes uv as the closest-hit update does. (Through
// closestTriangle, any hit would pay for both on every lane on lavapipe, which runs an `if` body for
// all lanes, and shadow rays are most of a render's rays.)
void anyTriangle(uint triangle, WatertightRay ray, inout Hit best) {
    float t;
    vec2 uv;
    if (hitTriangle(ray, loadTriangle(triangle), t, uv) && t < best.t) best.triangle = int(triangle);
}

#endif
