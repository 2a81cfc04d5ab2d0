// Secondary-ray origins pushed off the surface, after Waechter and Binder, "A Fast and Robust
// Method for Avoiding Self-Intersection", Ray Tracing Gems (2019), chapter 6: move each coordinate
// a fixed number of ULPs along the normal, so the offset grows with the coordinate's magnitude
// (float spacing), and use a small absolute offset near the origin where ULPs vanish.
#ifndef VKRAY_RAY_OFFSET_GLSL
#define VKRAY_RAY_OFFSET_GLSL

const float kOffsetNearZero = 1.0 / 32.0;    // below this magnitude ULP steps are too small
const float kOffsetAbsolute = 1.0 / 65536.0;  // absolute step used there
const float kOffsetUlps = 256.0;             // ULPs per unit of normal elsewhere

vec3 offsetRayOrigin(vec3 p, vec3 n) {
    const ivec3 ulps = ivec3(kOffsetUlps * n);
    // Stepping the integer representation moves away from zero for positive floats and towards it
    // for negative ones, hence the sign flip.
    const vec3 stepped = intBitsToFloat(floatBitsToInt(p) + mix(ulps, -ulps, lessThan(p, vec3(0.0))));
    return mix(stepped, p + kOffsetAbsolute * n, lessThan(abs(p), vec3(kOffsetNearZero)));
}

#endif
