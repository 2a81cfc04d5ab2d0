#include "accel/kd/kd_split.h"

#include <algorithm>

#include "accel/kd/kd_clip.h"
#include "accel/kd/kd_cost.h"

namespace vkray::accel::kd {

// With their classification: at plane p, below = triangles starting before p (those ending at p
// touch it from below), above = triangles ending after p (those starting at p touch it from above);
// triangles flat in p are tried on each side. A split whose two sides together hold more
// references than `budget` is not a candidate (the half absorbs the rounding of budgets handed down
// in proportion: counts are whole).
void sweepEvents(int axis, EventSpan ev, const Box& box, double invArea, size_t n, double budget,
                 const KdConfig& config, SplitChoice& best) {
    const AxisCost cost(box, axis, invArea, config);
    int64_t startedBefore = 0, endingAfter = int64_t(n);
    const Event* e = ev.data();
    const Event* const end = e + ev.size();
    while (e != end) {
        const float p = e->pos();
        const uint32_t at = e->orderedPos();
        // The events at p, counted by type without branching on it: ends and starts alternate
        // unpredictably along an axis, and a branch on the type would be mispredicted half the time.
        int64_t ends = 0, planars = 0, starts = 0;
        do {
            const EventType type = e->type();
            ends += type == EventType::End;
            planars += type == EventType::Planar;
            starts += type == EventType::Start;
        } while (++e != end && e->orderedPos() == at);
        endingAfter -= ends + planars;
        if (usableSplit(box, axis, p) && double(startedBefore + endingAfter + planars) <= budget + 0.5) {
            const int64_t below = startedBefore, above = endingAfter;
            // Without planar triangles both placements are the same split, costed once.
            const double planarBelowCost = cost(p, below + planars, above);
            const double planarAboveCost = planars == 0 ? planarBelowCost : cost(p, below, above + planars);
            const bool planarBelow = planarBelowCost <= planarAboveCost;
            const double c = planarBelow ? planarBelowCost : planarAboveCost;
            if (c < best.cost)
                best = SplitChoice{axis, p, planarBelow, c, size_t(below + (planarBelow ? planars : 0)),
                                   size_t(above + (planarBelow ? 0 : planars))};
        }
        startedBefore += starts + planars;
    }
}

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
