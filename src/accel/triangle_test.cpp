// intersect_triangle against hand-computed answers, and the brute-force loop's
// closest-hit and tie rules.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "accel/accel.h"
#include "accel/triangle.h"

namespace sombra {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// The unit right triangle in z = 0: for a ray straight down through (x, y),
// b1 = x and b2 = y exactly.
const Vec3 kP0{0, 0, 0}, kP1{1, 0, 0}, kP2{0, 1, 0};

struct Result {
    bool hit = false;
    float t = -1, b1 = -1, b2 = -1;
};

Result trace(Vec3 o, Vec3 d, Vec3 p0 = kP0, Vec3 p1 = kP1, Vec3 p2 = kP2, float tmax = kInf) {
    Result r;
    r.hit = intersect_triangle(o, d, p0, p1, p2, tmax, r.t, r.b1, r.b2);
    return r;
}

TEST(Triangle, HitInsideGivesDistanceAndBarycentrics) {
    const Result r = trace({0.25f, 0.5f, 2.0f}, {0, 0, -1});
    ASSERT_TRUE(r.hit);
    EXPECT_FLOAT_EQ(r.t, 2.0f);
    EXPECT_FLOAT_EQ(r.b1, 0.25f);
    EXPECT_FLOAT_EQ(r.b2, 0.5f);
}

TEST(Triangle, DistanceIsInMultiplesOfTheDirection) {
    const Result r = trace({0.2f, 0.2f, 2.0f}, {0, 0, -4});
    ASSERT_TRUE(r.hit);
    EXPECT_FLOAT_EQ(r.t, 0.5f);
}

TEST(Triangle, ObliqueRayOnAGeneralTriangle) {
    // Aim at the point with weights (0.2, 0.3, 0.5) of a tilted triangle from afar.
    const Vec3 p0{1, 2, 3}, p1{4, -1, 2}, p2{0, 5, -2};
    const Vec3 target = 0.2f * p0 + 0.3f * p1 + 0.5f * p2;
    const Vec3 o{7, 9, 11};
    const Result r = trace(o, (target - o) * 0.5f, p0, p1, p2);
    ASSERT_TRUE(r.hit);
    EXPECT_NEAR(r.t, 2.0f, 1e-5f);
    EXPECT_NEAR(r.b1, 0.3f, 1e-5f);
    EXPECT_NEAR(r.b2, 0.5f, 1e-5f);
}

TEST(Triangle, MissesOnEverySide) {
    const Vec3 down{0, 0, -1};
    EXPECT_FALSE(trace({-0.01f, 0.5f, 1}, down).hit);    // beyond edge p0-p2 (b1 < 0)
    EXPECT_FALSE(trace({0.5f, -0.01f, 1}, down).hit);    // beyond edge p0-p1 (b2 < 0)
    EXPECT_FALSE(trace({0.51f, 0.5f, 1}, down).hit);     // beyond edge p1-p2 (b1 + b2 > 1)
    EXPECT_FALSE(trace({1.01f, 0.0f, 1}, down).hit);     // past corner p1
    EXPECT_FALSE(trace({0.0f, 1.01f, 1}, down).hit);     // past corner p2
    EXPECT_FALSE(trace({-0.01f, -0.01f, 1}, down).hit);  // past corner p0
}

TEST(Triangle, EdgesAndCornersCountAsInside) {
    const Vec3 down{0, 0, -1};
    const struct {
        float x, y;
    } points[] = {{0, 0.5f}, {0.5f, 0}, {0.5f, 0.5f}, {0.25f, 0.75f}, {0, 0}, {1, 0}, {0, 1}};
    for (const auto& p : points) {
        const Result r = trace({p.x, p.y, 1}, down);
        ASSERT_TRUE(r.hit) << p.x << ", " << p.y;
        EXPECT_EQ(r.b1, p.x);
        EXPECT_EQ(r.b2, p.y);
        EXPECT_EQ(r.t, 1.0f);
    }
}

TEST(Triangle, RayParallelToThePlaneMisses) {
    EXPECT_FALSE(trace({-1, 0.25f, 0}, {1, 0, 0}).hit);  // in the plane, crossing the triangle
    EXPECT_FALSE(trace({-1, 0.25f, 1}, {1, 0, 0}).hit);  // above it
    EXPECT_FALSE(trace({-1, -1, 0}, {1, 1, 0}).hit);
}

TEST(Triangle, BackFacesHitToo) {
    const Result front = trace({0.3f, 0.2f, 1}, {0, 0, -1});
    const Result back = trace({0.3f, 0.2f, -1}, {0, 0, 1});
    ASSERT_TRUE(front.hit);
    ASSERT_TRUE(back.hit);
    EXPECT_EQ(front.t, back.t);
    EXPECT_EQ(front.b1, back.b1);
    EXPECT_EQ(front.b2, back.b2);
}

TEST(Triangle, OnlyDistancesStrictlyBetweenZeroAndTmaxCount) {
    EXPECT_FALSE(trace({0.2f, 0.2f, -1}, {0, 0, -1}).hit);  // behind the origin: t = -1
    EXPECT_FALSE(trace({0.2f, 0.2f, 0}, {0, 0, -1}).hit);   // origin on the triangle: t = 0
    const Vec3 o{0.2f, 0.2f, 1}, d{0, 0, -1};
    EXPECT_FALSE(trace(o, d, kP0, kP1, kP2, 1.0f).hit);  // t = tmax is out
    EXPECT_FALSE(trace(o, d, kP0, kP1, kP2, 0.5f).hit);
    EXPECT_TRUE(trace(o, d, kP0, kP1, kP2, std::nextafter(1.0f, 2.0f)).hit);
    EXPECT_FALSE(trace(o, d, kP0, kP1, kP2, std::nanf("")).hit);
}

TEST(Triangle, MissLeavesOutputsUntouched) {
    float t = 7, b1 = 8, b2 = 9;
    EXPECT_FALSE(intersect_triangle({2, 2, 1}, {0, 0, -1}, kP0, kP1, kP2, kInf, t, b1, b2));
    EXPECT_EQ(t, 7);
    EXPECT_EQ(b1, 8);
    EXPECT_EQ(b2, 9);
}

// Degenerate triangles: collinear corners, repeated corners, a single point.
TEST(Triangle, DegenerateTrianglesNeverHitAndGiveNoNaN) {
    const Vec3 a{0.1f, 0.2f, 0.3f}, b{0.7f, -0.4f, 0.9f};
    const Vec3 degenerate[][3] = {
        {{0, 0, 0}, {1, 2, 0}, {2, 4, 0}},  // collinear
        {{0, 0, 0}, {2, 4, 0}, {1, 2, 0}},  // collinear, middle corner last
        {{0.1f, 0.1f, 0.1f}, {0.3f, 0.3f, 0.3f}, {0.2f, 0.2f, 0.2f}},
        {a, a, b},
        {a, b, a},
        {a, b, b},  // a repeated corner
        {a, a, a},  // a point
    };
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), along(0.0f, 1.0f);
    for (const auto& tri : degenerate) {
        EXPECT_FALSE(is_hittable(prepare_triangle(tri[0], tri[1], tri[2])));
        for (int i = 0; i < 2000; ++i) {
            // Rays through points of the segment (or point) the triangle collapses to.
            const float s = along(rng);
            const Vec3 on = tri[0] + s * (tri[1] - tri[0]) + (1 - s) * along(rng) * (tri[2] - tri[0]);
            const Vec3 o = on + Vec3{unit(rng), unit(rng), unit(rng)};
            float t = 5, b1 = 5, b2 = 5;
            EXPECT_FALSE(intersect_triangle(o, on - o, tri[0], tri[1], tri[2], kInf, t, b1, b2));
            EXPECT_EQ(t, 5);
        }
    }
}

TEST(Triangle, NonFiniteCornersNeverHit) {
    const float nan = std::nanf("");
    const Vec3 bad[] = {{nan, 0, 0}, {kInf, 0, 0}, {0, -kInf, 0}};
    for (const Vec3 p : bad) {
        EXPECT_FALSE(is_hittable(prepare_triangle(p, kP1, kP2)));
        EXPECT_FALSE(trace({0.2f, 0.2f, 1}, {0, 0, -1}, p, kP1, kP2).hit);
        EXPECT_FALSE(trace({0.2f, 0.2f, 1}, {0, 0, -1}, kP0, p, kP2).hit);
        EXPECT_FALSE(trace({0.2f, 0.2f, 1}, {0, 0, -1}, kP0, kP1, p).hit);
    }
}

// Random triangles and rays over a wide range of scales: every reported hit
// is finite and within its bounds.
TEST(Triangle, HitsAreAlwaysFiniteAndInRange) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f), exponent(-30.0f, 30.0f);
    int hits = 0;
    for (int i = 0; i < 200000; ++i) {
        const float scale = std::pow(10.0f, exponent(rng));
        const Vec3 p0 = Vec3{unit(rng), unit(rng), unit(rng)} * scale;
        const Vec3 p1 = Vec3{unit(rng), unit(rng), unit(rng)} * scale;
        const Vec3 p2 = Vec3{unit(rng), unit(rng), unit(rng)} * scale;
        const Vec3 o = Vec3{unit(rng), unit(rng), unit(rng)} * (scale * 3);
        const Vec3 d = (p0 + p1 + p2) * (1.0f / 3.0f) + Vec3{unit(rng), unit(rng), unit(rng)} * scale * 0.3f - o;
        const Result r = trace(o, d, p0, p1, p2);
        if (!r.hit) continue;
        ++hits;
        ASSERT_TRUE(std::isfinite(r.t) && r.t > 0);
        ASSERT_TRUE(r.b1 >= 0 && r.b2 >= 0 && r.b1 + r.b2 <= 1) << r.b1 << " " << r.b2;
        const Vec3 n = normalize(cross(p1 - p0, p2 - p0));
        ASSERT_NEAR(length(n), 1.0f, 1e-5f) << "a hittable triangle must have a usable normal";
    }
    EXPECT_GT(hits, 30000);  // about a third of the scales give triangles that can be hit
}

// The brute-force accel: nearest of several, ties, tmax.
class BruteForce : public ::testing::Test {
protected:
    // Three copies of the unit triangle at z = 0, 1, 2 (indices 0, 1, 2),
    // then a second copy of the z = 1 one (index 3).
    void SetUp() override {
        for (float z : {0.0f, 1.0f, 2.0f, 1.0f}) {
            const auto base = static_cast<std::uint32_t>(mesh.positions.size());
            mesh.positions.insert(mesh.positions.end(), {{0, 0, z}, {1, 0, z}, {0, 1, z}});
            mesh.triangles.push_back({base, base + 1, base + 2});
        }
        accel = make_accel(mesh, AccelKind::Brute);
    }
    TriangleMesh mesh;
    Accel accel;
};

TEST_F(BruteForce, FindsTheNearestHit) {
    Hit hit;
    ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, -1}}, hit));
    EXPECT_EQ(hit.triangle, 2u);
    EXPECT_EQ(hit.t, 3.0f);
    EXPECT_FLOAT_EQ(hit.b1, 0.2f);
    EXPECT_FLOAT_EQ(hit.b2, 0.3f);
    ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.3f, -5}, {0, 0, 1}}, hit));
    EXPECT_EQ(hit.triangle, 0u);
    EXPECT_EQ(hit.t, 5.0f);
}

TEST_F(BruteForce, EqualDistancesGoToTheLowerIndex) {
    Hit hit;
    // From z = 1.5 downwards the copies at z = 1 (indices 1 and 3) are nearest.
    ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.3f, 1.5f}, {0, 0, -1}}, hit));
    EXPECT_EQ(hit.triangle, 1u);
    EXPECT_EQ(hit.t, 0.5f);
}

TEST_F(BruteForce, TmaxLimitsHitsAndShadowRays) {
    Hit hit;
    hit.triangle = 99;
    EXPECT_FALSE(intersect(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, -1}, 3.0f}, hit));
    EXPECT_EQ(hit.triangle, 99u);  // untouched on a miss
    ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, -1}, 3.5f}, hit));
    EXPECT_EQ(hit.triangle, 2u);
    EXPECT_FALSE(occluded(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, -1}, 3.0f}));
    EXPECT_TRUE(occluded(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, -1}, 3.5f}));
    EXPECT_FALSE(occluded(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, 1}}));   // pointing away
    EXPECT_FALSE(occluded(accel, Ray{{0.8f, 0.8f, 5}, {0, 0, -1}}));  // beside them
}

TEST_F(BruteForce, UntraceableRaysHitNothing) {
    Hit hit;
    const float nan = std::nanf("");
    EXPECT_FALSE(intersect(accel, Ray{{0.2f, 0.3f, 5}, {0, 0, 0}}, hit));
    EXPECT_FALSE(intersect(accel, Ray{{0.2f, 0.3f, 5}, {0, nan, -1}}, hit));
    EXPECT_FALSE(intersect(accel, Ray{{0.2f, kInf, 5}, {0, 0, -1}}, hit));
    EXPECT_FALSE(occluded(accel, Ray{{nan, 0.3f, 5}, {0, 0, -1}}));
}

TEST(AccelNames, ParseAndNameRoundTrip) {
    for (std::string_view name : available_accels()) {
        const std::optional<AccelKind> kind = parse_accel_kind(name);
        ASSERT_TRUE(kind.has_value()) << name;
        EXPECT_EQ(accel_name(*kind), name);
    }
    EXPECT_EQ(available_accels().front(), "bvh");
    EXPECT_FALSE(parse_accel_kind("BVH").has_value());
#ifndef SOMBRA_HAVE_EMBREE
    EXPECT_FALSE(parse_accel_kind("embree").has_value());  // offered only in builds with Embree
#endif
    EXPECT_FALSE(parse_accel_kind("").has_value());
}

}  // namespace
}  // namespace sombra
