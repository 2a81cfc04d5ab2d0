#include "accel/kd/kd_clip.h"

#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <limits>
#include <utility>

namespace vkray::accel::kd {
namespace {

// The float next to f towards -infinity (up = false) or +infinity, as std::nextafter gives it for
// every float that a double's rounding makes (finite or infinite, never NaN), by stepping its bits:
// the library call was a good part of the clipping's time.
float nextFloat(float f, bool up) {
    if (f == 0.0f) return up ? std::numeric_limits<float>::denorm_min() : -std::numeric_limits<float>::denorm_min();
    const uint32_t u = std::bit_cast<uint32_t>(f);
    // Away from zero: the magnitude's bits grow; towards it, they shrink.
    return std::bit_cast<float>((f > 0.0f) == up ? u + 1 : u - 1);
}

float roundDown(double x) {
    float f = float(x);
    return double(f) > x ? nextFloat(f, false) : f;
}

float roundUp(double x) {
    float f = float(x);
    return double(f) < x ? nextFloat(f, true) : f;
}

}  // namespace

Box boundsOf(const Triangle& t) {
    return Box{glm::min(t.p0, glm::min(t.p1, t.p2)), glm::max(t.p0, glm::max(t.p1, t.p2))};
}

Box intersection(const Box& a, const Box& b) { return Box{glm::max(a.lo, b.lo), glm::min(a.hi, b.hi)}; }

bool isEmpty(const Box& b) { return b.lo.x > b.hi.x || b.lo.y > b.hi.y || b.lo.z > b.hi.z; }

bool contains(const Box& outer, const Box& inner) {
    return glm::all(glm::lessThanEqual(outer.lo, inner.lo)) && glm::all(glm::lessThanEqual(inner.hi, outer.hi));
}

// Bounds of the part of the triangle inside `box` ("perfect splits", Wald and Havran 4.3):
// Sutherland-Hodgman clipping against the six planes in double (a triangle gains at most one vertex
// per plane), bounds rounded outwards to float, then intersected with the box. When rounding makes
// the clipped polygon vanish or leave the box, the triangle's bounding box within `box` stands in:
// it contains the exact clipped part, so nothing is ever lost, only bounded less tightly.
Box clippedBounds(const Triangle& tri, const Box& box) {
    const Box fallback = intersection(boundsOf(tri), box);
    if (contains(box, boundsOf(tri))) return fallback;
    // Two vertex buffers that the passes swap by pointer: swapping the arrays would copy them.
    std::array<glm::dvec3, 10> bufferA{glm::dvec3(tri.p0), glm::dvec3(tri.p1), glm::dvec3(tri.p2)}, bufferB{};
    glm::dvec3* poly = bufferA.data();
    glm::dvec3* next = bufferB.data();
    size_t n = 3;
    for (int axis = 0; axis < 3 && n > 0; ++axis)
        for (int upper = 0; upper < 2 && n > 0; ++upper) {
            const double plane = upper ? box.hi[axis] : box.lo[axis];
            std::array<bool, 10> inside{};
            bool all = true;
            for (size_t i = 0; i < n; ++i) {
                inside[i] = upper ? poly[i][axis] <= plane : poly[i][axis] >= plane;
                all = all && inside[i];
            }
            if (all) continue;  // the plane cuts nothing off: the pass would copy the polygon as it is
            size_t m = 0;
            for (size_t i = 0; i < n; ++i) {
                const size_t j = i + 1 == n ? 0 : i + 1;
                const glm::dvec3& a = poly[i];
                const glm::dvec3& b = poly[j];
                if (inside[i]) next[m++] = a;
                if (inside[i] != inside[j]) {
                    glm::dvec3 v = a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis]));
                    v[axis] = plane;  // on the plane exactly, whatever the interpolation rounded to
                    next[m++] = v;
                }
            }
            std::swap(poly, next);
            n = m;
        }
    if (n == 0) return fallback;
    glm::dvec3 lo = poly[0], hi = poly[0];
    for (size_t i = 1; i < n; ++i) {
        lo = glm::min(lo, poly[i]);
        hi = glm::max(hi, poly[i]);
    }
    const Box rounded{{roundDown(lo.x), roundDown(lo.y), roundDown(lo.z)}, {roundUp(hi.x), roundUp(hi.y), roundUp(hi.z)}};
    const Box clipped = intersection(rounded, box);
    return isEmpty(clipped) ? fallback : clipped;
}

}  // namespace vkray::accel::kd
