// Morton codes of triangle centroids and their parallel radix sort: the first step of AAC (Gu et al. 2013;
// A. F. Mahmuda, "Bounding Volume Hierarchy Construction Using Agglomerative Clustering for Faster Ray
// Tracing", thesis, ITS 2017, listings 2.1 and 4.6), which orders the primitives along a Z-order curve so
// that the downward phase can split ranges by the codes' bits.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "accel/bvh/bvh.h"
#include "scene/scene.h"

namespace vkray::bvh {

// 10 bits per axis, 30 bits in all (Mahmuda 2017's layout, listing 4.6: x in the highest bit of each
// triple, then y, then z). At 1024 cells per axis a 1M-triangle mesh has about one centroid per
// occupied cell; ranges of equal codes are split in the middle by the builder.
inline constexpr int kMortonBitsPerAxis = 10;
inline constexpr int kMortonBits = 3 * kMortonBitsPerAxis;

// Spreads the low 10 bits of v so that two zero bits follow each one (bit i moves to bit 3i).
uint32_t expandBits(uint32_t v);

// The Morton code of point p quantised within `bounds` (a zero extent maps to cell 0).
uint32_t mortonCode(const glm::vec3& p, const Aabb& bounds);

// A primitive keyed by its code: code in the high 32 bits, primitive index in the low 32 bits.
using MortonKey = uint64_t;
inline uint32_t keyCode(MortonKey k) { return uint32_t(k >> 32); }
inline uint32_t keyPrimitive(MortonKey k) { return uint32_t(k); }

// The key of every centroid (its code within their common bounds, its index), computed in parallel
// straight into the array the sort takes: no separate array of codes to fault in and read again.
BuildArray<MortonKey> mortonKeys(std::span<const glm::vec3> centroids, const Aabb& centroidBounds);

// Sorts by code, stably (equal codes keep their primitive order), with a least-significant-digit
// radix sort of 10-bit digits (three passes for 30-bit codes; Mahmuda 2017, section 2.8). Each pass
// histograms and scatters fixed blocks in parallel (oneTBB); the blocks do not depend on the thread
// count, and a stable sort has one answer anyway.
void radixSortByCode(BuildArray<MortonKey>& keys);

// The triangles' indices in the Morton order of their centroids (ties in index order): the order
// the driver's structure is built over (`rayquery`, gpu/driver_structure.h).
std::vector<uint32_t> mortonOrder(std::span<const Triangle> triangles);

}  // namespace vkray::bvh
