#include "accel/bvh/flatten.h"

#include <algorithm>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh/quantize.h"
#include "core/error.h"
#include "core/fork_join.h"
#include "core/parallel_alloc.h"

namespace vkray::bvh {
namespace {

FlatNode makeNode(const Aabb& box, uint32_t rightOrFirst, uint32_t count) {
    FlatNode n{};
    n.lo = box.lo;
    n.hi = box.hi;
    n.rightOrFirst = rightOrFirst;
    n.count = count;
    return n;
}

class Flattener {
public:
    Flattener(const BinaryTree& tree, const CollapsedTree& collapsed, FlatBvh& out)
        : tree_(tree), collapsed_(collapsed), out_(out) {}

    // Writes the subtree of binary node `id` (at tree depth `depth`) to flat node `slot` onwards,
    // its triangles to triangleOrder[first] onwards; returns the depth of its deepest node.
    uint32_t write(uint32_t id, uint32_t slot, uint32_t first, uint32_t depth) {
        const BinaryNode& node = tree_.nodes[id];
        const CollapsedNode& self = collapsed_.nodes[id];
        if (self.leaf()) {
            const uint32_t count = self.primitives;
            gatherPrimitives(id, first);
            std::sort(out_.triangleOrder.begin() + first, out_.triangleOrder.begin() + first + count);
            out_.nodes[slot] = makeNode(node.box, first, count);
            if (!tree_.spheres.empty()) out_.spheres[slot] = tree_.spheres[id];
            return depth;
        }
        const uint32_t left = node.child[0], right = node.child[1];
        // The right subtree is written after the whole left one: ask for its first lines now (the
        // walk is bound by memory latency: nodes of a subtree lie far apart at the top).
        __builtin_prefetch(&tree_.nodes[right]);
        __builtin_prefetch(&collapsed_.nodes[right]);
        const CollapsedNode& below = collapsed_.nodes[left];
        const uint32_t rightSlot = slot + 1 + below.flatNodes;
        const uint32_t rightFirst = first + below.primitives;
        out_.nodes[slot] = makeNode(node.box, rightSlot, 0);
        if (!tree_.spheres.empty()) out_.spheres[slot] = tree_.spheres[id];
        uint32_t dl = 0, dr = 0;
        forkJoin(depth < kParallelDepth, [&] { dl = write(left, slot + 1, first, depth + 1); },
                 [&] { dr = write(right, rightSlot, rightFirst, depth + 1); });
        return std::max(dl, dr);
    }

private:
    // The primitives below binary node `id`, written from triangleOrder[first].
    void gatherPrimitives(uint32_t id, uint32_t first) {
        uint32_t stack[VKRAY_BVH_MAX_LEAF_SIZE * 2 + 2];  // a collapsed subtree has < 2 * maxLeaf nodes
        std::vector<uint32_t> big;                        // for a Config with larger leaves
        uint32_t* s = stack;
        if (collapsed_.nodes[id].primitives > VKRAY_BVH_MAX_LEAF_SIZE) {
            big.resize(2 * size_t(collapsed_.nodes[id].primitives) + 2);
            s = big.data();
        }
        size_t top = 0;
        s[top++] = id;
        while (top > 0) {
            const BinaryNode& n = tree_.nodes[s[--top]];
            if (n.isPrimitive()) {
                out_.triangleOrder[first++] = n.child[0];
            } else {
                s[top++] = n.child[1];
                s[top++] = n.child[0];
            }
        }
    }

    const BinaryTree& tree_;
    const CollapsedTree& collapsed_;
    FlatBvh& out_;
};

// A child's reference in the GPU layout: an inner node's index, or a leaf's count and first slot.
uint32_t leafRef(const FlatNode& leaf) {
    return VKRAY_BVH_LEAF_BIT | ((leaf.count - 1) << VKRAY_BVH_COUNT_SHIFT) | leaf.rightOrFirst;
}

// Half the surface area of flat node i's container: its box, or its sphere.
float halfArea(const FlatBvh& flat, uint32_t i) {
    if (!flat.spheres.empty()) return flat.spheres[i].halfArea();
    const glm::vec3 d = flat.nodes[i].hi - flat.nodes[i].lo;
    return d.x * d.y + d.y * d.z + d.z * d.x;
}

// The wide node whose children are flat nodes kids[0..n) with references `child`: their boxes
// quantised (GpuBvhNode), or their spheres (GpuBvhSphereNode).
template <class Node>
Node wideNode(const FlatBvh& flat, const uint32_t* kids, int n, const gpu::uvec4& child) {
    if constexpr (std::is_same_v<Node, gpu::GpuBvhNode>) {
        Aabb boxes[VKRAY_BVH_WIDTH];
        for (int k = 0; k < n; ++k) boxes[k] = Aabb{flat.nodes[kids[k]].lo, flat.nodes[kids[k]].hi};
        return quantizedNode(std::span<const Aabb>(boxes, size_t(n)), child);
    } else {
        Node node{};
        for (int k = 0; k < n; ++k) {
            const Sphere& sphere = flat.spheres[kids[k]];
            node.centreX[k] = sphere.centre.x;
            node.centreY[k] = sphere.centre.y;
            node.centreZ[k] = sphere.centre.z;
            node.radius[k] = sphere.radius;
        }
        node.child = child;
        return node;
    }
}

// The shape of a wide node: its children, flat nodes kids[0..n), and their references.
struct WideShape {
    uint32_t kids[VKRAY_BVH_WIDTH];
    gpu::uvec4 child;
    int n;
};

// Collapses the binary flat tree into VKRAY_BVH_WIDTH-wide nodes, depth-first: their shapes, which
// wideNodes() then turns into nodes in parallel. Only the shapes need the walk's order; quantising a
// node's boxes is independent of every other node's, and at millions of triangles it is most of
// the layout's time.
class WideWriter {
public:
    WideWriter(const FlatBvh& flat, std::vector<WideShape>& out) : flat_(flat), out_(out) {}

    // The wide node of binary inner node `i` and, below it, its subtrees; returns its index.
    uint32_t write(uint32_t i) {
        const uint32_t self = uint32_t(out_.size());
        out_.emplace_back();
        WideShape shape{};
        shape.n = gather(i, shape.kids);
        shape.child = gpu::uvec4(VKRAY_BVH_NO_CHILD);
        for (int k = 0; k < shape.n; ++k) {
            const FlatNode& kid = flat_.nodes[shape.kids[k]];
            shape.child[k] = kid.count > 0 ? leafRef(kid) : write(shape.kids[k]);
        }
        out_[self] = shape;
        return self;
    }

    // How many wide nodes write(i) makes, without making them.
    size_t count(uint32_t i) const {
        uint32_t kids[VKRAY_BVH_WIDTH];
        const int n = gather(i, kids);
        size_t total = 1;
        for (int k = 0; k < n; ++k)
            if (flat_.nodes[kids[k]].count == 0) total += count(kids[k]);
        return total;
    }

private:
    // The children of inner node i's wide node: its two children, then, while fewer than the width,
    // the inner one of largest surface area replaced by its own two (the choice of Wald, Benthin and
    // Boulos 2008). Depth-first order is kept for the rest.
    int gather(uint32_t i, uint32_t (&kids)[VKRAY_BVH_WIDTH]) const {
        int n = 0;
        kids[n++] = i + 1;
        kids[n++] = flat_.nodes[i].rightOrFirst;
        while (n < VKRAY_BVH_WIDTH) {
            int widest = -1;
            float widestArea = -1.0f;
            for (int k = 0; k < n; ++k) {
                if (flat_.nodes[kids[k]].count == 0 && halfArea(flat_, kids[k]) > widestArea) {
                    widest = k;
                    widestArea = halfArea(flat_, kids[k]);
                }
            }
            if (widest < 0) break;
            const uint32_t opened = kids[widest];
            for (int k = n; k > widest + 1; --k) kids[k] = kids[k - 1];  // right child next to its sibling
            kids[widest] = opened + 1;
            kids[widest + 1] = flat_.nodes[opened].rightOrFirst;
            ++n;
        }
        return n;
    }

    const FlatBvh& flat_;
    std::vector<WideShape>& out_;
};

template <class Node>
std::vector<Node> wideNodes(const FlatBvh& flat) {
    std::vector<Node> out;
    if (flat.nodes.empty()) return out;
    if (flat.triangleOrder.size() > VKRAY_BVH_MAX_TRIANGLES)
        throw Error("the BVH holds " + std::to_string(flat.triangleOrder.size()) +
                    " triangles; its GPU layout addresses at most " + std::to_string(VKRAY_BVH_MAX_TRIANGLES));
    if (flat.nodes[0].count > 0) {  // the root is a leaf: one node with one child
        const uint32_t root = 0;
        out.push_back(wideNode<Node>(flat, &root, 1, gpu::uvec4(leafRef(flat.nodes[0]), VKRAY_BVH_NO_CHILD,
                                                                VKRAY_BVH_NO_CHILD, VKRAY_BVH_NO_CHILD)));
        return out;
    }
    std::vector<WideShape> shapes;
    shapes.reserve(flat.nodes.size() / 4 + 1);
    WideWriter(flat, shapes).write(0);
    resizeFirstTouched(out, shapes.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, shapes.size(), 1024), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i < r.end(); ++i)
            out[i] = wideNode<Node>(flat, shapes[i].kids, shapes[i].n, shapes[i].child);
    });
    return out;
}

}  // namespace

namespace {

template <class Node>
std::vector<uint32_t> parentLinks(const std::vector<Node>& nodes) {
    if (nodes.size() > VKRAY_BVH_MAX_LINKED_NODES)
        throw Error("the BVH has " + std::to_string(nodes.size()) + " 4-wide nodes; the stackless walk's parent links name at most " +
                    std::to_string(VKRAY_BVH_MAX_LINKED_NODES));
    std::vector<uint32_t> links(nodes.size(), VKRAY_BVH_NO_PARENT);
    for (size_t i = 0; i < nodes.size(); ++i)
        for (uint32_t slot = 0; slot < VKRAY_BVH_WIDTH; ++slot) {
            const uint32_t ref = nodes[i].child[slot];
            if (ref != VKRAY_BVH_NO_CHILD && !(ref & VKRAY_BVH_LEAF_BIT) && ref < links.size())
                links[ref] = uint32_t(i) << 2 | slot;
        }
    return links;
}

}  // namespace

std::vector<gpu::GpuBvhNode> gpuNodes(const FlatBvh& flat) {
    std::vector<gpu::GpuBvhNode> nodes = wideNodes<gpu::GpuBvhNode>(flat);
    const std::vector<uint32_t> links = parentLinks(nodes);
    for (size_t i = 0; i < nodes.size(); ++i) nodes[i].planesZ.z = links[i];
    return nodes;
}

std::vector<gpu::GpuBvhSphereNode> gpuSphereNodes(const FlatBvh& flat) {
    if (flat.spheres.size() != flat.nodes.size()) throw Error("internal: a BVH without spheres has no sphere nodes");
    return wideNodes<gpu::GpuBvhSphereNode>(flat);
}

std::vector<uint32_t> gpuParentLinks(const std::vector<gpu::GpuBvhSphereNode>& nodes) { return parentLinks(nodes); }

size_t gpuNodeCount(const FlatBvh& flat) {
    if (flat.nodes.empty()) return 0;
    if (flat.nodes[0].count > 0) return 1;
    std::vector<WideShape> unused;
    return WideWriter(flat, unused).count(0);
}

FlatBvh flatten(const BinaryTree& tree, const CollapsedTree& collapsed) {
    FlatBvh flat;
    flat.sahCost = collapsed.sahCost;
    if (tree.nodes.empty()) return flat;
    resizeForOverwrite(flat.nodes, collapsed.nodes[tree.root].flatNodes);  // the walk writes each
    if (!tree.spheres.empty()) resizeFirstTouched(flat.spheres, flat.nodes.size());
    resizeFirstTouched(flat.triangleOrder, tree.primitives);
    flat.maxDepth = Flattener(tree, collapsed, flat).write(tree.root, 0, 0, 0);
    flat.leaves = uint32_t((flat.nodes.size() + 1) / 2);  // a full binary tree: leaves = inner nodes + 1
    return flat;
}

}  // namespace vkray::bvh
