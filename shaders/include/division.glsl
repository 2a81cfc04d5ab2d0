// Float division rounded as IEEE 754 rounds it, on any Vulkan device. Vulkan lets OpFDiv be up to
// 2.5 ulp off (the precision table of the spec's SPIR-V environment appendix), and NVIDIA's driver
// uses that; lavapipe's division is IEEE's (tests/gpu/division_test.cpp). The camera divides with
// it (camera.glsl): on the ill-conditioned rays of scenes/stress/degenerate.scene (slivers, grazing
// rays) NVIDIA's camera rays put 32 of 2,961 primary hits on another triangle than the
// double-precision reference on an H200, beyond the stress test's 1%; with IEEE-rounded camera
// divisions 21, against lavapipe's 18 (docs/stability.md, "Division on GPUs").
//
// One correction step of the device's quotient q (Markstein, "Computation of elementary functions
// on the IBM RISC System/6000 processor", IBM J. Res. Dev. 34(1), 1990): the residual a - q b,
// exact, and q + residual * (1 / b). Markstein takes the residual from a fused multiply-add, but
// GLSL's fma() need not be fused (on lavapipe a first version with fma() put 12% of the quotients
// an ulp off); so q b is taken exactly as p + e by Dekker's product ("A floating-point technique
// for extending the available precision", Numer. Math. 18, 1971) with Veltkamp's split, and a - p
// is exact for q within a few ulp (Sterbenz). Every step is `precise`, so that no compiler
// contracts or reassociates it. Where q is already IEEE's (lavapipe), the correction is below half
// an ulp and q is returned unchanged.
#ifndef VKRAY_DIVISION_GLSL
#define VKRAY_DIVISION_GLSL

// x = hi + lo, each half of x's 24-bit significand (Veltkamp's split, factor 2^12 + 1).
void splitFloat(float x, out float hi, out float lo) {
    precise const float c = 4097.0 * x;
    precise const float h = c - (c - x);
    hi = h;
    precise const float l = x - h;
    lo = l;
}

// Where the step holds: a, b and q within 2^-100 .. 2^100 in magnitude, so that every product and
// residual below is a normal float (no overflow in the split, no flushed subnormal, no zero whose
// sign the final sum would lose). Outside it the device's quotient stands.
const float kDivisionMin = 1.0 / 1267650600228229401496703205376.0;  // 2^-100
const float kDivisionMax = 1267650600228229401496703205376.0;        // 2^100

// The IEEE quotient a / b from an approximation q within a few ulp of it.
float roundedQuotient(float a, float b, float q) {
    float qh, ql, bh, bl;
    splitFloat(q, qh, ql);
    splitFloat(b, bh, bl);
    precise const float p = q * b;
    precise const float e = ((qh * bh - p) + qh * bl + ql * bh) + ql * bl;  // q b = p + e exactly
    precise const float residual = (a - p) - e;
    precise const float rounded = q + residual * (1.0 / b);
    const vec3 m = abs(vec3(a, b, q));
    const bool normal = all(greaterThan(m, vec3(kDivisionMin))) && all(lessThan(m, vec3(kDivisionMax)));
    return normal ? rounded : q;
}

float quotient(float a, float b) { return roundedQuotient(a, b, a / b); }

#endif
