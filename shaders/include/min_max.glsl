// min and max as a compare and a select. GLSL's min() and max() become NIR's fmin and fmax, which
// must return the other operand when one is a NaN; llvmpipe (lavapipe) pays for that with a NaN
// compare and a blend besides each vector min or max, where a compare and a select is the one x86
// instruction. The callers' operands are never NaN, and there the two agree (docs/performance.md,
// "What lavapipe charges for").
#ifndef VKRAY_MIN_MAX_GLSL
#define VKRAY_MIN_MAX_GLSL

float minOf(float a, float b) { return a < b ? a : b; }
float maxOf(float a, float b) { return a > b ? a : b; }
vec3 maxOf(vec3 a, vec3 b) { return mix(b, a, greaterThan(a, b)); }
vec4 minOf(vec4 a, vec4 b) { return mix(b, a, lessThan(a, b)); }
vec4 maxOf(vec4 a, vec4 b) { return mix(b, a, greaterThan(a, b)); }

#endif
