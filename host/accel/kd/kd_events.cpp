#include "accel/kd/kd_events.h"

#include <algorithm>
#include <optional>

#include <tbb/parallel_for.h>

#include "accel/kd/kd_clip.h"

namespace vkray::accel::kd {

// The root's events, unsorted, and its box (left as it is when every triangle is degenerate, which
// have no events), made in parallel: each block of triangles counts its events, a prefix over the
// blocks places them, and each block writes its own in triangle order, so every axis's list
// ascends by triangle as one thread's appends would make it, while the appends and their page
// faults are spread over the workers.
NodeEvents rootEvents(const std::vector<Triangle>& tris, const std::vector<uint8_t>& degenerate, Box& root) {
    constexpr size_t kBlock = size_t(1) << 14;
    const size_t blocks = (tris.size() + kBlock - 1) / kBlock;
    const auto forEachTriangle = [&](size_t block, const auto& f) {
        for (size_t t = block * kBlock, end = std::min(tris.size(), t + kBlock); t < end; ++t)
            if (!degenerate[t]) f(uint32_t(t), boundsOf(tris[t]));
    };
    // The union of boxes, min and max: exact in any order.
    const auto grow = [](std::optional<Box>& box, const Box& b) {
        box = box ? Box{glm::min(box->lo, b.lo), glm::max(box->hi, b.hi)} : b;
    };
    std::vector<std::array<size_t, 3>> first(blocks + 1, std::array<size_t, 3>{});  // block b's first event per axis
    std::vector<std::optional<Box>> boxes(blocks);
    tbb::parallel_for(size_t(0), blocks, [&](size_t block) {
        std::array<size_t, 3>& count = first[block + 1];
        forEachTriangle(block, [&](uint32_t t, const Box& b) {
            grow(boxes[block], b);
            forEachEvent(t, b, [&](int k, const Event&) { ++count[k]; });
        });
    });
    std::optional<Box> all;
    for (size_t block = 0; block < blocks; ++block) {
        for (int k = 0; k < 3; ++k) first[block + 1][k] += first[block][k];
        if (boxes[block]) grow(all, *boxes[block]);
    }
    if (all) root = *all;
    NodeEvents ev;
    for (int k = 0; k < 3; ++k) resizeForOverwrite(ev[k], first[blocks][k]);
    tbb::parallel_for(size_t(0), blocks, [&](size_t block) {
        std::array<Event*, 3> out{};
        for (int k = 0; k < 3; ++k) out[k] = ev[k].data() + first[block][k];
        forEachTriangle(block, [&](uint32_t t, const Box& b) {
            forEachEvent(t, b, [&](int k, const Event& e) { *out[k]++ = e; });
        });
    });
    return ev;
}

// How many triangles the node holds: each has exactly one start or planar event on every axis.
size_t triangleCount(const NodeEvents& ev) {
    return size_t(std::count_if(ev[0].begin(), ev[0].end(), [](const Event& e) { return e.type() != EventType::End; }));
}

}  // namespace vkray::accel::kd
