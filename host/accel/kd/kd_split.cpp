#include "accel/kd/kd_split.h"

#include <algorithm>

#include "accel/kd/kd_clip.h"

namespace vkray::accel::kd {

// One pass in sorted order, where a triangle's start comes before its end: ending at or before the
// plane = below only, starting at or after it = above only (Wald and Havran 5.1); a planar one goes
// where the split chose; the rest straddle.
void ListSplitter::classify(EventSpan splitAxis, const SplitPlane& s, size_t triangleCount) {
    if (side_.size() < triangleCount) side_.resize(triangleCount);
    const uint32_t split = Event::orderedBits(s.pos);
    straddling_.clear();
    for (const Event& e : splitAxis) {
        const uint32_t at = e.orderedPos(), tri = e.triangle();
        switch (e.type()) {
        case EventType::Start: side_[tri] = at >= split ? Side::AboveOnly : Side::Both; break;
        case EventType::End:
            if (at <= split) side_[tri] = Side::BelowOnly;
            else if (side_[tri] == Side::Both) straddling_.push_back(tri);
            break;
        case EventType::Planar:
            side_[tri] = at < split || (at == split && s.planarBelow) ? Side::BelowOnly : Side::AboveOnly;
            break;
        }
    }
}

void ListSplitter::clip(const std::vector<Triangle>& tris, const Box& below, const Box& above, int axis) {
    for (NodeEvents& fresh : fresh_)
        for (AxisEvents& f : fresh) f.clear();
    for (uint32_t tri : straddling_) {
        const auto [inBelow, inAbove] = clippedBoundsOfSplit(tris[tri], below, above, axis);
        appendEvents(tri, inBelow, fresh_[0]);
        appendEvents(tri, inAbove, fresh_[1]);
    }
}

void sortFresh(AxisEvents& fresh) {
    if (fresh.size() >= 32) {
        std::sort(fresh.begin(), fresh.end());
        return;
    }
    for (size_t i = 1; i < fresh.size(); ++i) {
        const Event x = fresh[i];
        size_t j = i;
        for (; j > 0 && x < fresh[j - 1]; --j) fresh[j] = fresh[j - 1];
        fresh[j] = x;
    }
}

}  // namespace vkray::accel::kd
