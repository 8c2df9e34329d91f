// sombra's own bounding volume hierarchy: built as a binary tree with binned
// SAH (Wald 2007, bvh_build.cpp), collapsed into an 8-wide tree of 128-byte
// nodes with quantised boxes (bvh_collapse.cpp) and traversed iteratively with AVX box tests,
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

// One node of the wide tree: the boxes of up to kBvhWidth children, each
// coordinate quantised to 8 bits on a grid of 256 planes per axis spanning
// the node's own box (compressed wide nodes, as in Ylitie, Karras and Laine,
// "Efficient incoherent ray traversal on GPUs through compressed wide BVHs",
// 2017), stored as structure of arrays so one AVX instruction handles a
// coordinate of all eight. 128 bytes, two cache lines, where float bounds
// took four: under incoherent rays most node reads miss the caches.
//
// A plane's value is plane_value(origin[a], scale[a], q), float operations
// the traversal repeats exactly, and the build picks each q so that the value
// lies on the outer side of the child's true bound (bvh_quantise.cpp): the
// quantised box always contains the float box, so traversal may enter a few
// more children but never misses one, and hits stay bit-identical.
struct alignas(64) BvhWideNode {
    float origin[3];  // the grid's first plane per axis: the node's box's min corner
    float scale[3];   // the grid's step per axis
    std::uint32_t child[kBvhWidth];  // inner child: its index in Bvh::nodes; leaf: its first block in Bvh::blocks
    // bounds[kBvhWidth·k + i] for child i: k = 0 min x, 1 max x, 2 min y,
    // 3 max y, 4 min z, 5 max z, as grid indices.
    std::uint8_t bounds[6 * kBvhWidth];
    std::uint8_t count[kBvhWidth];  // leaf: its triangle count (1 … 8), in (count + 3) / 4 blocks; inner child or empty slot: 0
    std::uint8_t used;              // bit i set: slot i holds a child (no ray enters an empty one)
    std::uint8_t padding[15];
};
static_assert(sizeof(BvhWideNode) == 128);

// The value of grid plane q on an axis whose grid starts at `origin` with
// step `scale`. Built with -ffp-contract=off, so no FMA forms: the build's
// quantisation and the traversal's SIMD lanes round alike.
inline float plane_value(float origin, float scale, std::uint8_t q) { return origin + scale * static_cast<float>(q); }

// Child slot i's box as traversal sees it (the quantised planes' values).
struct BvhChildBox {
    Vec3 lo, hi;
};
inline BvhChildBox child_box(const BvhWideNode& node, int i) {
    constexpr int W = kBvhWidth;
    Vec3 lo, hi;
    for (int a = 0; a < 3; ++a) {
        lo[a] = plane_value(node.origin[a], node.scale[a], node.bounds[(2 * a) * W + i]);
        hi[a] = plane_value(node.origin[a], node.scale[a], node.bounds[(2 * a + 1) * W + i]);
    }
    return {lo, hi};
}
inline bool slot_used(const BvhWideNode& node, int i) { return (node.used >> i) & 1u; }

// The deepest path from the root to a leaf that make_bvh builds (the root has
// depth 0); traversal stacks hold this many entries.
inline constexpr int kBvhMaxDepth = 64;
// Leaves hold at most this many triangles.
inline constexpr std::uint32_t kBvhMaxLeafSize = 8;
static_assert(kBvhMaxLeafSize <= 255, "BvhWideNode::count is a byte");
// Nodes this deep or deeper are split at the object median instead of by the
// SAH, which on adversarial input (geometrically spaced triangles) can peel
// off a few triangles per level. Medians halve the count, so leaves stay
// above kBvhMaxDepth even for 2^32 triangles: 31 + 29 < 64.
inline constexpr int kBvhSahMaxDepth = 31;

// A lane of a TriangleBlock that holds no triangle.
inline constexpr std::uint32_t kBvhEmptyLane = 0xffffffffu;

// Four triangles of a leaf, structure of arrays for the SSE test
// (bvh_triangle4.h): [axis][lane]. p0 is the first corner as the mesh gives
// it, e1 = p1 − p0 and e2 = p2 − p0 computed in float exactly as
// intersect_triangle computes them, so each lane repeats the scalar test's
// arithmetic. An empty lane is all zeros (a zero normal: never hit). 176
// bytes, against 48 + 4 for a PreparedTriangle and an index.
struct alignas(16) TriangleBlock {
    float p0[3][4];
    float e1[3][4];
    float e2[3][4];
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
    BvhNodeArray nodes;        // nodes[0] is the root; empty when no triangle can be hit
    TriangleBlockArray blocks;   // the leaves' triangles, each leaf's blocks contiguous
};

// Builds the tree over every triangle of `mesh` that can be hit: triangles
// with an out-of-range index, a non-finite corner or zero area are left out
// (they never hit). Deterministic: the same tree for any number of threads.
// Subtrees above ~2k triangles are built in parallel with TBB.
Bvh make_bvh(const TriangleMesh& mesh);

// Closest hit with 0 < t < ray.tmax, ties at equal t going to the lower
// triangle index (see accel.h). Returns false and leaves `hit` untouched when
// nothing is hit. Rays with a non-finite or zero direction, or a non-finite
// origin, hit nothing.
bool intersect_bvh(const Bvh& bvh, const TriangleMesh& mesh, const Ray& ray, Hit& hit);

// True when any triangle is hit with 0 < t < ray.tmax; stops at the first.
bool occluded_bvh(const Bvh& bvh, const TriangleMesh& mesh, const Ray& ray);

// The same two queries skipping the hits where `cutouts` (active, over
// `mesh`) says the surface does not exist.
bool intersect_bvh(const Bvh& bvh, const Cutouts& cutouts, const Ray& ray, Hit& hit);
bool occluded_bvh(const Bvh& bvh, const Cutouts& cutouts, const Ray& ray);

// Bytes of the node and triangle block arrays (sizes, not capacities).
std::size_t bvh_memory_bytes(const Bvh& bvh);

}  // namespace sombra
