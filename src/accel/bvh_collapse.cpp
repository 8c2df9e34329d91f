// make_bvh: the binary SAH tree (bvh_build.cpp) collapsed into a wide one.
// Each wide node starts from a binary node's two children and repeatedly
// opens the inner child with the largest surface area, replacing it by its
// two children, until it has kBvhWidth or only leaves are left (Wald, Benthin and
// Boulos, "Getting rid of packets", 2008); its children's boxes are then
// quantised to the node's grid (bvh_quantise.cpp). Everything here is a function of
// the binary tree alone, so the wide tree is as deterministic as it is.
// Each leaf's triangles go into blocks of four (TriangleBlock), in leaf
// order: the collapse reserves their places, a parallel pass fills them.
#include <array>
#include <cstdint>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "accel/bvh.h"
#include "accel/bvh_binary.h"
#include "accel/bvh_quantise.h"

namespace sombra {
namespace {

float half_area(const BvhNode& n) {
    const Vec3 e = n.bmax - n.bmin;
    return e.x * e.y + e.y * e.z + e.z * e.x;
}

// A leaf of the binary tree, triangle_order[first, first + count), and
// where its blocks go in Bvh::blocks.
struct LeafBlocks {
    std::uint32_t first, count, block;
};

// Fills the leaf's blocks: four triangles each, the last one's spare lanes
// empty.
void fill_blocks(const TriangleMesh& mesh, const BinaryBvh& binary, const LeafBlocks& leaf, TriangleBlock* blocks) {
    for (std::uint32_t k = 0; k < leaf.count; k += 4) {
        TriangleBlock block{};
        for (std::uint32_t lane = 0; lane < 4; ++lane) {
            block.triangle[lane] = kBvhEmptyLane;
            if (k + lane >= leaf.count) continue;
            const std::uint32_t triangle = binary.triangle_order[leaf.first + k + lane];
            const Index3& tri = mesh.triangles[triangle];
            const Vec3 p0 = mesh.positions[tri[0]];
            const Vec3 e1 = mesh.positions[tri[1]] - p0, e2 = mesh.positions[tri[2]] - p0;
            for (int a = 0; a < 3; ++a) {
                block.p0[a][lane] = p0[a];
                block.e1[a][lane] = e1[a];
                block.e2[a][lane] = e2[a];
            }
            block.em[lane] = max_component(max(abs(e1), abs(e2)));
            block.triangle[lane] = triangle;
        }
        blocks[leaf.block + k / 4] = block;
    }
}

struct Collapser {
    const BinaryBvh& binary;
    BvhNodeArray& nodes;
    std::vector<LeafBlocks>& leaves;
    std::uint32_t block_count = 0;

    // Writes the wide node for binary inner node `inner` at nodes[at].
    void collapse(std::uint32_t inner, std::uint32_t at) {
        std::array<std::uint32_t, kBvhWidth> children{};
        int size = 0;
        if (binary.nodes[inner].count > 0) {
            children[size++] = inner;  // a root that is a leaf: one child, itself
        } else {
            children[size++] = binary.nodes[inner].left_or_first;
            children[size++] = binary.nodes[inner].left_or_first + 1;
        }
        while (size < kBvhWidth) {
            int widest = -1;
            float widest_area = -1.0f;
            for (int i = 0; i < size; ++i) {
                const BvhNode& c = binary.nodes[children[i]];
                if (c.count == 0 && half_area(c) > widest_area) {
                    widest = i;
                    widest_area = half_area(c);
                }
            }
            if (widest < 0) break;
            const std::uint32_t left = binary.nodes[children[widest]].left_or_first;
            children[widest] = left;
            children[size++] = left + 1;
        }
        BvhWideNode node{};
        std::array<BvhChildBox, kBvhWidth> boxes{};
        std::array<std::uint32_t, kBvhWidth> inner_at{};
        for (int i = 0; i < size; ++i) {
            const BvhNode& c = binary.nodes[children[i]];
            boxes[i] = {c.bmin, c.bmax};
            if (c.count > 0) {
                leaves.push_back({c.left_or_first, c.count, block_count});
                node.child[i] = block_count;
                block_count += (c.count + 3) / 4;
                node.count[i] = static_cast<std::uint8_t>(c.count);
            } else {
                inner_at[i] = static_cast<std::uint32_t>(nodes.size());
                node.child[i] = inner_at[i];
                nodes.emplace_back();
            }
        }
        quantise_children(boxes.data(), size, node);
        nodes[at] = node;
        for (int i = 0; i < size; ++i) {
            if (binary.nodes[children[i]].count == 0) collapse(children[i], inner_at[i]);
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
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, leaves.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                          for (std::size_t i = r.begin(); i < r.end(); ++i) {
                              fill_blocks(mesh, binary, leaves[i], bvh.blocks.data());
                          }
                      });
    return bvh;
}

std::size_t bvh_memory_bytes(const Bvh& bvh) {
    return bvh.nodes.size() * sizeof(BvhWideNode) + bvh.blocks.size() * sizeof(TriangleBlock);
}

}  // namespace sombra
