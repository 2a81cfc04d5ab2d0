// Ray-triangle intersection in float: Moeller and Trumbore, "Fast, Minimum Storage Ray/Triangle
// Intersection", JGT 1997. Barycentrics (u, v) weight p1 and p2; p0 gets 1 - u - v.
#ifndef VKRAY_TRIANGLE_GLSL
#define VKRAY_TRIANGLE_GLSL

struct Hit {
    float t;
    vec2 uv;
    int triangle;  // index into the triangle buffer; -1 = miss
};

const float kMinDet = 1e-30;

bool intersectTriangle(vec3 o, vec3 d, GpuTriangle tri, float tmax, out float t, out vec2 uv) {
    const vec3 p0 = tri.p0;
    const vec3 e1 = tri.p1 - p0;
    const vec3 e2 = tri.p2 - p0;
    const vec3 pvec = cross(d, e2);
    const float det = dot(e1, pvec);
    // Parallel ray or degenerate triangle. The test must keep every later value finite: shader
    // compilers may rewrite !(x >= 0.0) as x < 0.0 (valid only without NaN), so a NaN from 1/0
    // would slip through the range tests below. kMinDet is far below any real triangle's det.
    if (abs(det) < kMinDet) return false;
    const float inv = 1.0 / det;
    const vec3 tvec = o - p0;
    uv.x = dot(tvec, pvec) * inv;
    if (uv.x < 0.0 || uv.x > 1.0) return false;
    const vec3 qvec = cross(tvec, e1);
    uv.y = dot(d, qvec) * inv;
    if (uv.y < 0.0 || uv.x + uv.y > 1.0) return false;
    t = dot(e2, qvec) * inv;
    return t > 0.0 && t < tmax;
}

#endif
