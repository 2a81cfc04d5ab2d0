#include "accel/bvh/morton.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh/primitives.h"
#include "core/parallel_alloc.h"
#include "core/radix_sort.h"

namespace vkray::bvh {
namespace {

uint32_t quantise(float x, float lo, float extent) {
    if (!(extent > 0.0f)) return 0;
    const float cell = (x - lo) / extent * float(1 << kMortonBitsPerAxis);
    return uint32_t(std::clamp(cell, 0.0f, float((1 << kMortonBitsPerAxis) - 1)));
}

}  // namespace

uint32_t expandBits(uint32_t v) {
    v &= 0x3FFu;
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
}

uint32_t mortonCode(const glm::vec3& p, const Aabb& bounds) {
    const glm::vec3 extent = bounds.hi - bounds.lo;
    const uint32_t x = quantise(p.x, bounds.lo.x, extent.x);
    const uint32_t y = quantise(p.y, bounds.lo.y, extent.y);
    const uint32_t z = quantise(p.z, bounds.lo.z, extent.z);
    return (expandBits(x) << 2) | (expandBits(y) << 1) | expandBits(z);
}

BuildArray<MortonKey> mortonKeys(std::span<const glm::vec3> centroids, const Aabb& centroidBounds) {
    BuildArray<MortonKey> keys;
    resizeForOverwrite(keys, centroids.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, centroids.size(), 4096), [&](const auto& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            keys[i] = (MortonKey(mortonCode(centroids[i], centroidBounds)) << 32) | i;
    });
    return keys;
}

void radixSortByCode(BuildArray<MortonKey>& keys) {
    radixSortBits(keys, 32, kMortonBits, [](MortonKey k) { return k; });
}

std::vector<uint32_t> mortonOrder(std::span<const Triangle> triangles) {
    const PrimitiveSet prims = primitivesOf(triangles);
    BuildArray<MortonKey> keys = mortonKeys(prims.centroids, prims.centroidBounds);
    radixSortByCode(keys);
    std::vector<uint32_t> order(keys.size());
    for (size_t i = 0; i < keys.size(); ++i) order[i] = keyPrimitive(keys[i]);
    return order;
}

}  // namespace vkray::bvh
