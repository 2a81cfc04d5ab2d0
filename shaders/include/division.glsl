// Float division rounded as IEEE 754 rounds it, on any Vulkan device. Vulkan lets OpFDiv be up to
// 2.5 ulp off (the precision table of the spec's SPIR-V environment appendix), and devices use that:
// the quotients below change the results of NVIDIA's driver and of lavapipe. On the ill-conditioned
// rays of scenes/stress/degenerate.scene (slivers, grazing rays) the approximate quotients put 32 of
// 2,961 primary hits on another triangle than the double-precision reference on an NVIDIA H200 (the
// stress test allows 1%) and 18 on lavapipe; with these, 18 on the H200 and 15 on lavapipe
// (docs/stability.md, "Division on GPUs").
//
// One correction step: for q within an ulp of a / b, the residual a - q b is exact in one fused
// multiply-add (`fma` consumed by a `precise` variable is one rounding: GLSL 4.60, 8.3), and
// q + residual * (1 / b), fused, is the correctly rounded quotient when 1 / b is (Markstein,
// "Computation of elementary functions on the IBM RISC System/6000 processor", IBM J. Res. Dev.
// 34(1), 1990). A device's 1 / b may itself be an ulp or two off, which leaves rare last-bit cases.
#ifndef VKRAY_DIVISION_GLSL
#define VKRAY_DIVISION_GLSL

float quotient(float a, float b) {
    const float q = a / b;
    precise const float residual = fma(-q, b, a);
    precise const float rounded = fma(residual, 1.0 / b, q);
    return rounded;
}

#endif
