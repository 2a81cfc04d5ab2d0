// Approximate Agglomerative Clustering (Gu, He, Fatahalian and Blelloch, "Efficient BVH Construction
// via Approximate Agglomerative Clustering", HPG 2013; as implemented in A. F. Mahmuda, "Bounding
// Volume Hierarchy Construction Using Agglomerative Clustering for Faster Ray Tracing", thesis,
// ITS 2017: sections 2.6 and 3.3.2, listings 3.1-3.3 and 4.8-4.11).
//
// 1. Morton codes of the centroids, radix-sorted (morton.h).
// 2. Downward phase (the paper's BuildTree): a range of more than delta primitives is split at the
//    highest bit in which its first and last codes differ, found by binary search (the codes are
//    sorted, so the range holds all codes with that bit clear, then all with it set); a range whose
//    codes are all equal is split in the middle, its primitives ordered by box area after the sort
//    (aac_builder.cpp, orderTiedRuns).
// 3. Upward phase: every range clusters the clusters of its two halves agglomeratively (the
//    paper's CombineClusters: merge the pair whose merged box has the smallest surface area,
//    with each cluster's closest partner cached and recomputed only when that partner merges) until
//    f(n) clusters remain for its n primitives; a range of at most delta primitives starts from
//    its primitives and keeps f(delta) = delta / 2. The root combines what is left into one. Ties
//    go to the lowest position, except among clusters of equal boxes, such as copies of a
//    triangle, which merge so as to fill the collapsed leaves (aac_builder.cpp,
//    equalContainerPair).
//
// Independent ranges run as oneTBB tasks. No decision depends on the thread count or on the order
// tasks finish, and neither do node ids: each range merges into its own region of the node array
// (aac_builder.cpp, "Node slots"), so the binary tree is byte-identical for any number of threads.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "accel/bvh/bvh.h"
#include "accel/bvh/leaf_collapse.h"
#include "accel/bvh/primitives.h"
#include "core/phase_log.h"

namespace vkray::bvh {

// The paper's cluster count reduction function: f(n) = c * n^alpha, alpha = 1/2 - epsilon,
// c = delta^(1/2 + epsilon) / 2 (so f(delta) = delta / 2), rounded down and at least 1.
struct AacReduction {
    AacReduction(int delta, double epsilon);
    size_t operator()(size_t n) const { return n < small_.size() ? small_[n] : compute(n); }

    double c, alpha;

private:
    size_t compute(size_t n) const;
    // f(n) for the range sizes a build asks for most: one per range of the recursion, and all but a
    // few hundred of a million-triangle build's are this small, so a table lookup replaces a pow in
    // nearly every call (Gu et al. 2013's f(n) = c n^alpha).
    std::vector<uint32_t> small_;
};
size_t aacReduction(size_t n, int delta, double epsilon);

// Throws vkray::Error when delta < 1 or epsilon is outside [0, 1/2) (alpha must stay positive).
void validateAacConfig(const Config& config);

// Builds the AAC tree of `prims` on the calling thread's oneTBB arena; phases "morton", "sort" and
// "cluster" go to `log`. With `collapsed`, also the tree's leaf collapse, recorded as the clusters
// merge (leaf_collapse.h, CollapseRecorder): equal to collapseLeaves() of the returned tree.
BinaryTree buildAac(const PrimitiveSet& prims, const Config& config, PhaseLog& log,
                    CollapsedTree* collapsed = nullptr);

}  // namespace vkray::bvh
