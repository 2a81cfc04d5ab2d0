// Numeric constants that more than one include needs, defined once.
#ifndef VKRAY_CONSTANTS_GLSL
#define VKRAY_CONSTANTS_GLSL

// +infinity. A macro: glslang does not accept uintBitsToFloat in a const initializer, and GLSL has
// no infinity literal (1.0 / 0.0 is undefined behaviour in a constant expression).
#define kInfinity uintBitsToFloat(0x7F800000u)

// A distance computed by a box or plane test and one computed by the triangle test round
// differently, so comparing them needs a widening of about 3 ulps (2 gamma(3): Ize, "Robust BVH
// Ray Traversal", JCGT 2(2), 2013). The BVH's slab test and node skip and the kd stop rule use it.
const float kRoundingSlack = 1.0 + 4.0e-7;

#endif
