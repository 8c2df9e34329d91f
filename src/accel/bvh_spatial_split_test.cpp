// Spatial splits: the clipping they rest on, the trees they build (every
// part of every triangle still inside a leaf that holds it, the reference
// budget kept, the same bytes for any thread count), and hits bit-identical
// to brute force with splitting forced everywhere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <random>
#include <vector>

#include <tbb/global_control.h>

#include "accel/accel.h"
#include "accel/accel_test_util.h"
#include "accel/bvh_spatial_split.h"
#include "scene/mesh_file.h"

namespace sombra {
namespace {

using bvh_build::Box;
using testing::add_triangle;
using testing::aggressive_spatial_splits;
using testing::compare_with_brute;
using testing::Comparison;
using testing::random_point;
using testing::random_rays;
using testing::random_soup;

constexpr int W = kBvhWidth;

bool inside(const Box& box, Vec3 p) {
    return box.bmin.x <= p.x && p.x <= box.bmax.x && box.bmin.y <= p.y && p.y <= box.bmax.y && box.bmin.z <= p.z &&
           p.z <= box.bmax.z;
}

Vec3 point_on(const Vec3 v[3], float b1, float b2) { return (1 - b1 - b2) * v[0] + b1 * v[1] + b2 * v[2]; }

// Points of the triangle on either side of the plane lie in that side's box;
// the boxes stay within the given box and on their side of the plane.
TEST(SpatialSplit, ClippedBoxesHoldTheTrianglesPartsOnEachSide) {
    std::mt19937 rng(41);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int left_points = 0, right_points = 0, flat_corners = 0;
    for (int trial = 0; trial < 2000; ++trial) {
        Vec3 v[3];
        for (Vec3& p : v) p = random_point(rng, Vec3{-3.0f}, Vec3{5.0f});
        const int axis = trial % 3;
        if (trial % 7 == 0) v[1][axis] = v[0][axis];  // an edge in a plane perpendicular to the axis
        Box box;
        for (const Vec3& p : v) box.grow(p);
        // Sometimes a box around only part of the triangle, as after an earlier split.
        if (trial % 3 == 1) box.bmax[(axis + 1) % 3] = 0.5f * (box.bmin[(axis + 1) % 3] + box.bmax[(axis + 1) % 3]);
        float plane = box.bmin[axis] + unit(rng) * (box.bmax[axis] - box.bmin[axis]);
        if (trial % 5 == 0) plane = v[trial % 3][axis];  // through a corner
        flat_corners += trial % 5 == 0;
        Box left, right;
        bvh_build::clip_triangle_box(v, box, axis, plane, left, right);
        if (!left.empty()) {
            EXPECT_LE(left.bmax[axis], plane);
        }
        if (!right.empty()) {
            EXPECT_GE(right.bmin[axis], plane);
        }
        for (int s = 0; s < 200; ++s) {
            float b1 = unit(rng), b2 = unit(rng);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            const Vec3 p = s == 0 ? v[trial % 3] : point_on(v, b1, b2);
            if (!inside(box, p)) continue;
            if (p[axis] <= plane) {
                ++left_points;
                ASSERT_TRUE(inside(left, p)) << "trial " << trial << " sample " << s;
            }
            if (p[axis] >= plane) {
                ++right_points;
                ASSERT_TRUE(inside(right, p)) << "trial " << trial << " sample " << s;
            }
        }
    }
    EXPECT_GT(left_points, 50000);
    EXPECT_GT(right_points, 50000);
    EXPECT_GT(flat_corners, 0);
}

// The leaves that hold each triangle, as (node, slot) boxes.
std::vector<std::vector<Box>> leaf_boxes_per_triangle(const Bvh& bvh, std::size_t triangles) {
    std::vector<std::vector<Box>> boxes(triangles);
    for (const BvhWideNode& node : bvh.nodes) {
        for (int i = 0; i < W; ++i) {
            if (node.count[i] == 0) continue;
            const Box box{{node.bounds[i], node.bounds[2 * W + i], node.bounds[4 * W + i]},
                          {node.bounds[W + i], node.bounds[3 * W + i], node.bounds[5 * W + i]}};
            std::vector<std::uint32_t> seen;
            for (std::uint32_t k = 0; k < node.count[i]; ++k) {
                const std::uint32_t t = bvh.blocks[node.child[i] + k / 4].triangle[k % 4];
                EXPECT_EQ(std::count(seen.begin(), seen.end(), t), 0) << "triangle " << t << " twice in one leaf";
                seen.push_back(t);
                boxes[t].push_back(box);
            }
        }
    }
    return boxes;
}

// Large triangles (a soup of big ones, the parts of a room) around many
// small ones: the case spatial splits are for.
TriangleMesh room_with_clutter() {
    TriangleMesh mesh = random_soup(3000, 42, 0.02f);
    add_triangle(mesh, {-1, -1, -1}, {2, -1, -1}, {2, -1, 2});  // floor
    add_triangle(mesh, {-1, -1, -1}, {2, -1, 2}, {-1, -1, 2});
    add_triangle(mesh, {-1, -1, -1}, {-1, 2, -1}, {2, 2, -1});  // back wall
    add_triangle(mesh, {-1, -1, -1}, {2, 2, -1}, {2, -1, -1});
    std::mt19937 rng(43);
    for (int k = 0; k < 60; ++k) {  // long thin slivers across the room
        const Vec3 a = random_point(rng, Vec3{-1.0f}, Vec3{2.0f}), b = random_point(rng, Vec3{-1.0f}, Vec3{2.0f});
        add_triangle(mesh, a, b, b + Vec3{0.01f, 0.02f, -0.01f});
    }
    return mesh;
}

TEST(SpatialSplit, EveryPartOfEveryTriangleIsInALeafThatHoldsIt) {
    const TriangleMesh mesh = room_with_clutter();
    const Bvh bvh = make_bvh(mesh, aggressive_spatial_splits());
    const std::vector<std::vector<Box>> boxes = leaf_boxes_per_triangle(bvh, mesh.triangles.size());
    std::size_t references = 0;
    std::mt19937 rng(44);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        ASSERT_FALSE(boxes[t].empty()) << "triangle " << t << " in no leaf";
        references += boxes[t].size();
        Vec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = mesh.positions[mesh.triangles[t][k]];
        for (int s = 0; s < 300; ++s) {
            float b1 = unit(rng), b2 = unit(rng);
            if (b1 + b2 > 1) {
                b1 = 1 - b1;
                b2 = 1 - b2;
            }
            // The point in double, and a box test with a tolerance far below
            // any triangle's size: a float point may round off the triangle
            // (off an axis-aligned one's plane), but a lost part is no rounding.
            const double w0 = 1.0 - b1 - b2;
            double p[3];
            for (int a = 0; a < 3; ++a) p[a] = s < 3 ? v[s][a] : w0 * v[0][a] + b1 * double(v[1][a]) + b2 * double(v[2][a]);
            constexpr double kTolerance = 1e-6;
            bool covered = false;
            for (const Box& box : boxes[t]) {
                bool in = true;
                for (int a = 0; a < 3; ++a) in = in && box.bmin[a] - kTolerance <= p[a] && p[a] <= box.bmax[a] + kTolerance;
                covered = covered || in;
            }
            ASSERT_TRUE(covered) << "triangle " << t << ": a point in none of its " << boxes[t].size() << " leaves";
        }
    }
    // Splitting happened (else this test proves nothing), within the budget.
    EXPECT_GT(references, mesh.triangles.size() + mesh.triangles.size() / 50);
    EXPECT_LE(references, 2 * mesh.triangles.size());
}

// A few huge triangles crossing each other and the whole scene, over many
// small ones: every node's children overlap, so spatial splits are wanted
// everywhere; the budget must hold the references to it.
TEST(SpatialSplit, ReferenceBudgetHoldsOnAPathologicalMesh) {
    TriangleMesh mesh = random_soup(5000, 45, 0.005f);
    std::mt19937 rng(45);
    for (int k = 0; k < 300; ++k) {
        add_triangle(mesh, random_point(rng, Vec3{-5.0f}, Vec3{0.0f}), random_point(rng, Vec3{1.0f}, Vec3{6.0f}),
                     random_point(rng, Vec3{-5.0f, 1.0f, -5.0f}, Vec3{0.0f, 6.0f, 0.0f}));
    }
    for (const float budget : {0.0f, 0.05f, 0.3f}) {
        BvhBuildOptions options = aggressive_spatial_splits();
        options.spatial_split_budget = budget;
        const Bvh bvh = make_bvh(mesh, options);
        const std::size_t references = testing::bvh_triangles(bvh).size();
        const auto allowed = static_cast<std::size_t>(static_cast<double>(mesh.triangles.size()) * (1.0 + budget));
        EXPECT_LE(references, allowed) << "budget " << budget;
        if (budget == 0.0f) {
            EXPECT_EQ(references, mesh.triangles.size());
        }
        if (budget == 0.05f) {  // the huge triangles want more than this: the budget is what stops them
            EXPECT_GT(references, allowed - allowed / 100) << "the budget did not bind: the test proves nothing";
        }
    }
    const Comparison c = compare_with_brute(mesh, random_rays(mesh, 3000, 46, Vec3{-0.5f}, Vec3{1.5f}),
                                            BvhBuildOptions{true, 0.0f, 0.3f});
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1000);
}

TEST(SpatialSplit, SameTreeForAnyThreadCount) {
    const TriangleMesh mesh = room_with_clutter();
    const TriangleMesh big = random_soup(30000, 47, 0.05f);  // above the parallel threshold at several levels
    for (const TriangleMesh* m : {&mesh, &big}) {
        const Bvh parallel = make_bvh(*m, aggressive_spatial_splits());
        Bvh serial;
        {
            tbb::global_control one_thread(tbb::global_control::max_allowed_parallelism, 1);
            serial = make_bvh(*m, aggressive_spatial_splits());
        }
        EXPECT_GT(testing::bvh_triangles(parallel).size(), m->triangles.size());  // splits happened
        ASSERT_EQ(parallel.nodes.size(), serial.nodes.size());
        EXPECT_EQ(std::memcmp(parallel.nodes.data(), serial.nodes.data(), parallel.nodes.size() * sizeof(BvhWideNode)),
                  0);
        ASSERT_EQ(parallel.blocks.size(), serial.blocks.size());
        EXPECT_EQ(
            std::memcmp(parallel.blocks.data(), serial.blocks.data(), parallel.blocks.size() * sizeof(TriangleBlock)),
            0);
    }
}

TEST(SpatialSplit, ForcedSplitsHitExactlyAsBruteForce) {
    const TriangleMesh room = room_with_clutter();
    Comparison c = compare_with_brute(room, random_rays(room, 4000, 48, Vec3{-1.2f}, Vec3{2.2f}),
                                      aggressive_spatial_splits());
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1000);

    // Axis-aligned triangles lying exactly in bin planes, and ones sharing edges.
    TriangleMesh grid;
    for (int k = 0; k < 16; ++k) {
        const float x = static_cast<float>(k) / 16.0f;
        add_triangle(grid, {x, 0, 0}, {x, 1, 0}, {x, 0, 1});
        add_triangle(grid, {0, x, 0}, {1, x, 1}, {1, x, 0});
        add_triangle(grid, {0, 0, x}, {1, 1, x}, {0, 1, x});
        add_triangle(grid, {0, 0, x}, {1, 0, x}, {1, 1, x});
    }
    c = compare_with_brute(grid, random_rays(grid, 4000, 49, Vec3{-0.5f}, Vec3{1.5f}), aggressive_spatial_splits());
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1000);
}

TEST(SpatialSplit, HighQualityAccelHitsExactlyAsBruteForce) {
    const TriangleMesh room = room_with_clutter();
    const Accel high = make_accel(room, AccelKind::Bvh, BuildQuality::High);
    const Accel brute = make_accel(room, AccelKind::Brute);
    EXPECT_GT(testing::bvh_triangles(high.bvh).size(), room.triangles.size());  // the knob turns spatial splits on
    EXPECT_EQ(testing::bvh_triangles(make_accel(room, AccelKind::Bvh, BuildQuality::Fast).bvh).size(),
              room.triangles.size());
    for (const Ray& ray : random_rays(room, 2000, 50, Vec3{-1.2f}, Vec3{2.2f})) {
        Hit want, got;
        const bool want_found = intersect(brute, ray, want);
        ASSERT_EQ(intersect(high, ray, got), want_found);
        ASSERT_EQ(occluded(high, ray), want_found);
        if (want_found) {
            EXPECT_EQ(got.triangle, want.triangle);
            EXPECT_EQ(std::memcmp(&got.t, &want.t, sizeof(float)), 0);
        }
    }
    EXPECT_EQ(parse_build_quality("high"), BuildQuality::High);
    EXPECT_EQ(parse_build_quality("fast"), BuildQuality::Fast);
    EXPECT_FALSE(parse_build_quality("medium"));
    EXPECT_EQ(build_quality_name(BuildQuality::High), "high");
}

}  // namespace
}  // namespace sombra
