// make_bvh: the binary SAH tree (bvh_build.cpp) collapsed into a wide one.
// Each wide node starts from a binary node's two children and repeatedly
// opens the inner child with the largest surface area, replacing it by its
// two children, until it has kBvhWidth or only leaves are left (Wald, Benthin and
// Boulos, "Getting rid of packets", 2008). Slots still free then go to the
// widest leaves of more than four triangles, each split in two leaves of at
// most four (as Embree fills its nodes): the same two blocks, but a ray
// tests only the halves whose boxes it enters. Everything here is a function
// of the binary tree alone, so the wide tree is as deterministic as it is.
// Each leaf's triangles go into blocks of four (TriangleBlock), in leaf
// order: the collapse reserves their places, a parallel pass fills them and
// decides where the split leaves split, reading each triangle once.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh.h"
#include "accel/bvh_binary.h"

namespace sombra {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// A leaf of the binary tree, triangle_order[first, first + count), and
// where its blocks go in Bvh::blocks. A split leaf (5 to 8 triangles) also
// names the wide node and the two slots its halves take.
struct LeafBlocks {
    std::uint32_t first, count, block;
    std::uint32_t node = 0;
    std::int32_t slot = -1, second_slot = -1;  // -1: not split
};

// A triangle of a leaf as its block lanes (and, for a split leaf, its box)
// need it.
struct LeafTriangle {
    Vec3 p0, p1, p2;
    Vec3 bmin, bmax;  // set by fill_split_leaf only
    std::uint32_t triangle;
};

inline LeafTriangle leaf_triangle(const TriangleMesh& mesh, std::uint32_t triangle) {
    const Index3& tri = mesh.triangles[triangle];
    return {mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]], {}, {}, triangle};
}

// Writes up to four triangles into one block, the spare lanes empty.
void fill_block(const LeafTriangle* const* triangles, std::uint32_t count, TriangleBlock& block) {
    block = TriangleBlock{};
    for (std::uint32_t lane = 0; lane < 4; ++lane) {
        block.triangle[lane] = kBvhEmptyLane;
        if (lane >= count) continue;
        const LeafTriangle& t = *triangles[lane];
        const Vec3 e1 = t.p1 - t.p0, e2 = t.p2 - t.p0;
        for (int a = 0; a < 3; ++a) {
            block.p0[a][lane] = t.p0[a];
            block.p1[a][lane] = t.p1[a];
            block.p2[a][lane] = t.p2[a];
        }
        block.em[lane] = max_component(max(abs(e1), abs(e2)));
        block.triangle[lane] = t.triangle;
    }
}

float half_area(Vec3 bmin, Vec3 bmax) {
    const Vec3 e = bmax - bmin;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

void write_slot(BvhWideNode& node, int i, Vec3 bmin, Vec3 bmax, std::uint32_t child, std::uint32_t count) {
    constexpr int W = kBvhWidth;
    node.bounds[0 * W + i] = bmin.x;
    node.bounds[1 * W + i] = bmax.x;
    node.bounds[2 * W + i] = bmin.y;
    node.bounds[3 * W + i] = bmax.y;
    node.bounds[4 * W + i] = bmin.z;
    node.bounds[5 * W + i] = bmax.z;
    node.child[i] = child;
    node.count[i] = count;
}

// Splits a leaf of 5 to 8 triangles in two of at most four where the
// halves' areas sum least (a ray entering the node tests each half with
// probability about its area), the triangles ordered by centroid along the
// leaf's widest axis, ties by index (deterministic); fills its two blocks
// and its two slots. One axis, not three: the widest one gives splits about
// as good, for less build time.
void fill_split_leaf(const TriangleMesh& mesh, const std::uint32_t* order, const LeafBlocks& leaf,
                     TriangleBlock* blocks, BvhWideNode* nodes) {
    constexpr std::uint32_t kMax = kBvhMaxLeafSize;
    const std::uint32_t n = leaf.count;
    std::array<LeafTriangle, kMax> triangles;
    std::array<const LeafTriangle*, kMax> sorted;
    Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
    for (std::uint32_t i = 0; i < n; ++i) {
        LeafTriangle& t = triangles[i];
        t = leaf_triangle(mesh, order[leaf.first + i]);
        t.bmin = min(t.p0, min(t.p1, t.p2));
        t.bmax = max(t.p0, max(t.p1, t.p2));
        lo = min(lo, t.bmin);
        hi = max(hi, t.bmax);
        sorted[i] = &t;
    }
    const Vec3 extent = hi - lo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
    std::sort(sorted.begin(), sorted.begin() + n, [axis](const LeafTriangle* p, const LeafTriangle* q) {
        const float cp = p->bmin[axis] + p->bmax[axis], cq = q->bmin[axis] + q->bmax[axis];
        return cp < cq || (cp == cq && p->triangle < q->triangle);
    });
    // Boxes of the first i triangles (prefix) and of the rest (suffix).
    std::array<Vec3, kMax + 1> prefix_min, prefix_max, suffix_min, suffix_max;
    prefix_min[0] = suffix_min[n] = Vec3{kInf, kInf, kInf};
    prefix_max[0] = suffix_max[n] = Vec3{-kInf, -kInf, -kInf};
    for (std::uint32_t i = 0; i < n; ++i) {
        prefix_min[i + 1] = min(prefix_min[i], sorted[i]->bmin);
        prefix_max[i + 1] = max(prefix_max[i], sorted[i]->bmax);
    }
    for (std::uint32_t i = n; i-- > 0;) {
        suffix_min[i] = min(suffix_min[i + 1], sorted[i]->bmin);
        suffix_max[i] = max(suffix_max[i + 1], sorted[i]->bmax);
    }
    std::uint32_t k = n / 2;  // kept when no cost is finite (a box too large for float)
    float best_cost = kInf;
    for (std::uint32_t i = n - 4; i <= 4; ++i) {
        const float cost = half_area(prefix_min[i], prefix_max[i]) + half_area(suffix_min[i], suffix_max[i]);
        if (cost < best_cost) {
            best_cost = cost;
            k = i;
        }
    }
    fill_block(sorted.data(), k, blocks[leaf.block]);
    fill_block(sorted.data() + k, n - k, blocks[leaf.block + 1]);
    BvhWideNode& node = nodes[leaf.node];
    write_slot(node, leaf.slot, prefix_min[k], prefix_max[k], leaf.block, k);
    write_slot(node, leaf.second_slot, suffix_min[k], suffix_max[k], leaf.block + 1, n - k);
}

// Fills the leaf's blocks, four triangles each, the last one's spare lanes
// empty; a split leaf's, and its slots, by fill_split_leaf.
void fill_leaf(const TriangleMesh& mesh, const std::uint32_t* order, const LeafBlocks& leaf, TriangleBlock* blocks,
               BvhWideNode* nodes) {
    if (leaf.slot >= 0) {
        fill_split_leaf(mesh, order, leaf, blocks, nodes);
        return;
    }
    for (std::uint32_t k = 0; k < leaf.count; k += 4) {
        std::array<LeafTriangle, 4> triangles;
        std::array<const LeafTriangle*, 4> lanes;
        const std::uint32_t in_block = std::min(4u, leaf.count - k);
        for (std::uint32_t lane = 0; lane < in_block; ++lane) {
            triangles[lane] = leaf_triangle(mesh, order[leaf.first + k + lane]);
            lanes[lane] = &triangles[lane];
        }
        fill_block(lanes.data(), in_block, blocks[leaf.block + k / 4]);
    }
}

// A child of the wide node being formed: a binary node; or a binary leaf
// split in two slots, each of which names the other (fill_split_leaf
// decides the halves).
struct Slot {
    std::uint32_t node;
    int other_half = -1;
};

struct Collapser {
    const BinaryBvh& binary;
    BvhNodeArray& nodes;
    std::vector<LeafBlocks>& leaves;
    std::uint32_t block_count = 0;

    float area(const Slot& s) const { return half_area(binary.nodes[s.node].bmin, binary.nodes[s.node].bmax); }

    // The widest child that can be opened: an inner node, or (when
    // `split_leaves`) a leaf of more than four triangles not split yet.
    int widest_openable(const std::array<Slot, kBvhWidth>& children, int size, bool split_leaves) const {
        int widest = -1;
        float widest_area = -1.0f;
        for (int i = 0; i < size; ++i) {
            const std::uint32_t count = binary.nodes[children[i].node].count;
            if (count != 0 && !(split_leaves && count > 4 && children[i].other_half < 0)) continue;
            const float a = area(children[i]);
            if (a > widest_area) {
                widest = i;
                widest_area = a;
            }
        }
        return widest;
    }

    // Writes the wide node for binary inner node `inner` at nodes[at].
    void collapse(std::uint32_t inner, std::uint32_t at) {
        std::array<Slot, kBvhWidth> children{};
        int size = 0;
        if (binary.nodes[inner].count > 0) {
            children[size++] = {inner};  // a root that is a leaf: one child, itself
        } else {
            children[size++] = {binary.nodes[inner].left_or_first};
            children[size++] = {binary.nodes[inner].left_or_first + 1};
        }
        // Inner children first: a leaf split never takes a slot an inner
        // node could have had (that would add nodes).
        for (bool split_leaves : {false, true}) {
            while (size < kBvhWidth) {
                const int widest = widest_openable(children, size, split_leaves);
                if (widest < 0) break;
                const BvhNode& opened = binary.nodes[children[widest].node];
                if (opened.count == 0) {
                    children[widest] = {opened.left_or_first};
                    children[size++] = {opened.left_or_first + 1};
                } else {
                    children[widest].other_half = size;
                    children[size] = {children[widest].node, widest};
                    ++size;
                }
            }
        }
        BvhWideNode node{};
        constexpr int W = kBvhWidth;
        for (int i = 0; i < W; ++i) write_slot(node, i, Vec3{kInf, kInf, kInf}, Vec3{-kInf, -kInf, -kInf}, 0, 0);
        std::array<std::uint32_t, kBvhWidth> inner_at{};
        for (int i = 0; i < size; ++i) {
            const BvhNode& c = binary.nodes[children[i].node];
            const int other = children[i].other_half;
            if (c.count == 0) {
                inner_at[i] = static_cast<std::uint32_t>(nodes.size());
                write_slot(node, i, c.bmin, c.bmax, inner_at[i], 0);
                nodes.emplace_back();
            } else if (other < 0) {
                leaves.push_back({c.left_or_first, c.count, block_count});
                write_slot(node, i, c.bmin, c.bmax, block_count, c.count);
                block_count += (c.count + 3) / 4;
            } else if (other > i) {
                // Both halves' slots hold the whole leaf until fill_split_leaf
                // writes each half's box and count.
                leaves.push_back({c.left_or_first, c.count, block_count, at, i, other});
                write_slot(node, i, c.bmin, c.bmax, block_count, c.count);
                write_slot(node, other, c.bmin, c.bmax, block_count + 1, c.count);
                block_count += 2;
            }
        }
        nodes[at] = node;
        for (int i = 0; i < size; ++i) {
            if (binary.nodes[children[i].node].count == 0) collapse(children[i].node, inner_at[i]);
        }
    }
};

}  // namespace

Bvh make_bvh(const TriangleMesh& mesh) {
    Bvh bvh;
    BinaryBvh binary = make_binary_bvh(mesh);
    if (binary.nodes.empty()) return bvh;

    bvh.nodes.reserve(binary.triangle_order.size() / 16 + 1);  // about one node per seven leaves of three or four
    bvh.nodes.emplace_back();
    std::vector<LeafBlocks> leaves;
    leaves.reserve(binary.triangle_order.size() / 3 + 1);
    Collapser collapser{binary, bvh.nodes, leaves};
    collapser.collapse(0, 0);
    // The binary nodes are done with (the leaves' list says where each
    // leaf's triangles go): freed before the blocks, the largest array, are
    // allocated, so that the two are never held at once.
    BinaryNodeArray().swap(binary.nodes);

    bvh.blocks.resize(collapser.block_count);
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, leaves.size(), 1024), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i < r.end(); ++i) {
                fill_leaf(mesh, binary.triangle_order.data(), leaves[i], bvh.blocks.data(), bvh.nodes.data());
            }
        });
    return bvh;
}

std::size_t bvh_memory_bytes(const Bvh& bvh) {
    return bvh.nodes.size() * sizeof(BvhWideNode) + bvh.blocks.size() * sizeof(TriangleBlock);
}

}  // namespace sombra
