// The BVH must return exactly what the brute-force loop returns, ray for ray:
// random soups, then the corner cases every BVH library got wrong once.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>

#include "accel/accel.h"
#include "accel/accel_test_util.h"

namespace sombra {
namespace {

using testing::add_triangle;
using testing::compare_with_brute;
using testing::Comparison;
using testing::random_rays;
using testing::random_soup;

constexpr float kInf = std::numeric_limits<float>::infinity();

class RandomSoup : public ::testing::TestWithParam<int> {};

TEST_P(RandomSoup, BvhEqualsBruteForce) {
    const int count = GetParam();
    const TriangleMesh mesh = random_soup(count, static_cast<std::uint32_t>(count));
    // 70,000 triangles: the root is binned and partitioned in parallel chunks
    // (kParallelPassRefs); few rays, since brute force pays for each.
    const int ray_count = count >= 70000 ? 150 : count >= 10000 ? 3000 : 4000;
    const Comparison c = compare_with_brute(mesh, random_rays(mesh, ray_count, 1, Vec3{-0.5f}, Vec3{1.5f}));
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, ray_count / 5);
    EXPECT_GT(c.occluded, ray_count / 5);
    EXPECT_LT(c.hits, ray_count);
}

INSTANTIATE_TEST_SUITE_P(Sizes, RandomSoup, ::testing::Values(1, 2, 3, 100, 10000, 70000));

TEST(Bvh, RaysStartingInsideTheSoup) {
    const TriangleMesh mesh = random_soup(2000, 5, 0.05f);
    const Comparison c = compare_with_brute(mesh, random_rays(mesh, 3000, 6, Vec3{0.2f}, Vec3{0.8f}));
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1500);
}

// Many triangles about one centroid: rotated copies and exact duplicates.
TEST(Bvh, AllCentroidsEqual) {
    TriangleMesh mesh;
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> angle(0.0f, 6.2831853f);
    const Vec3 centre{0.5f, 0.5f, 0.5f};
    for (int i = 0; i < 300; ++i) {
        // Corners at 120° steps around the centre: the centroid is the centre.
        const float a = angle(rng), tilt = angle(rng);
        Vec3 corners[3];
        for (int k = 0; k < 3; ++k) {
            const float phi = a + 2.0943951f * static_cast<float>(k);
            corners[k] =
                centre + 0.3f * Vec3{std::cos(phi), std::sin(phi) * std::cos(tilt), std::sin(phi) * std::sin(tilt)};
        }
        add_triangle(mesh, corners[0], corners[1], corners[2]);
        if (i % 3 == 0) add_triangle(mesh, corners[0], corners[1], corners[2]);  // an exact duplicate
    }
    const Comparison c = compare_with_brute(mesh, random_rays(mesh, 3000, 4, Vec3{-0.5f}, Vec3{1.5f}));
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1000);

    const Bvh bvh = make_bvh(mesh);
    for (const BvhWideNode& node : bvh.nodes) {
        for (std::uint32_t count : node.count) EXPECT_LE(count, kBvhMaxLeafSize);
    }
}

// Exact duplicates everywhere: the lower index of each pair must win in both.
TEST(Bvh, DuplicateTrianglesResolveToTheLowerIndex) {
    const TriangleMesh base = random_soup(500, 8);
    TriangleMesh mesh = base;
    for (const Index3& tri : base.triangles) mesh.triangles.push_back(tri);  // indices 500..999 copy 0..499
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    int hits = 0;
    for (const Ray& ray : random_rays(mesh, 2000, 9, Vec3{-0.5f}, Vec3{1.5f})) {
        Hit hit;
        if (!intersect(bvh, ray, hit)) continue;
        ++hits;
        EXPECT_LT(hit.triangle, 500u);
    }
    EXPECT_GT(hits, 500);
    const Comparison c = compare_with_brute(mesh, random_rays(mesh, 2000, 9, Vec3{-0.5f}, Vec3{1.5f}));
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
}

// Degenerate, non-finite and out-of-range triangles among good ones: left out
// of the tree, never hit, and nothing else changes.
TEST(Bvh, UnhittableTrianglesMixedIn) {
    TriangleMesh mesh = random_soup(1500, 10);
    std::mt19937 rng(12);
    const float nan = std::nanf("");
    std::vector<std::uint32_t> bad;
    for (std::uint32_t i = 0; i < mesh.triangles.size(); i += 3) {
        Index3& tri = mesh.triangles[i];
        Vec3* p[3] = {&mesh.positions[tri[0]], &mesh.positions[tri[1]], &mesh.positions[tri[2]]};
        switch (i % 5) {
            case 0: *p[2] = *p[0] + 2.0f * (*p[1] - *p[0]); break;  // collinear (after rounding: nearly)
            case 1: *p[1] = *p[0]; break;                           // repeated corner
            case 2:
                *p[1] = *p[0];
                *p[2] = *p[0];
                break;                          // a point
            case 3: p[1]->y = nan; break;       // NaN corner
            default: tri[2] = 1u << 30; break;  // index out of range
        }
        if (!is_hittable(prepare_triangle(*p[0], *p[1], *p[2])) || i % 5 == 4) bad.push_back(i);
    }
    ASSERT_GT(bad.size(), 400u);

    const std::vector<std::uint32_t> held = testing::bvh_triangles(make_bvh(mesh));
    for (std::uint32_t i : bad) {
        EXPECT_EQ(std::count(held.begin(), held.end(), i), 0) << i;
    }
    const std::vector<Ray> rays = random_rays(mesh, 4000, 13, Vec3{-0.5f}, Vec3{1.5f});
    const Accel accel = make_accel(mesh, AccelKind::Bvh);
    for (const Ray& ray : rays) {
        Hit hit;
        if (intersect(accel, ray, hit)) {
            EXPECT_FALSE(std::binary_search(bad.begin(), bad.end(), hit.triangle)) << hit.triangle;
        }
    }
    const Comparison c = compare_with_brute(mesh, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, 1000);
}

// A grid of axis-aligned boxes and axis-aligned rays running along box faces
// and edges, with +0 and −0 direction components: the slab test must not
// turn 0·∞ into a culled box.
TEST(Bvh, AxisAlignedRaysGrazingBoxFaces) {
    TriangleMesh mesh;
    auto add_quad = [&](Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
        add_triangle(mesh, a, b, c);
        add_triangle(mesh, a, c, d);
    };
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                const Vec3 lo{static_cast<float>(i), static_cast<float>(j), static_cast<float>(k)};
                const Vec3 hi = lo + Vec3{0.5f};
                add_quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z});
                add_quad({lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
                add_quad({lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {lo.x, lo.y, hi.z});
                add_quad({hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z});
                add_quad({lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z});
                add_quad({lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z});
            }
    // Origins on the half-unit lattice (every box face and edge lies on it),
    // directions along the axes and the face diagonals.
    std::vector<Ray> rays;
    const float coords[] = {-1.0f, 0.0f, 0.25f, 0.5f, 1.0f, 2.5f, 3.0f, 3.5f, 5.0f};
    const Vec3 dirs[] = {{1, 0, 0},     {-1, 0, 0},         {0, 1, 0}, {0, -1, 0}, {0, 0, 1},  {0, 0, -1},
                         {1, -0.0f, 0}, {-0.0f, -1, -0.0f}, {1, 1, 0}, {0, -1, 1}, {-1, 0, -1}};
    for (float x : coords)
        for (float y : coords)
            for (float z : coords)
                for (const Vec3& d : dirs) rays.push_back(Ray{{x, y, z}, d});
    const Comparison c = compare_with_brute(mesh, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, static_cast<int>(rays.size()) / 4);
}

// A ray straight down the edge x = 0 of a single quad lies in a face plane of
// every box around it; it must still hit, whatever the sign of its zeros.
TEST(Bvh, ZeroDirectionComponentsOnABoxFaceStillHit) {
    TriangleMesh mesh;
    add_triangle(mesh, {0, 0, 0}, {1, 0, 0}, {1, 1, 0});
    add_triangle(mesh, {0, 0, 0}, {1, 1, 0}, {0, 1, 0});
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    for (float zero : {0.0f, -0.0f}) {
        for (Vec3 o : {Vec3{0, 0.5f, 1}, Vec3{1, 0.5f, 1}, Vec3{0.5f, 0, 1}, Vec3{0, 0, 1}, Vec3{1, 1, 1}}) {
            Hit hit;
            ASSERT_TRUE(intersect(bvh, Ray{o, {zero, zero, -1}}, hit)) << o.x << " " << o.y;
            EXPECT_EQ(hit.t, 1.0f);
            EXPECT_TRUE(occluded(bvh, Ray{o, {zero, zero, -1}}));
        }
        // Along the quad's own plane and edge: parallel, so no hit.
        Hit hit;
        EXPECT_FALSE(intersect(bvh, Ray{{-1, 0, 0}, {1, zero, zero}}, hit));
        EXPECT_FALSE(intersect(bvh, Ray{{-1, 0.5f, 0}, {1, zero, zero}}, hit));
    }
}

// Rays exactly through a shared edge or a shared corner hit several triangles
// at the same t; both backends must pick the lowest index. The fan around one
// corner spans several leaves and its triangle order is shuffled.
TEST(Bvh, SharedEdgesAndCornersPickTheLowestIndex) {
    TriangleMesh mesh = random_soup(200, 14, 0.05f);
    for (Vec3& p : mesh.positions) p.z += 2.0f;  // clutter above, out of the way
    const Vec3 centre{0.5f, 0.5f, 0.0f};
    const int fan = 40;
    std::vector<std::array<Vec3, 3>> fan_triangles;
    for (int k = 0; k < fan; ++k) {
        const float a0 = 6.2831853f * static_cast<float>(k) / fan, a1 = 6.2831853f * static_cast<float>(k + 1) / fan;
        const Vec3 p1 = centre + 0.4f * Vec3{std::cos(a0), std::sin(a0), 0};
        const Vec3 p2 = centre + 0.4f * Vec3{std::cos(a1), std::sin(a1), 0};
        fan_triangles.push_back({centre, p1, p2});
    }
    // The two halves of a square split along its diagonal, away from the fan.
    fan_triangles.push_back({Vec3{2, 0, 0}, Vec3{3, 0, 0}, Vec3{2, 1, 0}});
    fan_triangles.push_back({Vec3{3, 0, 0}, Vec3{3, 1, 0}, Vec3{2, 1, 0}});
    std::vector<int> order(fan_triangles.size());
    std::iota(order.begin(), order.end(), 0);
    std::shuffle(order.begin(), order.end(), std::mt19937(15));
    for (int i : order) add_triangle(mesh, fan_triangles[i][0], fan_triangles[i][1], fan_triangles[i][2]);
    // A rotated copy of the fan's corners (corner order changed) right after.
    for (int i : order) add_triangle(mesh, fan_triangles[i][1], fan_triangles[i][2], fan_triangles[i][0]);

    std::vector<Ray> rays;
    rays.push_back(Ray{{0.5f, 0.5f, 1}, {0, 0, -1}});  // the fan's centre
    rays.push_back(Ray{{0.5f, 0.5f, -1}, {0, 0, 1}});  // from below
    for (int k = 1; k < 64; ++k) {                     // points of the diagonal x + y = 3, exact in binary
        const float s = static_cast<float>(k) / 64;
        rays.push_back(Ray{{2 + s, 1 - s, 1}, {0, 0, -1}});
    }
    std::mt19937 rng(16);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    for (int k = 0; k < 500; ++k) {  // oblique rays through the centre
        const Vec3 o = centre + Vec3{unit(rng), unit(rng), 0.2f + std::fabs(unit(rng))};
        rays.push_back(Ray{o, centre - o});
    }
    const Comparison c = compare_with_brute(mesh, rays);
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;

    // An independent oracle for the exact rays: every triangle hit at the
    // smallest t is a candidate, and the lowest index among them must win.
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    for (std::size_t r = 0; r < 65; ++r) {
        float best_t = kInf;
        std::uint32_t best = kNoHit;
        int ties = 0;
        for (std::uint32_t i = 0; i < mesh.triangles.size(); ++i) {
            const Index3& tri = mesh.triangles[i];
            float t, b1, b2;
            if (!intersect_triangle(rays[r].origin, rays[r].dir, mesh.positions[tri[0]], mesh.positions[tri[1]],
                                    mesh.positions[tri[2]], kInf, t, b1, b2))
                continue;
            if (t < best_t) {
                best_t = t;
                best = i;
                ties = 1;
            } else if (t == best_t) {
                ++ties;
                best = std::min(best, i);
            }
        }
        ASSERT_GE(ties, 2) << "ray " << r << " should hit several triangles at the same t";
        Hit hit;
        ASSERT_TRUE(intersect(bvh, rays[r], hit));
        EXPECT_EQ(hit.triangle, best) << "ray " << r;
        EXPECT_EQ(hit.t, best_t);
    }
}

TEST(Bvh, TmaxIsExclusive) {
    TriangleMesh mesh = random_soup(300, 17);
    add_triangle(mesh, {-5, -5, -1}, {5, -5, -1}, {0, 5, -1});  // a big floor under everything
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    const Ray down{{0.5f, 0.5f, 2}, {0, 0, -1}};
    Hit first;
    ASSERT_TRUE(intersect(bvh, down, first));
    Ray limited = down;
    limited.tmax = first.t;
    Hit hit;
    hit.triangle = 12345;
    // `first` is the closest hit: with tmax = first.t (exclusive) nothing is
    // left to hit, and `hit` stays untouched.
    EXPECT_FALSE(intersect(bvh, limited, hit));
    EXPECT_EQ(hit.triangle, 12345u);
    limited.tmax = std::nextafter(first.t, kInf);
    ASSERT_TRUE(intersect(bvh, limited, hit));
    EXPECT_EQ(hit.triangle, first.triangle);
    EXPECT_TRUE(occluded(bvh, limited));
    limited.tmax = 0.5f;  // stops above all the geometry
    EXPECT_FALSE(intersect(bvh, limited, hit));
    EXPECT_FALSE(occluded(bvh, limited));
}

TEST(Bvh, EmptyMeshesHitNothing) {
    TriangleMesh empty;
    TriangleMesh only_degenerate;
    add_triangle(only_degenerate, {0, 0, 0}, {1, 1, 1}, {2, 2, 2});
    add_triangle(only_degenerate, {1, 0, 0}, {1, 0, 0}, {0, 1, 0});
    for (const TriangleMesh* mesh : {&empty, &only_degenerate}) {
        const Accel accel = make_accel(*mesh, AccelKind::Bvh);
        EXPECT_TRUE(accel.bvh.nodes.empty());
        EXPECT_EQ(accel_memory_bytes(accel), 0u);
        Hit hit;
        EXPECT_FALSE(intersect(accel, Ray{{0.5f, 0.5f, 5}, {0, 0, -1}}, hit));
        EXPECT_FALSE(occluded(accel, Ray{{0.5f, 0.5f, 5}, {0, 0, -1}}));
        EXPECT_FALSE(intersect(make_accel(*mesh, AccelKind::Brute), Ray{{0.5f, 0.5f, 5}, {0, 0, -1}}, hit));
    }
}

TEST(Bvh, UntraceableRaysHitNothing) {
    const TriangleMesh mesh = random_soup(100, 18);
    const Accel accel = make_accel(mesh, AccelKind::Bvh);
    const float nan = std::nanf("");
    Hit hit;
    EXPECT_FALSE(intersect(accel, Ray{{0.5f, 0.5f, 0.5f}, {0, 0, 0}}, hit));
    EXPECT_FALSE(intersect(accel, Ray{{0.5f, 0.5f, 0.5f}, {nan, 0, 1}}, hit));
    EXPECT_FALSE(intersect(accel, Ray{{0.5f, kInf, 0.5f}, {0, 0, 1}}, hit));
    EXPECT_FALSE(occluded(accel, Ray{{0.5f, 0.5f, 0.5f}, {0, -kInf, 0}}));
    EXPECT_FALSE(intersect(accel, Ray{{0.5f, 0.5f, 5}, {0, 0, -1}, nan}, hit));
    EXPECT_FALSE(intersect(accel, Ray{{0.5f, 0.5f, 5}, {0, 0, -1}, -1.0f}, hit));
}

}  // namespace
}  // namespace sombra
