// sombra's own bounding volume hierarchy: a binary SAH tree in one flat array
// of 32-byte nodes, built with binned SAH (Wald 2007) and traversed
// iteratively, nearer child first.
#pragma once

#include <cstdint>
#include <vector>

#include "accel/triangle.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "scene/mesh.h"

namespace sombra {

struct Hit;

struct BvhNode {
    Vec3 bmin;
    std::uint32_t left_or_first;  // inner node: index of the left child (right = left + 1); leaf: first entry in Bvh::triangle_order
    Vec3 bmax;
    std::uint32_t count;          // 0 for an inner node, else the leaf's triangle count
};
static_assert(sizeof(BvhNode) == 32);

// The deepest path from the root to a leaf that make_bvh builds (the root has
// depth 0); traversal stacks hold this many entries.
inline constexpr int kBvhMaxDepth = 64;
// Leaves hold at most this many triangles.
inline constexpr std::uint32_t kBvhMaxLeafSize = 8;
// Nodes this deep or deeper are split at the object median instead of by the
// SAH, which on adversarial input (geometrically spaced triangles) can peel
// off a few triangles per level. Medians halve the count, so leaves stay
// above kBvhMaxDepth even for 2^32 triangles: 31 + 29 < 64.
inline constexpr int kBvhSahMaxDepth = 31;

struct Bvh {
    std::vector<BvhNode> nodes;                 // nodes[0] is the root; empty when no triangle can be hit
    std::vector<std::uint32_t> triangle_order;  // leaf entries, indices into TriangleMesh::triangles
    // triangle_order[k]'s corners prepared for intersect_triangle, in leaf
    // order so traversal reads them without the index indirection. Computed
    // from the mesh's own vertex values by make_triangle_edges, so hits are
    // bit-identical to the brute-force loop.
    std::vector<TriangleEdges> ordered_triangles;
};

// Builds the tree over every triangle of `mesh` that can be hit: triangles
// with an out-of-range index, a non-finite corner or zero area are left out
// (they never hit). Deterministic: the same tree for any number of threads.
// Subtrees above ~10k triangles are built in parallel with TBB.
Bvh make_bvh(const TriangleMesh& mesh);

// Closest hit with 0 < t < ray.tmax, ties at equal t going to the lower
// triangle index (see accel.h). Returns false and leaves `hit` untouched when
// nothing is hit. Rays with a non-finite or zero direction, or a non-finite
// origin, hit nothing.
bool intersect_bvh(const Bvh& bvh, const TriangleMesh& mesh, const Ray& ray, Hit& hit);

// True when any triangle is hit with 0 < t < ray.tmax; stops at the first.
bool occluded_bvh(const Bvh& bvh, const TriangleMesh& mesh, const Ray& ray);

// Bytes of nodes, index and precomputed triangle arrays (sizes, not capacities).
std::size_t bvh_memory_bytes(const Bvh& bvh);

}  // namespace sombra
