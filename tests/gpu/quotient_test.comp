// Test kernel of tests/gpu/division_test.cpp: for every pair (a, b) of the buffer, quotient(a, b)
// of shaders/include/division.glsl, and roundedQuotient(a, b, q) from the device's quotient moved
// by -2, +1 and +2 ulp (an approximate division such as NVIDIA's, on any device).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "include/division.glsl"

layout(local_size_x = 64) in;
layout(std430, set = 0, binding = 0) buffer Pairs { vec4 v[]; };
layout(push_constant) uniform Count { uint n; } count;

void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= count.n) return;
    const float a = v[i].x, b = v[i].y, q = a / b;
    v[i] = vec4(quotient(a, b), roundedQuotient(a, b, movedByUlps(q, -2)), roundedQuotient(a, b, movedByUlps(q, 1)),
                roundedQuotient(a, b, movedByUlps(q, 2)));
}
