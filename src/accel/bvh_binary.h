// The binary SAH tree that make_bvh builds first and then collapses into the
// 8-wide tree it traverses (bvh_collapse.cpp). Internal to src/accel.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "accel/unset_elements.h"
#include "core/vec3.h"
#include "scene/mesh.h"

namespace sombra {

struct BvhNode {
    Vec3 bmin;
    std::uint32_t
        left_or_first;  // inner node: index of the left child (right = left + 1); leaf: first entry in BinaryBvh::triangle_order
    Vec3 bmax;
    std::uint32_t count;  // 0 for an inner node, else the leaf's triangle count
};
static_assert(sizeof(BvhNode) == 32);

// std::allocator, except that resize() leaves new elements unset
// (unset_elements.h). Slots of the binary tree that no node takes are never
// written, and their untouched pages never become resident; the build's
// other arrays are first touched by the parallel passes that fill them
// (bvh_build.cpp).
template <class T>
struct UninitialisedAllocator : std::allocator<T>, LeavesNewElementsUnset {
    template <class U>
    struct rebind {
        using other = UninitialisedAllocator<U>;
    };
    UninitialisedAllocator() = default;
    template <class U>
    UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
    using LeavesNewElementsUnset::construct;  // not the one std::allocator may bring
};
using BinaryNodeArray = std::vector<BvhNode, UninitialisedAllocator<BvhNode>>;

struct BinaryBvh {
    // nodes[0] is the root, children in adjacent pairs; sparse (slots no
    // node refers to are unused and uninitialised: read only the slots that
    // nodes refer to); empty when no triangle can be hit.
    BinaryNodeArray nodes;
    std::vector<std::uint32_t, UninitialisedAllocator<std::uint32_t>>
        triangle_order;  // leaf entries, indices into TriangleMesh::triangles
};

// Binned SAH over every triangle of `mesh` that can be hit (see make_bvh).
// Deterministic: the same tree for any number of threads.
BinaryBvh make_binary_bvh(const TriangleMesh& mesh);

}  // namespace sombra
