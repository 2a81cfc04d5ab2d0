// The SAH kd-tree builder's tree before its GPU layout (sah_kd_builder.cpp), and its flattening
// into that layout (kd_flatten.cpp).
#pragma once

#include <cstdint>
#include <memory>
#include <new>
#include <utility>
#include <vector>

#include <tbb/scalable_allocator.h>

#include "accel/kd/kd_tree.h"

namespace vkray::accel::kd {

// A leaf's triangle list. The tree's millions of nodes and leaf lists come from oneTBB's scalable
// allocator: from glibc's, their frees pile up until the next large free merges them all on one
// thread (malloc_consolidate), a serial pause at the end of every large build.
using TriangleList = std::vector<uint32_t, tbb::scalable_allocator<uint32_t>>;

struct BuildNode;
// Frees a build node, except kEmptyLeaf.
struct NodeDeleter {
    void operator()(BuildNode* node) const;
};
using NodePtr = std::unique_ptr<BuildNode, NodeDeleter>;

// A subtree under kTimedEvents events (sah_kd_builder.cpp), built on one worker straight in the flat layout
// (kd_layout.h) with indices relative to its root: its above-child links and its leaves' first
// entries are offsets that flatten() adds its place to. Millions of small nodes are then written
// once, not allocated as build nodes, walked and freed.
using FlatSubtree = std::vector<gpu::KdNode, tbb::scalable_allocator<gpu::KdNode>>;

struct BuildNode {
    static constexpr int kLeaf = -1, kFlat = -2;
    int axis = kLeaf;  // 0-2: inner node
    float split = 0.0f;
    uint32_t subtreeNodes = 1;  // nodes of its subtree, itself included (the flat layout's offsets)
    uint64_t subtreeRefs = 0;   // index-list entries of its subtree's leaves
    NodePtr below, above;
    TriangleList triangles;  // a leaf's, ascending; a flat subtree's index list
    FlatSubtree flat;        // kFlat only

    bool emptyLeaf() const { return axis == kLeaf && triangles.empty(); }

    static void* operator new(size_t bytes) {
        if (void* p = scalable_malloc(bytes)) return p;
        throw std::bad_alloc();
    }
    static void operator delete(void* p) { scalable_free(p); }
};

// The one empty leaf that every empty leaf of every tree is: a tree over small triangles has
// millions, each else allocated, walked and freed. Never changed.
inline BuildNode kEmptyLeaf;

inline void NodeDeleter::operator()(BuildNode* node) const {
    if (node != &kEmptyLeaf) delete node;
}

// Depth-first layout (kd_layout.h): below child next, above child by index. Writes the subtree of
// `n` at node `index` and index-list entry `first` onwards, whose places its subtree sizes give, so
// the subtrees near the root are written as parallel tasks; it consumes the tree, which is then
// freed in parallel too (millions of nodes and leaf lists freed one by one would be a serial tail
// of the build). The nodes' boxes and parent links are not written here: deriveNodeExtras
// (kd_tree.h) derives them from the nodes where a traversal needs them.
void flattenKdTree(NodePtr n, uint32_t index, uint64_t first, KdTree& out, int depth);

}  // namespace vkray::accel::kd
