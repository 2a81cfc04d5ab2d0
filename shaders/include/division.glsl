// Float division rounded as IEEE 754 rounds it, on any Vulkan device. Vulkan lets OpFDiv be up to
// 2.5 ulp off (the precision table of the spec's SPIR-V environment appendix), and NVIDIA's driver
// uses that; lavapipe's division is IEEE's (tests/gpu/division_test.cpp). The camera divides with
// it (camera.glsl): on the ill-conditioned rays of scenes/stress/degenerate.scene (slivers, grazing
// rays) NVIDIA's approximate division moves enough camera rays onto another triangle than the
// double-precision reference's to fail the stress test's limit on an H200; with IEEE-rounded camera
// divisions the case is within it, as on lavapipe (docs/stability.md, "Division on GPUs").
//
// Two steps from the device's quotient q. First Markstein's ("Computation of elementary functions
// on the IBM RISC System/6000 processor", IBM J. Res. Dev. 34(1), 1990): the residual a - q b,
// exact, and q1 = q + residual * (1 / b), within an ulp of a / b. Markstein takes the residual from
// a fused multiply-add, but GLSL's fma() need not be fused (lavapipe splits it into a multiply and
// an add, and the residual is then not exact); so q b is taken exactly as p + e by Dekker's product ("A
// floating-point technique for extending the available precision", Numer. Math. 18, 1971) with
// Veltkamp's split, and a - p is exact for q within a few ulp (Sterbenz). Without a fused last
// step q1 may still be the wrong one of two floats when a / b lies within rounding of the midpoint
// between them: 1 / (4 - 2^-22) lies 2^-50 above the midpoint of 0.25 and its successor, and the
// step, its product rounded, moved the IEEE quotient down to 0.25 (seen on lavapipe, where the
// device's quotient is already IEEE's, in 369 of 3,625 hits of scenes/stress/coplanar.scene when
// the triangle test's 1 / det was corrected). So the second step compares exact residuals: of q1
// and of its neighbour towards a / b, the one with the smaller |a - x b| is the nearest to a / b
// (b is common to both). There are no exact ties: a midpoint has 25 significant bits, so a = m b
// would need more than 24 unless b is a power of two, whose quotients are exact. Every step is
// `precise`, so that no compiler contracts or reassociates it. Where q is already IEEE's (lavapipe),
// q comes back unchanged.
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

// Where the steps hold: a, b and q within 2^-60 .. 2^60 in magnitude, so that every product,
// residual and low part below (down to 2^-48 of a) is a normal float: no overflow in the split, no
// flushed subnormal, no zero whose sign the final sum would lose. Outside it the device's quotient
// stands.
const float kDivisionMin = 1.0 / 1152921504606846976.0;  // 2^-60
const float kDivisionMax = 1152921504606846976.0;        // 2^60

// x moved by `ulps` floats of its own sign's direction (+1: away from zero): x's bits stepped. For
// x finite and nonzero, within the guard below.
float movedByUlps(float x, int ulps) { return uintBitsToFloat(uint(int(floatBitsToUint(x)) + ulps)); }

// a - x b, exact for x within a few ulp of a / b; (bh, bl) is b's split.
float exactResidual(float a, float b, float bh, float bl, float x) {
    float xh, xl;
    splitFloat(x, xh, xl);
    precise const float p = x * b;
    precise const float e = ((xh * bh - p) + xh * bl + xl * bh) + xl * bl;  // x b = p + e exactly
    precise const float r = (a - p) - e;
    return r;
}

// The IEEE quotient a / b from an approximation q within a few ulp of it.
float roundedQuotient(float a, float b, float q) {
    float bh, bl;
    splitFloat(b, bh, bl);
    precise const float q1 = q + exactResidual(a, b, bh, bl, q) * (1.0 / b);
    const float r1 = exactResidual(a, b, bh, bl, q1);
    // The float next to q1 on the side of a / b (r1 / b > 0: above q1).
    const bool above = (r1 > 0.0) == (b > 0.0);
    const float next = movedByUlps(q1, (q1 > 0.0) == above ? 1 : -1);
    const float rounded = abs(exactResidual(a, b, bh, bl, next)) < abs(r1) ? next : q1;
    const vec4 m = abs(vec4(a, b, q, q1));
    const bool normal = all(greaterThan(m, vec4(kDivisionMin))) && all(lessThan(m, vec4(kDivisionMax)));
    return normal ? rounded : q;
}

float quotient(float a, float b) { return roundedQuotient(a, b, a / b); }

#endif
