// Large arrays of a build, first touched by all workers of the calling oneTBB arena.
//
// A fresh multi-megabyte std::vector gets its pages from the kernel on first write; value-
// initialising it in resize() takes every page fault on one thread, and on the development VM a
// page fault costs microseconds (64 MB of BinaryNode: about 40 ms, a tenth of an AAC-Fast build at
// one million triangles, all serial). resizeFirstTouched reserves the storage, has the kernel
// populate its pages in parallel (madvise MADV_POPULATE_WRITE, Linux 5.14+) so the faults spread
// over the workers, and only then constructs the elements.
//
// The pages are populated, not written: the storage past size() is the vector's, and writing to it
// (as an earlier memset did) is outside std::vector's contract; AddressSanitizer with libstdc++'s
// vector annotations (-D_GLIBCXX_SANITIZE_VECTOR) reports it as a container overflow.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace vkray {

// Below this many bytes the plain resize is cheaper than a parallel loop.
inline constexpr size_t kFirstTouchBytes = size_t(1) << 20;

// Asks the kernel to back [begin, end) with pages now, in parallel chunks. Advisory: on a kernel
// without MADV_POPULATE_WRITE (or any failure) nothing happens and resize() takes the faults.
inline void populatePages(const void* begin, const void* end) {
#ifdef MADV_POPULATE_WRITE
    const uintptr_t page = uintptr_t(sysconf(_SC_PAGESIZE));
    const uintptr_t first = (reinterpret_cast<uintptr_t>(begin) + page - 1) & ~(page - 1);
    const uintptr_t last = reinterpret_cast<uintptr_t>(end) & ~(page - 1);
    if (last <= first) return;
    constexpr uintptr_t kChunk = uintptr_t(1) << 18;
    tbb::parallel_for(tbb::blocked_range<uintptr_t>(0, (last - first + kChunk - 1) / kChunk),
                      [&](const tbb::blocked_range<uintptr_t>& r) {
                          for (uintptr_t c = r.begin(); c < r.end(); ++c) {
                              const uintptr_t a = first + c * kChunk;
                              madvise(reinterpret_cast<void*>(a), std::min(last, a + kChunk) - a, MADV_POPULATE_WRITE);
                          }
                      });
#else
    (void)begin;
    (void)end;
#endif
}

// Resizes the empty vector v to n value-initialised elements.
template <class T>
void resizeFirstTouched(std::vector<T>& v, size_t n) {
    if (n * sizeof(T) >= kFirstTouchBytes) {
        v.reserve(n);
        populatePages(v.data(), v.data() + n);  // storage only: no element lives there yet
    }
    v.resize(n);
}

}  // namespace vkray
