#include "accel/kd/kd_clip.h"

#include <algorithm>
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

namespace {

// A triangle being clipped (Sutherland-Hodgman) in double. A convex polygon gains at most one
// vertex a plane, nine at most after six; rounding can bend a nearly degenerate one so that a plane
// crosses it more than twice, and a pass then writes up to twice its vertices. The buffers hold
// that for any polygon a convex one can become; one beyond it is given up (nothing left: the
// triangle's bounds within the box stand in, bounds()), never written past the end.
class ClipPolygon {
public:
    explicit ClipPolygon(const Triangle& tri) : n_(3) {
        v_[0][0] = glm::dvec3(tri.p0);
        v_[0][1] = glm::dvec3(tri.p1);
        v_[0][2] = glm::dvec3(tri.p2);
    }

    bool empty() const { return n_ == 0; }

    // A copy of the current polygon only: a whole copy would move both buffers.
    ClipPolygon fork() const {
        ClipPolygon copy;
        copy.n_ = n_;
        std::copy_n(v_[cur_].begin(), n_, copy.v_[0].begin());
        return copy;
    }

    // Pass `pass` of the six, in the order x low, x high, y low, ... : the part on the box's side of
    // that face's plane.
    void clip(const Box& box, int pass) {
        switch (pass) {
        case 0: clipAt<0, false>(box.lo.x); break;
        case 1: clipAt<0, true>(box.hi.x); break;
        case 2: clipAt<1, false>(box.lo.y); break;
        case 3: clipAt<1, true>(box.hi.y); break;
        case 4: clipAt<2, false>(box.lo.z); break;
        default: clipAt<2, true>(box.hi.z); break;
        }
    }

    // Passes first..5 against `box`, stopping when nothing is left.
    void clipFrom(const Box& box, int first) {
        for (int pass = first; pass < 6 && n_ > 0; ++pass) clip(box, pass);
    }

    // The polygon's bounds rounded outwards to float, within `box`; `fallback` when rounding made
    // it vanish or leave the box, or nothing is left.
    Box bounds(const Box& box, const Box& fallback) const {
        if (n_ == 0) return fallback;
        const glm::dvec3* poly = v_[cur_].data();
        glm::dvec3 lo = poly[0], hi = poly[0];
        for (size_t i = 1; i < n_; ++i) {
            lo = glm::min(lo, poly[i]);
            hi = glm::max(hi, poly[i]);
        }
        const Box rounded{{roundDown(lo.x), roundDown(lo.y), roundDown(lo.z)},
                          {roundUp(hi.x), roundUp(hi.y), roundUp(hi.z)}};
        const Box clipped = intersection(rounded, box);
        return isEmpty(clipped) ? fallback : clipped;
    }

private:
    // One pass with its axis and side as constants: with the axis an index known only at run time,
    // each new vertex was stored to memory, its coordinate on the axis overwritten there and the
    // whole vertex read back, a load stalled behind a narrower store at every crossing.
    template <int axis, bool upper>
    void clipAt(double plane) {
        if (n_ > kMaxConvex) {  // bent by rounding (above): given up
            n_ = 0;
            return;
        }
        const glm::dvec3* poly = v_[cur_].data();
        std::array<bool, kMaxConvex> inside;
        bool all = true;
        for (size_t i = 0; i < n_; ++i) {
            inside[i] = upper ? poly[i][axis] <= plane : poly[i][axis] >= plane;
            all = all && inside[i];
        }
        if (all) return;  // the plane cuts nothing off: the pass would copy the polygon as it is
        // Which vertices are kept changes from edge to edge without a pattern, so without branches:
        // every slot is written and the count steps past what is kept. A crossing's point is made
        // for every edge (NaN for an edge in the plane: never kept), on the plane exactly, whatever
        // the interpolation would round its coordinate there to.
        glm::dvec3* next = v_[1 - cur_].data();
        size_t m = 0;
        for (size_t i = 0; i < n_; ++i) {
            const size_t j = i + 1 == n_ ? 0 : i + 1;
            const glm::dvec3& a = poly[i];
            const glm::dvec3& b = poly[j];
            next[m] = a;
            m += inside[i];
            const double t = (plane - a[axis]) / (b[axis] - a[axis]);
            next[m] = glm::dvec3(axis == 0 ? plane : a.x + (b.x - a.x) * t, axis == 1 ? plane : a.y + (b.y - a.y) * t,
                                 axis == 2 ? plane : a.z + (b.z - a.z) * t);
            m += inside[i] != inside[j];
        }
        cur_ = 1 - cur_;
        n_ = m;
    }

    ClipPolygon() = default;

    static constexpr size_t kMaxConvex = 9;  // a triangle after six planes
    // A pass of kMaxConvex vertices writes at most two a vertex, the last unkept: slots 0..2 * 9.
    std::array<std::array<glm::dvec3, 2 * kMaxConvex + 1>, 2> v_;  // the current polygon and the next pass's
    int cur_ = 0;
    size_t n_ = 0;
};

}  // namespace

// Bounds of the part of the triangle inside `box` ("perfect splits", Wald and Havran 4.3):
// Sutherland-Hodgman clipping against the six planes in double (a triangle gains at most one vertex
// per plane), bounds rounded outwards to float, then intersected with the box. When rounding makes
// the clipped polygon vanish or leave the box, the triangle's bounding box within `box` stands in:
// it contains the exact clipped part, so nothing is ever lost, only bounded less tightly.
Box clippedBounds(const Triangle& tri, const Box& box) {
    const Box fallback = intersection(boundsOf(tri), box);
    if (contains(box, boundsOf(tri))) return fallback;
    ClipPolygon poly(tri);
    poly.clipFrom(box, 0);
    return poly.bounds(box, fallback);
}

// The two children's boxes differ only in the split axis's planes, and the passes against the axes
// before it are the same for both: done once, then each child's from there, so each result is the
// one clippedBounds gives.
std::pair<Box, Box> clippedBoundsOfSplit(const Triangle& tri, const Box& below, const Box& above, int axis) {
    const Box b = boundsOf(tri);
    if (contains(below, b) || contains(above, b)) return {clippedBounds(tri, below), clippedBounds(tri, above)};
    ClipPolygon shared(tri);
    for (int pass = 0; pass < 2 * axis && !shared.empty(); ++pass) shared.clip(below, pass);
    ClipPolygon inAbove = shared.fork();
    shared.clipFrom(below, 2 * axis);
    inAbove.clipFrom(above, 2 * axis);
    return {shared.bounds(below, intersection(b, below)), inAbove.bounds(above, intersection(b, above))};
}

}  // namespace vkray::accel::kd
