// Splitting a node's event lists at a chosen plane, for the SAH kd-tree builder
// (sah_kd_builder.h): Wald and Havran, "On building fast kd-Trees for Ray Tracing, and on doing that
// in O(N log N)", IEEE Symposium on Interactive Ray Tracing 2006, sections 5.2-5.3. The lists are
// read as spans and written through sinks, so the same steps serve lists in vectors of their own
// (big nodes) and lists on a worker's stack (small subtrees).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "accel/kd/kd_events.h"
#include "accel/kd/kd_tree.h"
#include "scene/scene.h"

namespace vkray::accel::kd {

using EventSpan = std::span<const Event>;
using NodeSpans = std::array<EventSpan, 3>;

inline NodeSpans spansOf(const NodeEvents& ev) { return {EventSpan(ev[0]), EventSpan(ev[1]), EventSpan(ev[2])}; }

struct SplitPlane {
    int axis = 0;
    float pos = 0.0f;
    bool planarBelow = true;  // where triangles lying in the plane go
};

// One worker's splitter: what it reuses from node to node instead of allocating it anew. The side
// marks are indexed by triangle (Wald and Havran 5.2); marks and new events hold one split's state,
// from classify() to the last distribute().
class ListSplitter {
public:
    // Marks each triangle's side from the split axis's events (a start comes before its triangle's
    // end) and collects the straddlers. triangleCount: the scene's.
    void classify(EventSpan splitAxis, const SplitPlane& s, size_t triangleCount);
    // Clips the straddlers to both children ("perfect splits", 4.3): their new events, unsorted.
    void clip(const std::vector<Triangle>& tris, const Box& below, const Box& above, int axis);
    // Axis k's one-sided events to their child in order, the straddlers' new events sorted and
    // merged in on the way (one pass, where a merge after the copy would move the events again):
    // toBelow(e) and toAbove(e) take them in ascending order. Different axes may run at once.
    template <class Below, class Above>
    void distribute(int k, EventSpan ev, const Below& toBelow, const Above& toAbove);

private:
    enum class Side : uint8_t { Both, BelowOnly, AboveOnly };
    std::vector<Side> side_;
    std::vector<uint32_t> straddling_;
    std::array<NodeEvents, 2> fresh_;  // the straddlers' events in the child below, above
};

// Sorts a straddlers' list of new events: a few in most nodes, by insertion below 32, without
// std::sort's set-up.
void sortFresh(AxisEvents& fresh);

template <class Below, class Above>
void ListSplitter::distribute(int k, EventSpan ev, const Below& toBelow, const Above& toAbove) {
    AxisEvents &newBelow = fresh_[0][k], &newAbove = fresh_[1][k];
    sortFresh(newBelow);
    sortFresh(newAbove);
    const Event *nextBelow = newBelow.data(), *nextAbove = newAbove.data();
    const Event *const endBelow = nextBelow + newBelow.size(), *const endAbove = nextAbove + newAbove.size();
    for (const Event& e : ev) {
        const Side where = side_[e.triangle()];
        if (where == Side::BelowOnly) {
            while (nextBelow != endBelow && *nextBelow < e) toBelow(*nextBelow++);
            toBelow(e);
        } else if (where == Side::AboveOnly) {
            while (nextAbove != endAbove && *nextAbove < e) toAbove(*nextAbove++);
            toAbove(e);
        }
    }
    while (nextBelow != endBelow) toBelow(*nextBelow++);
    while (nextAbove != endAbove) toAbove(*nextAbove++);
}

}  // namespace vkray::accel::kd
