// The events of the SAH kd-tree builder (sah_kd_builder.h): Wald and Havran, "On building fast
// kd-Trees for Ray Tracing, and on doing that in O(N log N)", IEEE Symposium on Interactive Ray
// Tracing 2006, section 4.2.
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/kd/kd_tree.h"
#include "core/parallel_alloc.h"
#include "scene/scene.h"

namespace vkray::accel::kd {

// Wald and Havran 2006, section 4.2: at equal positions, ends sort before planars before starts,
// which is the order the sweep needs to count each side.
enum class EventType : uint8_t { End = 0, Planar = 1, Start = 2 };

// An event in 8 bytes that are also its sort key: the position's bits turned to sort like the float
// (top 32), the type (2 bits), the triangle (30 bits). Integer order is the sweep's order: position,
// then ends < planars < starts, then triangle, a total order, so the sort, hence the tree, is
// deterministic. 8 bytes instead of the 12 of the fields side by side, in lists that are most of
// the build's memory traffic.
class Event {
public:
    static constexpr uint32_t kMaxTriangles = 1u << 30;

    Event() = default;  // for the radix sort's scratch list
    Event(float pos, uint32_t triangle, EventType type)
        : key_(uint64_t(orderedBits(pos)) << 32 | uint64_t(type) << 30 | triangle) {}

    float pos() const {
        const uint32_t u = orderedPos();
        return std::bit_cast<float>(u & 0x80000000u ? u & 0x7fffffffu : ~u);
    }
    // The position as orderedBits() made it: compares like the float, without decoding it.
    uint32_t orderedPos() const { return uint32_t(key_ >> 32); }
    EventType type() const { return EventType((key_ >> 30) & 3u); }
    uint32_t triangle() const { return uint32_t(key_) & (kMaxTriangles - 1); }
    bool operator<(const Event& o) const { return key_ < o.key_; }
    uint64_t key() const { return key_; }

    // Positive floats above negative ones, each in numeric order; -0 is made +0 first, so equal
    // positions have equal bits.
    static uint32_t orderedBits(float f) {
        const uint32_t u = std::bit_cast<uint32_t>(f + 0.0f);
        return u & 0x80000000u ? ~u : u | 0x80000000u;
    }

private:
    uint64_t key_ = 0;
};

// The lists of nodes of at least kSmallSubtreeEvents events (smaller subtrees keep theirs on a
// per-worker stack, sah_kd_builder.cpp): thousands, up to megabytes each, made level by level as
// their parents' are freed. From glibc's allocator, which hands a freed list's memory to the next
// level's (its mmap threshold rises to the sizes freed, up to 32 MiB a list), so a level writes
// to pages already mapped; oneTBB's scalable allocator mapped fresh pages for every level, and
// the page faults were three quarters of the lists' split at the big nodes (1M-triangle grid,
// 2 threads: 628 against 132-159 ms of the workers).
using AxisEvents = std::vector<Event, FirstTouchAllocator<Event>>;
using NodeEvents = std::array<AxisEvents, 3>;

// The events of one triangle from its clipped bounds `b` (Wald and Havran 4.2), f(k, event) for
// each: on axis k a planar event where the clipped part is flat on that axis, a start and an end
// otherwise. Flat clipped parts are not only triangles lying in an axis plane: a triangle that
// meets the node only in an edge or a point on the node's face is flat there too, and a planar
// event gives it exactly one side at any later split.
template <class F>
void forEachEvent(uint32_t triangle, const Box& b, const F& f) {
    for (int k = 0; k < 3; ++k) {
        if (b.lo[k] == b.hi[k]) {
            f(k, Event{b.lo[k], triangle, EventType::Planar});
        } else {
            f(k, Event{b.lo[k], triangle, EventType::Start});
            f(k, Event{b.hi[k], triangle, EventType::End});
        }
    }
}

inline void appendEvents(uint32_t triangle, const Box& b, NodeEvents& out) {
    forEachEvent(triangle, b, [&](int k, const Event& e) { out[k].push_back(e); });
}

// The root's events, unsorted, and its box (left as it is when every triangle is degenerate: they
// have no events), made in parallel (kd_events.cpp).
NodeEvents rootEvents(const std::vector<Triangle>& tris, const std::vector<uint8_t>& degenerate, Box& root);

// How many triangles the node holds: each has exactly one start or planar event on every axis.
size_t triangleCount(const NodeEvents& ev);

}  // namespace vkray::accel::kd
