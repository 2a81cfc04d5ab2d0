#include "accel/bvh/quantize.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"

namespace vkray::bvh {
namespace {

constexpr int kSteps = 255;

// One axis of the grid, for children spanning [lo, hi]: its corner and the exponent of its step.
// With 2^top the largest magnitude on the axis, every step is a power of two no smaller than
// g = 2^(top - 30), and every corner a float that is a multiple of g and below 2^(top + 2) in
// magnitude: the corner and every plane corner + q step are multiples of g within 32 bits of each
// other, so planes are exact in double, and comparing them with a child's float bounds is exact.
struct AxisGrid {
    double corner;
    int exponent;
};

// The smallest exponent, from `smallest` up, whose 255 steps from `corner` reach hi.
int reachingExponent(double corner, float hi, int smallest) {
    const double span = (double(hi) - corner) / kSteps;
    int e = span > 0.0 ? std::max(smallest, std::ilogb(span) - 1) : smallest;
    while (corner + kSteps * std::ldexp(1.0, e) < double(hi)) ++e;
    return e;
}

// A child flat on the axis: its plane, and its area across the axis (what rays start on).
struct FlatChild {
    float plane;
    float area;
};

// The area of the flat children whose planes the grid has among its own.
double areaOnGrid(const AxisGrid& grid, std::span<const FlatChild> flats) {
    double area = 0.0;
    for (const FlatChild& f : flats) {
        const double q = (double(f.plane) - grid.corner) / std::ldexp(1.0, grid.exponent);
        if (q >= 0.0 && q <= kSteps && q == std::floor(q)) area += f.area;
    }
    return area;
}

// The grid: from lo rounded down to a multiple of u, the ulp of 2^top (lower than lo by less than
// u, and only where lo is far smaller than 2^top), with the smallest step that reaches hi; or,
// where that puts more area of the children that are flat on this axis (a wall, a floor) on a plane
// of the grid, from a corner aligned with one of them, with that step or the next. A flat child off
// the grid becomes a slab one step thick, which a ray starting on it (a shadow or reflected ray)
// enters: in scenes/cornell.scene, a tenth more triangle tests without the alignment.
AxisGrid axisGrid(float lo, float hi, std::span<const FlatChild> flats) {
    const int top = std::ilogb(std::max({std::abs(lo), std::abs(hi), 1.0e-30f}));
    const double u = std::ldexp(1.0, top - 23);
    const int smallest = std::max(1 - VKRAY_BVH_EXPONENT_BIAS, top - 30);
    const double g = std::ldexp(1.0, smallest);
    const double corner = std::floor(double(lo) / u) * u;
    AxisGrid best{corner, reachingExponent(corner, hi, smallest)};
    double bestOnGrid = areaOnGrid(best, flats);
    for (const FlatChild& flat : flats) {
        const float v = flat.plane;
        if (std::fmod(double(v), g) != 0.0) continue;  // the corners would not be multiples of g
        for (const int e : {best.exponent, best.exponent + 1}) {
            const double step = std::ldexp(1.0, e);
            double aligned = double(v) - std::ceil((double(v) - lo) / step) * step;  // exact: multiples of g
            if (aligned > lo) aligned -= step;
            if (double(float(aligned)) != aligned || aligned + kSteps * step < double(hi)) continue;
            const AxisGrid candidate{aligned, e};
            const double onGrid = areaOnGrid(candidate, flats);
            if (onGrid > bestOnGrid) {
                best = candidate;
                bestOnGrid = onGrid;
            }
        }
    }
    if (best.exponent + VKRAY_BVH_EXPONENT_BIAS > 254) throw Error("internal: a BVH node too wide for its grid");
    return best;
}

// The bytes of a lower and an upper plane: the largest q with corner + q step <= lo, the smallest
// with corner + q step >= hi. The quotient may round; the exact comparisons settle q.
uint32_t lowerByte(double corner, double step, float lo) {
    double q = std::clamp(std::floor((double(lo) - corner) / step), 0.0, double(kSteps));
    while (q > 0.0 && corner + q * step > lo) q -= 1.0;
    return uint32_t(q);
}
uint32_t upperByte(double corner, double step, float hi) {
    double q = std::clamp(std::ceil((double(hi) - corner) / step), 0.0, double(kSteps));
    while (q < kSteps && corner + q * step < hi) q += 1.0;
    return uint32_t(q);
}

}  // namespace

gpu::GpuBvhNode quantizedNode(std::span<const Aabb> boxes, const gpu::uvec4& child) {
    if (boxes.empty() || boxes.size() > VKRAY_BVH_WIDTH)
        throw Error("internal: a wide node of " + std::to_string(boxes.size()) + " children");
    Aabb all;
    for (const Aabb& b : boxes) {
        const glm::vec3 size = b.hi - b.lo;  // finite exactly when both corners are
        if (b.empty() || !std::isfinite(size.x + size.y + size.z))
            throw Error("internal: an empty or infinite child box");
        all.grow(b);
    }
    gpu::GpuBvhNode node{};
    node.child = child;
    uint32_t exponents = 0;
    uint32_t planes[6] = {};  // lower x, upper x, lower y, upper y, lower z, upper z
    for (int a = 0; a < 3; ++a) {
        FlatChild flats[VKRAY_BVH_WIDTH];
        size_t flatCount = 0;
        for (const Aabb& box : boxes) {
            const glm::vec3 size = box.hi - box.lo;
            if (size[a] == 0.0f) flats[flatCount++] = {box.lo[a], size[(a + 1) % 3] * size[(a + 2) % 3]};
        }
        const AxisGrid grid = axisGrid(all.lo[a], all.hi[a], std::span<const FlatChild>(flats, flatCount));
        const double step = std::ldexp(1.0, grid.exponent);
        for (size_t k = 0; k < boxes.size(); ++k) {
            planes[2 * a] |= lowerByte(grid.corner, step, boxes[k].lo[a]) << (8 * k);
            planes[2 * a + 1] |= upperByte(grid.corner, step, boxes[k].hi[a]) << (8 * k);
        }
        node.corner[a] = float(grid.corner);
        exponents |= uint32_t(grid.exponent + VKRAY_BVH_EXPONENT_BIAS) << (8 * a);
    }
    node.exponents = exponents;
    node.planesXY = gpu::uvec4(planes[0], planes[1], planes[2], planes[3]);
    node.planesZ = gpu::uvec4(planes[4], planes[5], VKRAY_BVH_NO_PARENT, 0u);
    return node;
}

double gridStep(const gpu::GpuBvhNode& node, int a) {
    return std::ldexp(1.0, int((node.exponents >> (8 * a)) & 255u) - VKRAY_BVH_EXPONENT_BIAS);
}

GridBox gridBox(const gpu::GpuBvhNode& node, int k) {
    const uint32_t planes[6] = {node.planesXY.x, node.planesXY.y, node.planesXY.z,
                                node.planesXY.w, node.planesZ.x,  node.planesZ.y};
    GridBox box;
    for (int a = 0; a < 3; ++a) {
        const double step = gridStep(node, a);
        box.lo[a] = double(node.corner[a]) + double((planes[2 * a] >> (8 * k)) & 255u) * step;
        box.hi[a] = double(node.corner[a]) + double((planes[2 * a + 1] >> (8 * k)) & 255u) * step;
    }
    return box;
}

}  // namespace vkray::bvh
