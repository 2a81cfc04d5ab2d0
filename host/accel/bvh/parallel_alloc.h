// Large arrays of a build, first touched by all workers of the calling oneTBB arena.
//
// A fresh multi-megabyte std::vector gets its pages from the kernel on first write; value-
// initialising it in resize() takes every page fault on one thread, and on the development VM a
// page fault costs microseconds (64 MB of BinaryNode: about 40 ms, a tenth of an AAC-Fast build at
// one million triangles, all serial). resizeFirstTouched reserves the storage, writes zeros to it in
// parallel so the faults spread over the workers, and only then constructs the elements.
#pragma once

#include <cstddef>
#include <cstring>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vkray::bvh {

// Below this many bytes the plain resize is cheaper than a parallel loop.
inline constexpr size_t kFirstTouchBytes = size_t(1) << 20;

// Resizes the empty vector v to n value-initialised elements.
template <class T>
void resizeFirstTouched(std::vector<T>& v, size_t n) {
    const size_t bytes = n * sizeof(T);
    if (bytes >= kFirstTouchBytes) {
        v.reserve(n);
        auto* raw = reinterpret_cast<unsigned char*>(v.data());  // storage only: no element lives there yet
        tbb::parallel_for(tbb::blocked_range<size_t>(0, bytes, size_t(1) << 18),
                          [raw](const tbb::blocked_range<size_t>& r) { std::memset(raw + r.begin(), 0, r.size()); });
    }
    v.resize(n);
}

}  // namespace vkray::bvh
