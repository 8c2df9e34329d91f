// The build's memory savings change no tree: the wide trees of two shared
// models are pinned by a hash of their bytes, taken before the savings
// (commit 19eec48; the blocks' hashes taken again after 2e6c339, whose
// chunked partition of the top levels reorders triangles within some
// leaves: the same triangles per leaf, the node hashes unchanged; and again
// when the blocks came to hold the corners p1, p2 instead of the edges e1,
// e2: same triangles in the same lanes, bvh_structure_test checks each lane's
// corners; and again when free slots came to take the halves of leaves of
// more than four triangles: the same node and block counts,
// bvh_structure_test checks each leaf's box and triangles), and the binary
// tree's slots are checked to be used the way the savings rely on (a prefix
// of each serial subtree's range).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

#include "accel/accel_test_util.h"
#include "accel/bvh.h"
#include "accel/bvh_binary.h"
#include "accel/huge_pages.h"
#include "io/mesh_file.h"

namespace sombra {
namespace {

const std::filesystem::path kModels = std::filesystem::path(SOMBRA_SHARED_DIR) / "models";

// FNV-1a over raw bytes: the arrays have no padding (their static_asserts
// fix their sizes), so equal hashes mean equal trees.
std::uint64_t fnv1a(const void* data, std::size_t bytes) {
    std::uint64_t h = 1469598103934665603ull;
    const auto* b = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ b[i]) * 1099511628211ull;
    return h;
}

struct PinnedTree {
    const char* model;
    std::size_t nodes, blocks;
    std::uint64_t nodes_hash, blocks_hash;
};

class BvhMemory : public ::testing::TestWithParam<PinnedTree> {};

// The hashes depend on float arithmetic being the build's (-ffp-contract=off,
// the same compiler): a different toolchain may legitimately change them.
TEST_P(BvhMemory, SameTreeAsBeforeTheMemorySavings) {
    const PinnedTree& pinned = GetParam();
    const std::filesystem::path path = kModels / pinned.model;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared/ not found at " << kModels;
    Diagnostics diag;
    const LoadedMesh loaded = load_mesh_file(path, diag);
    const Bvh bvh = make_bvh(loaded.mesh);
    ASSERT_EQ(bvh.nodes.size(), pinned.nodes);
    ASSERT_EQ(bvh.blocks.size(), pinned.blocks);
    EXPECT_EQ(fnv1a(bvh.nodes.data(), bvh.nodes.size() * sizeof(BvhWideNode)), pinned.nodes_hash);
    EXPECT_EQ(fnv1a(bvh.blocks.data(), bvh.blocks.size() * sizeof(TriangleBlock)), pinned.blocks_hash);
}

INSTANTIATE_TEST_SUITE_P(
    Models, BvhMemory,
    ::testing::Values(PinnedTree{"stanford-bunny.obj", 4327, 18088, 0x7131f7fe65b7f622ull, 0xe0c46ee6e71fe43eull},
                      PinnedTree{"dragon.ply", 48416, 234718, 0x38aff62072063632ull, 0xa55b397a831b760cull}),
    [](const ::testing::TestParamInfo<PinnedTree>& param_info) {
        return std::string(param_info.param.model) == "dragon.ply" ? "dragon" : "bunny";
    });

// The slots a tree of at most 2,048 references (built on one thread) uses:
// the root's, then a prefix of the rest with no gap, about a third of the
// 2n − 1 reserved. The untouched tail is what the build saves.
TEST(BvhMemory, SerialSubtreesUseAPrefixOfTheirSlots) {
    const TriangleMesh mesh = testing::random_soup(2000, 7, 0.05f);
    const BinaryBvh binary = make_binary_bvh(mesh);
    ASSERT_FALSE(binary.nodes.empty());
    std::vector<std::uint32_t> used, stack{0};
    while (!stack.empty()) {
        const std::uint32_t slot = stack.back();
        stack.pop_back();
        used.push_back(slot);
        const BvhNode& n = binary.nodes[slot];
        if (n.count == 0) {
            stack.push_back(n.left_or_first);
            stack.push_back(n.left_or_first + 1);
        }
    }
    std::sort(used.begin(), used.end());
    for (std::size_t i = 0; i < used.size(); ++i) ASSERT_EQ(used[i], i) << "slot " << i << " skipped";
    EXPECT_LT(used.size(), binary.nodes.size() / 2);
}

// The arrays behind the tree: from one huge page on, they start on a 2 MiB
// boundary (the mapping's two trimmed ends are the rest of it) and every
// byte is theirs; smaller ones have the alignment asked for.
TEST(BigArrays, StartOnAHugePageBoundaryAndHoldEveryByte) {
    for (const std::size_t bytes :
         {std::size_t{64}, kHugePageBytes - 1, kHugePageBytes, kHugePageBytes + 1, 3 * kHugePageBytes + 4096}) {
        void* p = allocate_big_array(bytes, 64);
        ASSERT_NE(p, nullptr);
        EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % (bytes < kHugePageBytes ? 64 : kHugePageBytes), 0u) << bytes;
        std::memset(p, 0xab, bytes);
        EXPECT_EQ(static_cast<const unsigned char*>(p)[bytes - 1], 0xab) << bytes;
        release_big_array(p, bytes, 64);
    }
}

}  // namespace
}  // namespace sombra
