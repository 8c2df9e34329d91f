// The shape of the built tree: bounds, leaf contents, depth, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include <tbb/global_control.h>

#include "accel/accel.h"
#include "accel/accel_test_util.h"
#include "accel/bvh_binary.h"

namespace sombra {
namespace {

using testing::add_triangle;
using testing::compare_with_brute;
using testing::Comparison;
using testing::random_soup;

constexpr int W = kBvhWidth;

bool slot_used(const BvhWideNode& node, int i) { return node.bounds[i] <= node.bounds[W + i]; }

// Child box i of `node` contains p.
bool contains(const BvhWideNode& node, int i, Vec3 p) {
    const float* b = node.bounds;
    return b[i] <= p.x && p.x <= b[W + i] && b[2 * W + i] <= p.y && p.y <= b[3 * W + i] && b[4 * W + i] <= p.z &&
           p.z <= b[5 * W + i];
}

struct TreeFacts {
    int depth = 0;  // of the deepest leaf; the root's children have depth 1
    int leaves = 0;
    int nodes = 0;         // inner nodes reached
    int narrow_nodes = 0;  // nodes with fewer than two children
    int bad_bounds = 0;    // children or triangles outside their parent's box
    int oversized_leaves = 0;
    int loose_leaves = 0;                // leaves whose box is not exactly their triangles' box
    int unsplit_leaves = 0;              // leaves of more than four triangles in a node with a free slot
    std::vector<std::uint32_t> reached;  // the triangles the leaves hold, as traversal reads them
};

TreeFacts inspect(const Bvh& bvh, const TriangleMesh& mesh, std::uint32_t node = 0, int depth = 0) {
    TreeFacts facts;
    const BvhWideNode& n = bvh.nodes[node];
    facts.depth = depth;
    facts.nodes = 1;
    int used = 0, big_leaves = 0;
    for (int i = 0; i < W; ++i) {
        if (!slot_used(n, i)) continue;
        ++used;
        if (n.count[i] > 0) {
            facts.depth = std::max(facts.depth, depth + 1);
            facts.leaves += 1;
            facts.oversized_leaves += n.count[i] > kBvhMaxLeafSize;
            big_leaves += n.count[i] > 4;
            Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
            for (std::uint32_t k = 0; k < n.count[i]; ++k) {
                const std::uint32_t triangle = bvh.blocks[n.child[i] + k / 4].triangle[k % 4];
                facts.reached.push_back(triangle);
                if (triangle >= mesh.triangles.size()) {
                    ++facts.bad_bounds;
                    continue;
                }
                for (std::uint32_t v : mesh.triangles[triangle]) {
                    facts.bad_bounds += !contains(n, i, mesh.positions[v]);
                    lo = min(lo, mesh.positions[v]);
                    hi = max(hi, mesh.positions[v]);
                }
            }
            facts.loose_leaves += lo.x != n.bounds[i] || hi.x != n.bounds[W + i] || lo.y != n.bounds[2 * W + i] ||
                                  hi.y != n.bounds[3 * W + i] || lo.z != n.bounds[4 * W + i] ||
                                  hi.z != n.bounds[5 * W + i];
            continue;
        }
        const BvhWideNode& c = bvh.nodes[n.child[i]];
        for (int j = 0; j < W; ++j) {
            if (!slot_used(c, j)) continue;
            facts.bad_bounds += !contains(n, i, {c.bounds[j], c.bounds[2 * W + j], c.bounds[4 * W + j]}) ||
                                !contains(n, i, {c.bounds[W + j], c.bounds[3 * W + j], c.bounds[5 * W + j]});
        }
        const TreeFacts sub = inspect(bvh, mesh, n.child[i], depth + 1);
        facts.depth = std::max(facts.depth, sub.depth);
        facts.leaves += sub.leaves;
        facts.nodes += sub.nodes;
        facts.narrow_nodes += sub.narrow_nodes;
        facts.bad_bounds += sub.bad_bounds;
        facts.oversized_leaves += sub.oversized_leaves;
        facts.loose_leaves += sub.loose_leaves;
        facts.unsplit_leaves += sub.unsplit_leaves;
        facts.reached.insert(facts.reached.end(), sub.reached.begin(), sub.reached.end());
    }
    facts.narrow_nodes += used < 2;
    if (used < W) facts.unsplit_leaves += big_leaves;
    return facts;
}

TEST(BvhStructure, LeavesBoundTheirTrianglesAndHoldEachOnce) {
    const TriangleMesh mesh = random_soup(20000, 21);
    const Bvh bvh = make_bvh(mesh);
    ASSERT_FALSE(bvh.nodes.empty());
    const TreeFacts facts = inspect(bvh, mesh);
    EXPECT_EQ(facts.bad_bounds, 0);
    EXPECT_EQ(facts.oversized_leaves, 0);
    EXPECT_EQ(facts.loose_leaves, 0);
    // Free slots take halves of leaves of more than four triangles (as
    // Embree fills its nodes): a ray then tests only the halves it enters.
    EXPECT_EQ(facts.unsplit_leaves, 0);
    EXPECT_EQ(facts.narrow_nodes, 0);
    EXPECT_EQ(static_cast<std::size_t>(facts.nodes), bvh.nodes.size());  // every node reached once
    // Collapsing a binary tree fills nodes: far fewer than one per four leaves.
    EXPECT_LT(facts.nodes * 4, facts.leaves);
    EXPECT_LT(facts.depth, kBvhMaxDepth);
    EXPECT_GT(facts.leaves, 20000 / static_cast<int>(kBvhMaxLeafSize));

    std::vector<int> seen(mesh.triangles.size(), 0), reached(mesh.triangles.size(), 0);
    for (std::uint32_t t : testing::bvh_triangles(bvh)) ++seen[t];
    for (std::uint32_t t : facts.reached) {
        ASSERT_LT(t, reached.size());
        ++reached[t];
    }
    for (std::size_t i = 0; i < seen.size(); ++i) {
        ASSERT_EQ(seen[i], 1) << "triangle " << i;
        ASSERT_EQ(reached[i], 1) << "triangle " << i;
    }

    // Each lane holds the mesh's own corners, bit for bit, and the edge
    // length as the scalar test computes it; empty lanes are all zero.
    for (const TriangleBlock& block : bvh.blocks) {
        for (int lane = 0; lane < 4; ++lane) {
            Vec3 p[3]{};
            if (block.triangle[lane] != kBvhEmptyLane) {
                const Index3& tri = mesh.triangles[block.triangle[lane]];
                for (int k = 0; k < 3; ++k) p[k] = mesh.positions[tri[k]];
            }
            const float em = max_component(max(abs(p[1] - p[0]), abs(p[2] - p[0])));
            ASSERT_EQ(std::memcmp(&block.em[lane], &em, 4), 0);
            for (int a = 0; a < 3; ++a) {
                ASSERT_EQ(std::memcmp(&block.p0[a][lane], &p[0][a], 4), 0);
                ASSERT_EQ(std::memcmp(&block.p1[a][lane], &p[1][a], 4), 0);
                ASSERT_EQ(std::memcmp(&block.p2[a][lane], &p[2][a], 4), 0);
            }
        }
    }
    EXPECT_EQ(bvh_memory_bytes(bvh), bvh.nodes.size() * sizeof(BvhWideNode) + bvh.blocks.size() * 176);
    // Leaves of up to four triangles fill one block: few lanes stay empty.
    EXPECT_GT(static_cast<double>(mesh.triangles.size()) / (4.0 * static_cast<double>(bvh.blocks.size())), 0.6);
}

// The SAH's cost terms must reward splitting a big node: a well-spread soup
// gives leaves of a few triangles, not a handful of huge ones.
TEST(BvhStructure, SahProducesSmallLeaves) {
    const TriangleMesh mesh = random_soup(5000, 22, 0.01f);
    const Bvh bvh = make_bvh(mesh);
    const TreeFacts facts = inspect(bvh, mesh);
    const double mean_leaf = static_cast<double>(mesh.triangles.size()) / facts.leaves;
    EXPECT_GT(mean_leaf, 1.0);
    EXPECT_LT(mean_leaf, 6.0);
    EXPECT_LT(facts.depth, 30);
}

// The build's split rule written out once more as a plain scalar loop: 32
// bins of doubled centroids per axis, every plane between bins costed as
// half_area · blocks of four on each side, the cheapest taken (the first
// axis, then the lowest plane, among equal costs). The root's left child
// must be exactly the union of the bins left of that plane, which pins the
// build's SSE binning and its sweep of the three axes side by side.
TEST(BvhStructure, RootSplitIsTheCheapestBinnedPlane) {
    // The last soup is large enough for the root's binning to run in
    // parallel chunks (kParallelPassRefs).
    for (const auto& [seed, count] :
         {std::pair{7u, 3000}, std::pair{8u, 3000}, std::pair{9u, 3000}, std::pair{10u, 70000}}) {
        const TriangleMesh mesh = random_soup(count, seed, 0.05f);
        struct Bounds {
            Vec3 lo{std::numeric_limits<float>::infinity()}, hi{-std::numeric_limits<float>::infinity()};
            int count = 0;
            void grow(Vec3 l, Vec3 h) {
                lo = min(lo, l);
                hi = max(hi, h);
            }
            float half_area() const {
                const Vec3 e = hi - lo;
                return e.x * e.y + e.y * e.z + e.z * e.x;
            }
        };
        std::vector<Vec3> lo, hi;
        Bounds centroids;
        for (const Index3& t : mesh.triangles) {
            const Vec3 p0 = mesh.positions[t[0]], p1 = mesh.positions[t[1]], p2 = mesh.positions[t[2]];
            lo.push_back(min(p0, min(p1, p2)));
            hi.push_back(max(p0, max(p1, p2)));
            centroids.grow(lo.back() + hi.back(), lo.back() + hi.back());
        }
        constexpr int kBins = 32;
        float best_cost = std::numeric_limits<float>::infinity();
        Bounds best_left;
        for (int a = 0; a < 3; ++a) {
            const float extent = centroids.hi[a] - centroids.lo[a];
            ASSERT_GT(extent, 0.0f);
            const float scale = static_cast<float>(kBins) / extent;
            Bounds bins[kBins];
            for (std::size_t k = 0; k < lo.size(); ++k) {
                const float f = ((lo[k] + hi[k])[a] - centroids.lo[a]) * scale;
                const int bin = f > 0.0f ? std::min(static_cast<int>(f), kBins - 1) : 0;
                bins[bin].grow(lo[k], hi[k]);
                ++bins[bin].count;
            }
            for (int plane = 1; plane < kBins; ++plane) {
                Bounds left, right;
                for (int b = 0; b < kBins; ++b) {
                    Bounds& side = b < plane ? left : right;
                    side.grow(bins[b].lo, bins[b].hi);
                    side.count += bins[b].count;
                }
                if (left.count == 0 || right.count == 0) continue;
                const int left_blocks = (left.count + 3) / 4, right_blocks = (right.count + 3) / 4;
                const float cost = left.half_area() * static_cast<float>(left_blocks) +
                                   right.half_area() * static_cast<float>(right_blocks);
                if (cost < best_cost) {
                    best_cost = cost;
                    best_left = left;
                }
            }
        }
        const BinaryBvh binary = make_binary_bvh(mesh);
        ASSERT_EQ(binary.nodes[0].count, 0u);
        const BvhNode& left_child = binary.nodes[binary.nodes[0].left_or_first];
        EXPECT_EQ(left_child.bmin, best_left.lo) << "seed " << seed;
        EXPECT_EQ(left_child.bmax, best_left.hi) << "seed " << seed;
    }
}

// Parallel triangles in the planes x = 3^k · 1e-37, k = 0 … 155: every SAH
// split peels a few off the far end, so SAH alone builds a spine about 50
// levels deep. The median splits below kBvhSahMaxDepth keep it to
// kBvhSahMaxDepth + log2(156 / leaf size) + 1.
TEST(BvhStructure, DepthStaysWithinTheTraversalStack) {
    TriangleMesh mesh;
    std::vector<float> planes;
    for (float x = 1e-37f; x < 1e37f; x *= 3) {
        planes.push_back(x);
        add_triangle(mesh, {x, 0, 0}, {x, 1, 0}, {x, 0, 1});
    }
    const Bvh bvh = make_bvh(mesh);
    const TreeFacts facts = inspect(bvh, mesh);
    EXPECT_EQ(facts.bad_bounds, 0);
    EXPECT_LE(facts.depth, kBvhSahMaxDepth + 6);
    EXPECT_LT(facts.depth, kBvhMaxDepth);
    // Rays between each pair of planes, both ways along x, and oblique ones.
    std::vector<Ray> rays;
    for (std::size_t k = 0; k + 1 < planes.size(); ++k) {
        const float between = 2 * planes[k];
        rays.push_back(Ray{{between, 0.2f, 0.3f}, {1, 0, 0}});
        rays.push_back(Ray{{between, 0.2f, 0.3f}, {-1, 0, 0}});
        rays.push_back(Ray{{between, 0.2f, 0.3f}, {planes[k + 1], 0.1f, -0.1f}});
    }
    const Comparison c = compare_with_brute(mesh, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GE(c.hits, static_cast<int>(rays.size()) * 2 / 3);
}

// 150,000 triangles: the top levels bin and partition in parallel chunks,
// the subtrees below build in parallel.
TEST(BvhStructure, SameTreeForAnyThreadCount) {
    const TriangleMesh mesh = random_soup(150000, 23, 0.02f);
    const Bvh parallel = make_bvh(mesh);
    Bvh serial;
    {
        tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
        serial = make_bvh(mesh);
    }
    ASSERT_EQ(parallel.nodes.size(), serial.nodes.size());
    EXPECT_EQ(std::memcmp(parallel.nodes.data(), serial.nodes.data(), parallel.nodes.size() * sizeof(BvhWideNode)), 0);
    ASSERT_EQ(parallel.blocks.size(), serial.blocks.size());
    EXPECT_EQ(std::memcmp(parallel.blocks.data(), serial.blocks.data(), parallel.blocks.size() * sizeof(TriangleBlock)),
              0);
    // The chunked passes put every reference on its side: each triangle
    // inside its leaf's box, each once.
    EXPECT_EQ(inspect(parallel, mesh).bad_bounds, 0);
    std::vector<int> seen(mesh.triangles.size(), 0);
    for (std::uint32_t t : testing::bvh_triangles(parallel)) ++seen[t];
    EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<std::ptrdiff_t>(seen.size()));
}

// A closed mesh (a subdivided octahedron pushed onto a sphere): every ray
// from inside hits it, in both backends alike.
TriangleMesh closed_sphere(int subdivisions) {
    TriangleMesh mesh;
    mesh.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    mesh.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (int s = 0; s < subdivisions; ++s) {
        std::vector<Index3> finer;
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            const auto found = midpoints.find(key);
            if (found != midpoints.end()) return found->second;
            mesh.positions.push_back(normalize(mesh.positions[a] + mesh.positions[b]));
            const auto index = static_cast<std::uint32_t>(mesh.positions.size() - 1);
            midpoints[key] = index;
            return index;
        };
        for (const Index3& t : mesh.triangles) {
            const std::uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
            finer.insert(finer.end(), {{t[0], ab, ca}, {ab, t[1], bc}, {ca, bc, t[2]}, {ab, bc, ca}});
        }
        mesh.triangles = std::move(finer);
    }
    return mesh;
}

TEST(BvhStructure, RaysFromInsideAClosedMeshAlwaysHit) {
    const TriangleMesh mesh = closed_sphere(4);  // 2048 triangles
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::vector<Ray> rays;
    while (rays.size() < 3000) {
        const Vec3 o{0.5f * unit(rng), 0.5f * unit(rng), 0.5f * unit(rng)};
        Vec3 d{unit(rng), unit(rng), unit(rng)};
        if (rays.size() % 5 == 0) d = Vec3{rays.size() % 2 ? 1.0f : -1.0f, 0, 0};  // zero components too
        if (dot(d, d) > 0) rays.push_back(Ray{o, d});
    }
    const Comparison c = compare_with_brute(mesh, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_EQ(c.hits, 3000);
    EXPECT_EQ(c.occluded, 3000);
}

}  // namespace
}  // namespace sombra
