// The kd builder's clipping ("perfect splits", Wald and Havran 2006, section 4.3): the bounds of a
// triangle's part inside a box hold that part and exceed it by less than a float's step, stay
// within the box, are tight where the clip cuts a corner off, and the two children's bounds
// of a split (clippedBoundsOfSplit, which shares the passes before the split axis) are the ones
// clippedBounds gives each child alone.
#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "accel/kd/kd_clip.h"

namespace vkray::accel::kd {
namespace {

Triangle tri(glm::vec3 a, glm::vec3 b, glm::vec3 c) { return Triangle{a, b, c, 0}; }

bool holds(const Box& b, const glm::dvec3& p) {
    return glm::all(glm::lessThanEqual(glm::dvec3(b.lo), p)) &&
           glm::all(glm::lessThanEqual(p, glm::dvec3(b.hi)));
}

// A random triangle and a random box that cuts into it: the box's corners drawn around points of
// the triangle, so most of the six planes cut it.
struct Case {
    Triangle t;
    Box box;
};

Case randomCase(std::mt19937& rng) {
    std::uniform_real_distribution<float> coord(-10.0f, 10.0f), weight(0.0f, 1.0f), extent(0.01f, 4.0f);
    Case c;
    c.t = tri({coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)},
              {coord(rng), coord(rng), coord(rng)});
    const float u = weight(rng), v = weight(rng) * (1.0f - u);
    const glm::vec3 inside = c.t.p0 + u * (c.t.p1 - c.t.p0) + v * (c.t.p2 - c.t.p0);
    for (int k = 0; k < 3; ++k) {
        c.box.lo[k] = inside[k] - extent(rng);
        c.box.hi[k] = inside[k] + extent(rng);
    }
    return c;
}

TEST(KdClipBounds, CutsTheCornerOffWhereTheBoxHoldsPartOfTheTriangle) {
    // The triangle x + y <= 4 in z = 0; the box y in [2, 3]: its part has x in [0, 4 - y], at most 2,
    // where the triangle's own bounds inside the box would say 3.
    const Box b = clippedBounds(tri({0, 0, 0}, {4, 0, 0}, {0, 4, 0}), Box{{0, 2, -1}, {3, 3, 1}});
    EXPECT_EQ(b.lo, glm::vec3(0, 2, 0));
    EXPECT_EQ(b.hi, glm::vec3(2, 3, 0));
}

TEST(KdClipBounds, ATriangleInsideTheBoxKeepsItsBounds) {
    const Triangle t = tri({1, 1, 1}, {2, 1.5f, 1}, {1.5f, 2, 1.25f});
    const Box b = clippedBounds(t, Box{{0, 0, 0}, {4, 4, 4}});
    EXPECT_EQ(b, boundsOf(t));
}

// The part of t inside box, clipped against the box's six planes in long double: a reference
// computed apart from the builder's code, more precisely than its doubles.
std::vector<std::array<long double, 3>> partInside(const Triangle& t, const Box& box) {
    std::vector<std::array<long double, 3>> poly;
    for (const glm::vec3& v : {t.p0, t.p1, t.p2}) poly.push_back({v.x, v.y, v.z});
    for (int pass = 0; pass < 6 && !poly.empty(); ++pass) {
        const int k = pass / 2;
        const bool upper = pass % 2 == 1;
        const long double plane = upper ? box.hi[k] : box.lo[k];
        const auto in = [&](const std::array<long double, 3>& v) { return upper ? v[k] <= plane : v[k] >= plane; };
        std::vector<std::array<long double, 3>> next;
        for (size_t i = 0; i < poly.size(); ++i) {
            const auto& a = poly[i];
            const auto& b = poly[(i + 1) % poly.size()];
            if (in(a)) next.push_back(a);
            if (in(a) != in(b)) {
                const long double f = (plane - a[k]) / (b[k] - a[k]);
                std::array<long double, 3> v{};
                for (int j = 0; j < 3; ++j) v[j] = j == k ? plane : a[j] + (b[j] - a[j]) * f;
                next.push_back(v);
            }
        }
        poly = next;
    }
    return poly;
}

TEST(KdClipBounds, BoundsHoldThePartInsideAndNoMore) {
    std::mt19937 rng(7);
    for (int i = 0; i < 20000; ++i) {
        const Case c = randomCase(rng);
        const Box b = clippedBounds(c.t, c.box);
        ASSERT_TRUE(holds(c.box, glm::dvec3(b.lo)) && holds(c.box, glm::dvec3(b.hi))) << "case " << i;
        const auto part = partInside(c.t, c.box);
        ASSERT_FALSE(part.empty()) << "case " << i;  // the box was drawn around a point of the triangle
        for (int k = 0; k < 3; ++k) {
            long double lo = part[0][k], hi = part[0][k];
            for (const auto& v : part) {
                lo = std::min(lo, v[k]);
                hi = std::max(hi, v[k]);
            }
            // The builder clips in double, then rounds outwards to float: its bound is on the far
            // side of the part's extreme, by less than a float's step (up to the doubles' own
            // rounding, about 1e-15 of coordinates below 15), unless the box's face is nearer.
            constexpr long double kDoubleError = 1e-12L;
            ASSERT_LE(b.lo[k], lo + kDoubleError) << "case " << i << ", axis " << k;
            ASSERT_GE(b.hi[k], hi - kDoubleError) << "case " << i << ", axis " << k;
            ASSERT_GE(b.lo[k], std::max<long double>(c.box.lo[k], std::nextafter(float(lo), -INFINITY) - kDoubleError))
                << "case " << i << ", axis " << k;
            ASSERT_LE(b.hi[k], std::min<long double>(c.box.hi[k], std::nextafter(float(hi), INFINITY) + kDoubleError))
                << "case " << i << ", axis " << k;
        }
    }
}

TEST(KdClipBounds, ASplitsChildrenGetWhatEachWouldAlone) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> at(0.05f, 0.95f);
    for (int i = 0; i < 5000; ++i) {
        const Case c = randomCase(rng);
        const int axis = i % 3;
        const float pos = c.box.lo[axis] + at(rng) * (c.box.hi[axis] - c.box.lo[axis]);
        const auto [below, above] = splitBox(c.box, axis, pos);
        const auto [inBelow, inAbove] = clippedBoundsOfSplit(c.t, below, above, axis);
        ASSERT_EQ(inBelow, clippedBounds(c.t, below)) << "case " << i;
        ASSERT_EQ(inAbove, clippedBounds(c.t, above)) << "case " << i;
    }
}

}  // namespace
}  // namespace vkray::accel::kd
