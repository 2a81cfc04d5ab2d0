#include "accel/bvh/reinsert.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace vkray::bvh {
namespace {

constexpr uint32_t kNone = 0xFFFFFFFFu;

// The stopping rule: the best surface-area sum of the last kPatience iterations is not 0.1% below
// the best before them.
constexpr int kPatience = 3;
constexpr double kLeastGain = 1e-3;

bool sameBox(const Aabb& a, const Aabb& b) { return a.lo == b.lo && a.hi == b.hi; }

class Reinserter {
public:
    Reinserter(BinaryTree& tree, const Config& config)
        : tree_(tree), config_(config), parent_(tree.nodes.size(), kNone), reused_(tree.nodes.size(), 0) {
        for (uint32_t id = 0; id < tree.nodes.size(); ++id) {
            const BinaryNode& n = tree.nodes[id];
            if (n.isPrimitive()) continue;
            parent_[n.child[0]] = id;
            parent_[n.child[1]] = id;
        }
    }

    // The surface-area sum of the inner nodes over the root's: what the insertions lower.
    double innerAreaSum() const {
        double sum = 0.0;
        for (const BinaryNode& n : tree_.nodes)
            if (!n.isPrimitive()) sum += n.box.halfArea();
        const double root = tree_.nodes[tree_.root].box.halfArea();
        return root > 0.0 ? sum / root : sum;
    }

    void iterate() {
        std::vector<std::pair<double, uint32_t>> worst = rankCandidates();
        std::fill(reused_.begin(), reused_.end(), 0);
        for (const auto& [measure, id] : worst) {
            // A node freed earlier in this batch and reused as a new parent is no longer the node ranked.
            if (reused_[id] || id == tree_.root) continue;
            const BinaryNode node = tree_.nodes[id];
            const uint32_t freed = detach(id);
            reused_[id] = reused_[freed] = 1;
            // The larger child first: it has the more to lose from a poor place.
            const bool firstLarger =
                tree_.nodes[node.child[0]].box.halfArea() >= tree_.nodes[node.child[1]].box.halfArea();
            insert(node.child[firstLarger ? 0 : 1], id);
            insert(node.child[firstLarger ? 1 : 0], freed);
        }
    }

private:
    // Section 4.2: the inner nodes but the root, by M_sum * M_min * M_area = A^3 / (mean child area *
    // least child area); the worst Config::reinsertBatch of them, worst first.
    std::vector<std::pair<double, uint32_t>> rankCandidates() {
        std::vector<std::pair<double, uint32_t>> ranked;
        // Between iterations every node is in the tree (a batch reinserts all it removes).
        for (uint32_t id = 0; id < tree_.nodes.size(); ++id) {
            const BinaryNode& n = tree_.nodes[id];
            if (n.isPrimitive() || id == tree_.root) continue;
            const double a = n.box.halfArea();
            const double a0 = tree_.nodes[n.child[0]].box.halfArea(), a1 = tree_.nodes[n.child[1]].box.halfArea();
            const double denominator = 0.5 * (a0 + a1) * std::min(a0, a1);
            const double m = denominator > 0.0 ? a * a * a / denominator : std::numeric_limits<double>::max();
            ranked.emplace_back(m, id);
        }
        const size_t wanted = size_t(std::ceil(config_.reinsertBatch * double(ranked.size())));
        const size_t batch = std::min(ranked.size(), std::max<size_t>(1, wanted));
        const auto worse = [](const auto& x, const auto& y) {
            return x.first > y.first || (x.first == y.first && x.second < y.second);
        };
        std::nth_element(ranked.begin(), ranked.begin() + batch, ranked.end(), worse);
        ranked.resize(batch);
        std::sort(ranked.begin(), ranked.end(), worse);
        return ranked;
    }

    // Grows the boxes from `id` up to the root, stopping where a box does not change.
    void refit(uint32_t id) {
        for (; id != kNone; id = parent_[id]) {
            BinaryNode& n = tree_.nodes[id];
            const Aabb box = Aabb::merged(tree_.nodes[n.child[0]].box, tree_.nodes[n.child[1]].box);
            if (sameBox(box, n.box)) return;
            n.box = box;
        }
    }

    // Puts `to` where `from` hangs (under from's parent, or as the root).
    void replaceChild(uint32_t from, uint32_t to) {
        const uint32_t p = parent_[from];
        parent_[to] = p;
        if (p == kNone) {
            tree_.root = to;
            return;
        }
        BinaryNode& n = tree_.nodes[p];
        n.child[n.child[0] == from ? 0 : 1] = to;
        refit(p);
    }

    // Takes node `id` out with its parent, whose place its sibling takes; returns the parent, now free.
    uint32_t detach(uint32_t id) {
        const uint32_t p = parent_[id];
        const BinaryNode& pn = tree_.nodes[p];
        const uint32_t sibling = pn.child[pn.child[0] == id ? 1 : 0];
        replaceChild(p, sibling);
        return p;
    }

    // Section 4.1: the node beside which `x` adds least area: the new parent's area plus the growth
    // of every ancestor (the induced cost), searched best first and cut where even an empty growth
    // from here on (the new parent at least as large as x) could not win.
    uint32_t bestSibling(const Aabb& box) {
        const auto later = std::greater<Entry>();  // a min-heap on (induced cost, id): ties by id
        open_.clear();
        const double area = box.halfArea();
        double best = std::numeric_limits<double>::infinity();
        uint32_t bestId = tree_.root;
        open_.emplace_back(0.0, tree_.root);
        while (!open_.empty()) {
            std::pop_heap(open_.begin(), open_.end(), later);
            const auto [induced, id] = open_.back();
            open_.pop_back();
            if (induced + area >= best) break;
            const BinaryNode& n = tree_.nodes[id];
            const double total = induced + Aabb::merged(n.box, box).halfArea();
            if (total < best) {
                best = total;
                bestId = id;
            }
            if (n.isPrimitive()) continue;
            const double below = total - n.box.halfArea();
            if (below + area >= best) continue;
            for (const uint32_t child : n.child) {
                open_.emplace_back(below, child);
                std::push_heap(open_.begin(), open_.end(), later);
            }
        }
        return bestId;
    }

    // Inserts subtree `x` beside its best sibling, under the free node `parent`.
    void insert(uint32_t x, uint32_t parent) {
        const uint32_t sibling = bestSibling(tree_.nodes[x].box);
        BinaryNode& p = tree_.nodes[parent];
        p.child[0] = sibling;
        p.child[1] = x;
        p.box = Aabb::merged(tree_.nodes[sibling].box, tree_.nodes[x].box);
        replaceChild(sibling, parent);  // before the links below: it reads sibling's old parent
        parent_[sibling] = parent;
        parent_[x] = parent;
    }

    BinaryTree& tree_;
    const Config& config_;
    std::vector<uint32_t> parent_;
    std::vector<uint8_t> reused_;
    using Entry = std::pair<double, uint32_t>;
    std::vector<Entry> open_;  // the search's queue, kept between searches
};

}  // namespace

int reinsertNodes(BinaryTree& tree, const Config& config) {
    if (tree.nodes.size() < 5 || config.reinsertIterations <= 0) return 0;
    Reinserter reinserter(tree, config);
    std::vector<double> cost{reinserter.innerAreaSum()};
    for (int i = 0; i < config.reinsertIterations; ++i) {
        reinserter.iterate();
        cost.push_back(reinserter.innerAreaSum());
        const size_t n = cost.size();
        if (n > kPatience && *std::min_element(cost.end() - kPatience, cost.end()) >
                                 (1.0 - kLeastGain) * *std::min_element(cost.begin(), cost.end() - kPatience))
            break;
    }
    return int(cost.size()) - 1;
}

}  // namespace vkray::bvh
