// The binary SAH tree that make_bvh builds first and then collapses into the
// 8-wide tree it traverses (bvh_collapse.cpp). Internal to src/accel.
#pragma once

#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "scene/mesh.h"

namespace sombra {

struct BvhNode {
    Vec3 bmin;
    std::uint32_t left_or_first;  // inner node: index of the left child (right = left + 1); leaf: first entry in BinaryBvh::triangle_order
    Vec3 bmax;
    std::uint32_t count;          // 0 for an inner node, else the leaf's triangle count
};
static_assert(sizeof(BvhNode) == 32);

struct BinaryBvh {
    // nodes[0] is the root, children in adjacent pairs; sparse (slots no
    // node refers to are unused); empty when no triangle can be hit.
    std::vector<BvhNode> nodes;
    std::vector<std::uint32_t> triangle_order;  // leaf entries, indices into TriangleMesh::triangles
};

// Binned SAH over every triangle of `mesh` that can be hit (see make_bvh).
// Deterministic: the same tree for any number of threads.
BinaryBvh make_binary_bvh(const TriangleMesh& mesh);

}  // namespace sombra
