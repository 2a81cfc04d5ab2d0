// The one definition of the kd-tree's GPU layout, shared by the host (C++) and the kd kernels
// (GLSL, shaders/include/kd_common.glsl). See docs/kdtree.md for the whole picture.
//
// View VKRAY_BINDING_NODE_TEXELS (RG32UI): KdTreeHeader (32 bytes), then KdNode[nodeCount] (8 bytes each)
//   in depth-first order: an inner node's first (below) child is the next node, its above child is
//   named by index. The root is node 0.
// View VKRAY_BINDING_INDEX_TEXELS (R32UI): uint[] — the leaves' triangle-index lists, back to back;
//   an entry is an index into the triangles buffer.
// View VKRAY_BINDING_EXTRA_TEXELS (RGBA32UI): KdNodeExtra[nodeCount] (32 bytes each), kd-backtrack only:
//   parent link and node box (Foley and Sugerman 2005, section 4.2). Kept out of KdNode so that
//   kd-stack and kd-restart read (and upload) 8 bytes per node, not 40.
// Or, for kd-ropes only: KdRopeRecord[nodeCount] (48 bytes each): every node's box and each leaf's
//   six ropes (Popov, Guenther, Seidel and Slusallek 2007, section 3.1), the same binding since no
//   kernel reads both.
//
// KdNode is pbrt's 8-byte node (Pharr, Jakob, Humphreys, "Physically Based Rendering", 3rd ed.,
// section 4.4.1), two 32-bit words:
//   inner: word0 = split position (float bits),
//          word1 = aboveChild << 4 | aboveIsEmptyLeaf << 3 | belowIsEmptyLeaf << 2 | axis (0, 1, 2)
//   leaf:  word0 = first entry in the index list,  word1 = triangleCount << 2 | 3
// The two flag bits let a traversal step past an empty near child without visiting it (kd_common.glsl,
// kdStepInner): such a leaf holds nothing to test, and the segment goes on at the split plane.
// The split is a plain float: the builder never chooses a denormal split, so a driver that flushes
// denormals (lavapipe does, see gpu_layout.h) reads back exactly the value the builder used.
#ifndef VKRAY_KD_LAYOUT_H
#define VKRAY_KD_LAYOUT_H

#ifdef __cplusplus
#include <bit>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <glm/glm.hpp>
namespace vkray::gpu {
using vec3 = glm::vec3;
using uint = uint32_t;
#define VKRAY_KD_STRUCT(name) struct alignas(16) name
#else
#define VKRAY_KD_STRUCT(name) struct name
#endif

// word1 & 3 of a leaf; 0..2 is an inner node's split axis.
#define VKRAY_KD_LEAF_TAG 3u
// An inner node's word1: the flag bits saying its below or above child is a leaf without triangles,
// and the shift of the above child's index.
#define VKRAY_KD_EMPTY_BELOW 4u
#define VKRAY_KD_EMPTY_ABOVE 8u
#define VKRAY_KD_CHILD_SHIFT 4u
// Largest tree depth the builder produces; the kd-stack kernel's per-ray stack holds this many
// entries (a push happens at most once per level). 8 + 1.3 log2 N (pbrt's default) stays below it
// for any N a 32-bit index can name.
#define VKRAY_KD_MAX_DEPTH 56
#define VKRAY_KD_STACK_SIZE 56
// Entries of kd-shortstack's stack (Horn et al. 2007): a push onto a full one drops the oldest.
#define VKRAY_KD_SHORT_STACK_SIZE 4
// Most nodes a tree may have: kd-stack keeps a node index in the bits below
// VKRAY_KD_STACK_AXIS_SHIFT of a stack word and an axis above them.
#define VKRAY_KD_STACK_AXIS_SHIFT 28u
#define VKRAY_KD_MAX_NODES (1u << VKRAY_KD_STACK_AXIS_SHIFT)
#define VKRAY_KD_STACK_NODE_MASK (VKRAY_KD_MAX_NODES - 1u)
// Set in a stack word whose node is a leaf without triangles (its parent's flag bits), above the axis.
#define VKRAY_KD_STACK_EMPTY_LEAF (1u << (VKRAY_KD_STACK_AXIS_SHIFT + 2u))
// The nodes binding read as RG32UI texels (VKRAY_BINDING_NODE_TEXELS): texel i + VKRAY_KD_HEADER_TEXELS
// is node i.
#define VKRAY_KD_NODE_TEXEL_BYTES 8
#define VKRAY_KD_HEADER_TEXELS 4

// KdNodeExtra.parent of the root.
#define VKRAY_KD_NO_PARENT 0xffffffffu
// A rope across a face of the root box: the ray leaves the tree there.
#define VKRAY_KD_NO_ROPE 0xffffffffu
// Texels (RGBA32UI) of one KdRopeRecord record.
#define VKRAY_KD_ROPE_TEXELS 3
// Hard caps on one traversal's loop iterations (one iteration = one node visited, or one
// backtracking step). A ray that reaches its cap is a runaway (a malformed tree, or a floating-point
// case nobody foresaw): it ends as a miss and is counted (GpuPixel.capped), never hidden. Far above
// what any sane ray needs: kd-restart pays depth x leaves, e.g. 40 x 100.
#define VKRAY_KD_MAX_STEPS 16384

VKRAY_KD_STRUCT(KdTreeHeader) {  // 32 bytes, at offset 0 of the nodes binding
    vec3 lo;         // root box (the scene's bounds)
    uint nodeCount;
    vec3 hi;
    uint indexCount;
};

VKRAY_KD_STRUCT(KdNodeExtra) {  // 32 bytes
    vec3 lo;      // the node's box
    uint parent;  // VKRAY_KD_NO_PARENT for the root
    vec3 hi;
    uint pad0;
};

// A node's box and, for a leaf, its ropes: rope f = 2 axis + side (side 1: the face at hi[axis])
// names the smallest node whose box holds the whole face f, on its other side ("optimised ropes",
// Popov et al. 2007, section 3.1), or VKRAY_KD_NO_ROPE on the root box (and for inner nodes). The box
// is read where a rope leads: the walk clips the rest of the ray to it. Texels: (lo, rope0),
// (hi, rope1), (rope2, rope3, rope4, rope5).
VKRAY_KD_STRUCT(KdRopeRecord) {  // 48 bytes
    vec3 lo;
    uint ropeLoX;
    vec3 hi;
    uint ropeHiX;
    uint ropeLoY;
    uint ropeHiY;
    uint ropeLoZ;
    uint ropeHiZ;
};

#ifdef __cplusplus
#undef VKRAY_KD_STRUCT

struct KdNode {  // 8 bytes
    uint32_t word0 = 0;
    uint32_t word1 = VKRAY_KD_LEAF_TAG;

    // Range-checked factories: the packing leaves 28 bits for a child index, 30 for a triangle count.
    static KdNode inner(int axis, float split, uint32_t aboveChild, bool belowEmpty = false, bool aboveEmpty = false) {
        if (axis < 0 || axis > 2 || aboveChild >= (1u << (32u - VKRAY_KD_CHILD_SHIFT)))
            throw std::length_error("kd node: axis or child index out of range");
        return KdNode{std::bit_cast<uint32_t>(split), aboveChild << VKRAY_KD_CHILD_SHIFT |
                                                          (aboveEmpty ? VKRAY_KD_EMPTY_ABOVE : 0u) |
                                                          (belowEmpty ? VKRAY_KD_EMPTY_BELOW : 0u) | uint32_t(axis)};
    }
    static KdNode leaf(uint32_t firstIndex, uint32_t count) {
        if (count >= (1u << 30)) throw std::length_error("kd leaf: too many triangles");
        return KdNode{firstIndex, count << 2 | VKRAY_KD_LEAF_TAG};
    }

    bool isLeaf() const { return (word1 & 3u) == VKRAY_KD_LEAF_TAG; }
    int axis() const { return int(word1 & 3u); }
    float split() const { return std::bit_cast<float>(word0); }
    uint32_t aboveChild() const { return word1 >> VKRAY_KD_CHILD_SHIFT; }
    // Whether the child on the `above` side is a leaf without triangles (inner nodes only).
    bool childEmpty(bool above) const { return (word1 & (above ? VKRAY_KD_EMPTY_ABOVE : VKRAY_KD_EMPTY_BELOW)) != 0; }
    uint32_t firstIndex() const { return word0; }
    uint32_t triangleCount() const { return word1 >> 2; }
    bool operator==(const KdNode&) const = default;
};

static_assert(sizeof(KdNode) == 8 && offsetof(KdNode, word1) == 4);
static_assert(sizeof(KdTreeHeader) == 32 && offsetof(KdTreeHeader, nodeCount) == 12 &&
              offsetof(KdTreeHeader, hi) == 16 && offsetof(KdTreeHeader, indexCount) == 28);
static_assert(sizeof(KdNodeExtra) == 32 && offsetof(KdNodeExtra, parent) == 12 &&
              offsetof(KdNodeExtra, hi) == 16);
static_assert(sizeof(KdRopeRecord) == 16 * VKRAY_KD_ROPE_TEXELS && offsetof(KdRopeRecord, ropeLoX) == 12 &&
              offsetof(KdRopeRecord, hi) == 16 && offsetof(KdRopeRecord, ropeHiX) == 28 &&
              offsetof(KdRopeRecord, ropeLoY) == 32 && offsetof(KdRopeRecord, ropeHiZ) == 44);

// Rope f (2 axis + side) of a KdRopeRecord record.
inline uint32_t kdRope(const KdRopeRecord& r, int face) {
    const uint32_t ropes[6] = {r.ropeLoX, r.ropeHiX, r.ropeLoY, r.ropeHiY, r.ropeLoZ, r.ropeHiZ};
    return ropes[face];
}
}  // namespace vkray::gpu
#else
#undef VKRAY_KD_STRUCT
#endif

#endif  // VKRAY_KD_LAYOUT_H
