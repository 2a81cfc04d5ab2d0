#include "accel/bvh/morton.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

constexpr int kDigitBits = 10;
constexpr uint32_t kBuckets = 1u << kDigitBits;
constexpr int kPasses = (kMortonBits + kDigitBits - 1) / kDigitBits;
// Keys per block of the parallel passes: large enough that the per-block histograms (4 KiB each)
// and the serial prefix over them stay small against the scatter.
constexpr size_t kBlock = size_t(1) << 16;

uint32_t quantise(float x, float lo, float extent) {
    if (!(extent > 0.0f)) return 0;
    const float cell = (x - lo) / extent * float(1 << kMortonBitsPerAxis);
    return uint32_t(std::clamp(cell, 0.0f, float((1 << kMortonBitsPerAxis) - 1)));
}

// One stable counting-sort pass on the digit at `shift`, from `in` to `out`.
void countingPass(const std::vector<MortonKey>& in, std::vector<MortonKey>& out, int shift) {
    const size_t n = in.size(), blocks = (n + kBlock - 1) / kBlock;
    const auto digit = [shift](MortonKey k) { return uint32_t(k >> (32 + shift)) & (kBuckets - 1); };
    // counts[b * kBuckets + d]: keys of block b with digit d; becomes the first output slot.
    std::vector<size_t> counts(blocks * kBuckets, 0);
    tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
        size_t* c = &counts[b * kBuckets];
        for (size_t i = b * kBlock, end = std::min(n, i + kBlock); i < end; ++i) ++c[digit(in[i])];
    });
    // Exclusive prefix in (digit, block) order: digit-major keeps the sort stable across blocks.
    size_t sum = 0;
    for (uint32_t d = 0; d < kBuckets; ++d)
        for (size_t b = 0; b < blocks; ++b) {
            const size_t c = counts[b * kBuckets + d];
            counts[b * kBuckets + d] = sum;
            sum += c;
        }
    tbb::parallel_for(size_t(0), blocks, [&](size_t b) {
        size_t* next = &counts[b * kBuckets];
        for (size_t i = b * kBlock, end = std::min(n, i + kBlock); i < end; ++i) out[next[digit(in[i])]++] = in[i];
    });
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

std::vector<uint32_t> mortonCodes(std::span<const glm::vec3> centroids, const Aabb& centroidBounds) {
    std::vector<uint32_t> codes;
    resizeFirstTouched(codes, centroids.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, centroids.size(), 4096), [&](const auto& r) {
        for (size_t i = r.begin(); i < r.end(); ++i) codes[i] = mortonCode(centroids[i], centroidBounds);
    });
    return codes;
}

void radixSortByCode(std::vector<MortonKey>& keys) {
    std::vector<MortonKey> scratch;
    resizeFirstTouched(scratch, keys.size());
    for (int pass = 0; pass < kPasses; ++pass) {
        countingPass(keys, scratch, pass * kDigitBits);
        keys.swap(scratch);
    }
}

}  // namespace vkray::bvh
