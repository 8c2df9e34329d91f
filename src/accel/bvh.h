// sombra's own bounding volume hierarchy: built as a binary tree with binned
// SAH (Wald 2007, bvh_build.cpp), collapsed into an 8-wide tree of 256-byte
// nodes (bvh_collapse.cpp) and traversed iteratively with AVX box tests,
// nearest child first (bvh.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "accel/huge_pages.h"
#include "accel/triangle.h"
#include "core/ray.h"
#include "core/vec3.h"
#include "scene/cutout.h"
#include "scene/mesh.h"

namespace sombra {

struct Hit;

// Children per node of the wide tree.
inline constexpr int kBvhWidth = 8;

// One node of the wide tree: the boxes of up to kBvhWidth children, stored
// as structure of arrays so one AVX instruction handles a coordinate of all
// eight (Embree's BVH8 layout). 256 bytes, four cache lines.
struct alignas(64) BvhWideNode {
    // bounds[kBvhWidth·k + i] for child i: k = 0 min x, 1 max x, 2 min y,
    // 3 max y, 4 min z, 5 max z. An empty slot has min +∞ and max −∞: no ray
    // enters it.
    float bounds[6 * kBvhWidth];
    std::uint32_t child[kBvhWidth];  // inner child: its index in Bvh::nodes; leaf: its first block in Bvh::blocks
    std::uint32_t
        count[kBvhWidth];  // leaf: its triangle count (≥ 1), in (count + 3) / 4 blocks; inner child or empty slot: 0
};
static_assert(sizeof(BvhWideNode) == 256);

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

// A lane of a TriangleBlock that holds no triangle.
inline constexpr std::uint32_t kBvhEmptyLane = 0xffffffffu;

// Four triangles of a leaf, structure of arrays for the SSE test
// (bvh_triangle4.h): [axis][lane]. The corners p0, p1, p2 as the mesh gives
// them: the test takes e1 = p1 − p0 and e2 = p2 − p0 in float exactly as
// intersect_triangle does, so each lane repeats the scalar test's
// arithmetic, and a lane near an edge is re-decided from these corners
// without reading the mesh. An empty lane is all zeros (a zero normal: never
// hit). 176 bytes, against 48 + 4 for a PreparedTriangle and an index.
struct alignas(16) TriangleBlock {
    float p0[3][4];
    float p1[3][4];
    float p2[3][4];
    float em[4];                // max_component(max(abs(e1), abs(e2))): the near-edge band's edge length
    std::uint32_t triangle[4];  // index into TriangleMesh::triangles, or kBvhEmptyLane
};
static_assert(sizeof(TriangleBlock) == 176);

// Traversal stacks hold this many entries: each node pushes all but one of
// its children, on a path at most kBvhMaxDepth deep.
inline constexpr int kBvhStackSize = (kBvhWidth - 1) * kBvhMaxDepth + 1;

// The arrays traversal reads, in 2 MiB pages where the kernel has them
// (huge_pages.h).
using BvhNodeArray = std::vector<BvhWideNode, HugePageAllocator<BvhWideNode>>;
using TriangleBlockArray = std::vector<TriangleBlock, HugePageAllocator<TriangleBlock>>;

struct Bvh {
    BvhNodeArray nodes;         // nodes[0] is the root; empty when no triangle can be hit
    TriangleBlockArray blocks;  // the leaves' triangles, each leaf's blocks contiguous
};

// Builds the tree over every triangle of `mesh` that can be hit: triangles
// with an out-of-range index, a non-finite corner or zero area are left out
// (they never hit). Deterministic: the same tree for any number of threads.
// Subtrees above ~2k triangles are built in parallel with TBB.
Bvh make_bvh(const TriangleMesh& mesh);

// Closest hit with 0 < t < ray.tmax, ties at equal t going to the lower
// triangle index (see accel.h), among the triangles of the mesh the tree was
// built over (the blocks hold their corners: the mesh itself is not read).
// Returns false and leaves `hit` untouched when nothing is hit. Rays with a
// non-finite or zero direction, or a non-finite origin, hit nothing.
bool intersect_bvh(const Bvh& bvh, const Ray& ray, Hit& hit);

// True when any triangle is hit with 0 < t < ray.tmax; stops at the first.
bool occluded_bvh(const Bvh& bvh, const Ray& ray);

// The same two queries skipping the hits where `cutouts` (active, over the
// tree's mesh) says the surface does not exist.
bool intersect_bvh(const Bvh& bvh, const Cutouts& cutouts, const Ray& ray, Hit& hit);
bool occluded_bvh(const Bvh& bvh, const Cutouts& cutouts, const Ray& ray);

// Bytes of the node and triangle block arrays (sizes, not capacities).
std::size_t bvh_memory_bytes(const Bvh& bvh);

}  // namespace sombra
