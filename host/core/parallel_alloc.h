// Large arrays of a build, and copies into fresh memory, first touched by all workers of the
// calling oneTBB arena.
//
// A fresh multi-megabyte std::vector gets its pages from the kernel on first write; value-
// initialising it in resize() takes every page fault on one thread, and a page fault costs
// microseconds, so a build's large arrays would fault in serially for a sizeable share of a
// million-triangle build. resizeFirstTouched reserves the storage, has the kernel
// populate its pages in parallel (madvise MADV_POPULATE_WRITE, Linux 5.14+) so the faults spread
// over the workers, and only then constructs the elements.
//
// The pages are populated, not written: the storage past size() is the vector's, and writing to it
// (a memset, say) is outside std::vector's contract; AddressSanitizer with libstdc++'s
// vector annotations (-D_GLIBCXX_SANITIZE_VECTOR) reports it as a container overflow.
//
// A BuildArray (a std::vector with FirstTouchAllocator) goes further: its elements are
// value-initialised by all workers, each over its own run, which also takes that run's page faults,
// so neither the faults nor the writes are left to one thread. An array that its builder writes
// whole before reading any of it needs no value at all: resizeForOverwrite only populates it.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <type_traits>
#include <utility>
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

// Copies n bytes into fresh memory (a mapped Vulkan buffer, say) on all workers of the calling
// oneTBB arena, in runs of 4 MiB: the destination's page faults spread over them, as populatePages
// spreads a build array's. Below two runs, a plain memcpy.
inline void parallelCopy(void* dst, const void* src, size_t n) {
    constexpr size_t kChunk = size_t(1) << 22;
    if (n < 2 * kChunk) {
        std::memcpy(dst, src, n);
        return;
    }
    tbb::parallel_for(tbb::blocked_range<size_t>(0, (n + kChunk - 1) / kChunk), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t c = r.begin(); c < r.end(); ++c) {
            const size_t at = c * kChunk;
            std::memcpy(static_cast<char*>(dst) + at, static_cast<const char*>(src) + at, std::min(n, at + kChunk) - at);
        }
    });
}

// Reserves storage for n elements in the empty vector v and has the kernel populate its pages in
// parallel (populatePages); no element is constructed: the caller's resize or assign writes them
// without page faults on one thread.
template <class T, class A>
void reservePopulated(std::vector<T, A>& v, size_t n) {
    v.reserve(n);
    populatePages(v.data(), v.data() + n);  // storage only: no element lives there yet
}

namespace detail {
// Set around the one resize whose elements the caller then constructs, or leaves to be written.
inline thread_local bool gDeferValueInit = false;
}  // namespace detail

// std::allocator, except that the resize of resizeFirstTouched leaves its new elements to be
// value-initialised by resizeFirstTouched, in parallel, instead of one by one on the calling thread
// (otherwise a serial pass over every large array of a build). Every other construction is
// std::allocator's.
// Base: where the storage comes from (std::allocator, or oneTBB's scalable_allocator for arrays
// that a builder makes and frees by the million).
template <class T, class Base = std::allocator<T>>
struct FirstTouchAllocator : Base {
    template <class U>
    struct rebind {
        using other = FirstTouchAllocator<U, typename std::allocator_traits<Base>::template rebind_alloc<U>>;
    };
    FirstTouchAllocator() = default;
    template <class U, class B>
    FirstTouchAllocator(const FirstTouchAllocator<U, B>&) noexcept {}

    template <class U, class... Args>
    void construct(U* p, Args&&... args) {
        if constexpr (sizeof...(Args) == 0)
            if (detail::gDeferValueInit) return;
        ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
    template <class U, class B>
    bool operator==(const FirstTouchAllocator<U, B>&) const noexcept { return true; }
};

// The large arrays of a build: resizeFirstTouched value-initialises them in parallel.
template <class T>
using BuildArray = std::vector<T, FirstTouchAllocator<T>>;

namespace detail {
// Grows v to n elements within its reserved storage without writing any (FirstTouchAllocator
// skips the value-initialisation).
template <class T, class Base>
void resizeUnconstructed(std::vector<T, FirstTouchAllocator<T, Base>>& v, size_t n) {
    gDeferValueInit = true;
    v.resize(n);
    gDeferValueInit = false;
}
}  // namespace detail

// Resizes the empty vector v to n value-initialised elements.
template <class T, class Alloc>
void resizeFirstTouched(std::vector<T, Alloc>& v, size_t n) {
    constexpr bool kDeferrable = std::is_same_v<Alloc, FirstTouchAllocator<T>> && std::is_trivially_destructible_v<T>;
    if (n * sizeof(T) < kFirstTouchBytes || !v.empty()) {
        v.resize(n);
    } else if constexpr (kDeferrable) {
        // Each worker value-initialises a run of elements, which also takes that run's page faults.
        v.reserve(n);
        detail::resizeUnconstructed(v, n);
        T* data = v.data();
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, std::max<size_t>(1, (size_t(1) << 18) / sizeof(T))),
                          [data](const tbb::blocked_range<size_t>& r) {
                              for (size_t i = r.begin(); i < r.end(); ++i) ::new (static_cast<void*>(data + i)) T();
                          });
    } else {
        reservePopulated(v, n);
        v.resize(n);
    }
}

// Resizes the empty vector v to n elements that the caller writes, every one, before any is read
// (C++23's "for overwrite"): the pages are populated in parallel and no element is initialised.
// Populating costs less than faulting the pages in by touching them (the kernel maps them in bulk),
// and the value-initialisation pass it saves would be a write of the whole array that the caller's
// own write then repeats. T must be an implicit-lifetime type
// (trivially copyable and destructible), whose objects the caller's writes create.
template <class T, class Base>
void resizeForOverwrite(std::vector<T, FirstTouchAllocator<T, Base>>& v, size_t n) {
    static_assert(std::is_trivially_copyable_v<T> && std::is_trivially_destructible_v<T>);
    if (n * sizeof(T) < kFirstTouchBytes || !v.empty()) {
        v.resize(n);
        return;
    }
    reservePopulated(v, n);
    detail::resizeUnconstructed(v, n);
}

}  // namespace vkray
