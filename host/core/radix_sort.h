// Stable parallel LSD radix sort of 64-bit keys on a range of their bits: the Morton keys of the
// BVH builders (the code in the upper half) and the kd builder's events (position and type above
// the triangle index). Keys equal in the sorted bits keep their order, so a sort on the upper bits
// of keys whose lower bits already ascend is a sort on the whole key.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#include "core/parallel_alloc.h"

namespace vkray {

namespace radix_detail {

inline constexpr int kDigitBits = 10;
inline constexpr uint32_t kBuckets = 1u << kDigitBits;
// Keys per block of the parallel passes: large enough that the per-block histograms (8 KiB each)
// and the serial prefix over them stay small against the scatter.
inline constexpr size_t kBlock = size_t(1) << 16;

// One stable counting-sort pass on the digit at `shift`, from `in` to `out`.
template <class T, class A, class Key>
void countingPass(const std::vector<T, A>& in, std::vector<T, A>& out, int shift, const Key& key) {
    const size_t n = in.size(), blocks = (n + kBlock - 1) / kBlock;
    const auto digit = [&](const T& v) { return uint32_t(key(v) >> shift) & (kBuckets - 1); };
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

}  // namespace radix_detail

// Sorts `values` stably by bits [lowBit, lowBit + bits) of key(value), a uint64_t.
template <class T, class Alloc, class Key>
void radixSortBits(std::vector<T, Alloc>& values, int lowBit, int bits, const Key& key) {
    std::vector<T, Alloc> scratch;
    resizeForOverwrite(scratch, values.size());  // each pass writes every slot
    for (int done = 0; done < bits; done += radix_detail::kDigitBits) {
        radix_detail::countingPass(values, scratch, lowBit + done, key);
        values.swap(scratch);
    }
}

}  // namespace vkray
