// The four-lane triangle test against the scalar intersect_triangle: every
// lane it decides must match bit for bit, and every lane it leaves to the
// scalar test must be one the scalar test has to re-decide.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "accel/accel_test_util.h"
#include "accel/bvh_triangle4.h"
#include "accel/triangle.h"

namespace sombra {
namespace {

TriangleBlock make_block(const Vec3 (&corners)[4][3]) {
    TriangleBlock block{};
    for (int lane = 0; lane < 4; ++lane) {
        const Vec3 p0 = corners[lane][0], e1 = corners[lane][1] - p0, e2 = corners[lane][2] - p0;
        for (int a = 0; a < 3; ++a) {
            block.p0[a][lane] = p0[a];
            block.p1[a][lane] = corners[lane][1][a];
            block.p2[a][lane] = corners[lane][2][a];
        }
        block.em[lane] = max_component(max(abs(e1), abs(e2)));
        block.triangle[lane] = static_cast<std::uint32_t>(lane);
    }
    return block;
}

struct Tally {
    int sure = 0, near = 0, scalar_hits = 0, mismatches = 0;
};

// Runs one ray against the block both ways and counts disagreements: a
// `sure` lane must be a scalar hit with the same bits; a lane in neither
// set must be a scalar miss.
void check_ray(const TriangleBlock& block, const Vec3 (&corners)[4][3], Vec3 o, Vec3 d, float tmax, Tally& tally) {
    BlockHits found;
    intersect_block(block, make_ray_lanes(o, d), tmax, tmax, found);
    for (int lane = 0; lane < 4; ++lane) {
        float t = 0, b1 = 0, b2 = 0;
        const bool hit =
            intersect_triangle(o, d, corners[lane][0], corners[lane][1], corners[lane][2], tmax, t, b1, b2);
        tally.scalar_hits += hit;
        const bool sure = (found.sure >> lane) & 1, near = (found.near >> lane) & 1;
        tally.sure += sure;
        tally.near += near;
        if (sure) {
            float c1, c2;
            finish_barycentrics(found, lane, c1, c2);
            const float want[3] = {t, b1, b2}, got[3] = {found.t[lane], c1, c2};
            tally.mismatches += !hit || std::memcmp(want, got, sizeof want) != 0 || near;
        } else if (!near) {
            tally.mismatches += hit;
        }
    }
}

TEST(Triangle4, LanesMatchTheScalarTestOnRandomRays) {
    std::mt19937 rng(41);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    auto point = [&] { return Vec3{unit(rng), unit(rng), unit(rng)}; };
    Tally tally;
    for (int round = 0; round < 2000; ++round) {
        Vec3 corners[4][3];
        for (auto& tri : corners) tri[0] = point(), tri[1] = point(), tri[2] = point();
        const TriangleBlock block = make_block(corners);
        for (int r = 0; r < 20; ++r) {
            const Vec3 o = 3.0f * point();
            // Aim at a corner-weighted point of one triangle, an edge of one, or anywhere.
            const auto& tri = corners[r % 4];
            const float w = (unit(rng) + 1.0f) / 2.0f;
            const Vec3 target =
                r % 3 == 0 ? point()
                           : (r % 3 == 1 ? (1 - w) * tri[0] + w * tri[1] : (tri[0] + tri[1] + tri[2]) * (1.0f / 3));
            check_ray(block, corners, o, target - o, r % 5 == 0 ? 0.5f : INFINITY, tally);
        }
    }
    EXPECT_EQ(tally.mismatches, 0);
    EXPECT_GT(tally.sure, 10000);       // most hits are decided in the lanes,
    EXPECT_GT(tally.near, 100);         // rays at edges go to the scalar test,
    EXPECT_LT(tally.near, tally.sure);  // but they stay the exception
}

// A quad grid's shared edges and corners, hit exactly: the scalar test's
// near-edge branch decides these, so the lanes must hand them over.
TEST(Triangle4, RaysThroughSharedEdgesGoToTheScalarTest) {
    Vec3 corners[4][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                          {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                          {{1, 0, 0}, {2, 0, 0}, {2, 1, 0}},
                          {{1, 0, 0}, {2, 1, 0}, {1, 1, 0}}};
    const TriangleBlock block = make_block(corners);
    Tally tally;
    std::mt19937 rng(42);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int r = 0; r < 2000; ++r) {
        const float s = unit(rng);
        const Vec3 target = r % 2 == 0 ? Vec3{s, s, 0} : Vec3{1, s, 0};  // the diagonal, or the x = 1 edge
        const Vec3 o{unit(rng) * 3 - 1, unit(rng) * 3 - 1, 1 + unit(rng)};
        check_ray(block, corners, o, target - o, INFINITY, tally);
    }
    EXPECT_EQ(tally.mismatches, 0);
    EXPECT_GE(tally.scalar_hits, 2000);  // watertight: at least one triangle per ray
}

// The scalar test's own decision to re-decide a lane near an edge,
// transcribed from triangle.h: outside in float, within the band, and t in
// (0, tmax).
bool scalar_redecides(const Vec3 (&tri)[3], Vec3 o, Vec3 d, float tmax) {
    const PreparedTriangle p = prepare_triangle(tri[0], tri[1], tri[2]);
    const float det = -dot(d, p.n);
    if (!(det != 0.0f)) return false;
    const Vec3 e1 = p.p1 - p.p0, e2 = p.p2 - p.p0, tvec = o - p.p0, c = cross(tvec, d);
    const float su = dot(e2, c), sv = -dot(e1, c);
    const bool neg = det < 0.0f;
    const float U = neg ? -su : su, V = neg ? -sv : sv, W = (neg ? -det : det) - U - V;
    if (U >= 0.0f && V >= 0.0f && W >= 0.0f) return false;
    const float em = max_component(max(abs(e1), abs(e2)));
    const float band = 0x1p-15f * (max_component(abs(d)) * em * (max_component(abs(tvec)) + em));
    if (!(U >= -band && V >= -band && W >= -band)) return false;
    const float t = dot(tvec, p.n) * (1.0f / det);
    return t > 0.0f && t < tmax;
}

// The lanes handed to the scalar test are exactly those it would re-decide
// (the same band to the bit): rays from far away, where the band is wide,
// past the edges of small triangles.
TEST(Triangle4, NearLanesAreExactlyTheScalarTestsBand) {
    std::mt19937 rng(43);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int near = 0, mismatches = 0;
    for (int round = 0; round < 500; ++round) {
        Vec3 corners[4][3];
        for (auto& tri : corners) {
            const Vec3 c{unit(rng), unit(rng), unit(rng)};
            for (Vec3& p : tri) p = c + 1e-3f * Vec3{unit(rng), unit(rng), unit(rng)};
        }
        const TriangleBlock block = make_block(corners);
        for (int r = 0; r < 20; ++r) {
            const Vec3 o = 50.0f * Vec3{unit(rng), unit(rng), unit(rng)};
            const auto& tri = corners[r % 4];
            const float w = (unit(rng) + 1.0f) / 2.0f;
            const Vec3 d = (1 - w) * tri[0] + w * tri[1] - o;  // at an edge
            const float tmax = r % 5 == 0 ? 0.9f : INFINITY;
            BlockHits found;
            intersect_block(block, make_ray_lanes(o, d), tmax, tmax, found);
            for (int lane = 0; lane < 4; ++lane) {
                const bool lane_near = (found.near >> lane) & 1;
                near += lane_near;
                mismatches += lane_near != scalar_redecides(corners[lane], o, d, tmax);
            }
        }
    }
    EXPECT_EQ(mismatches, 0);
    EXPECT_GT(near, 1000);
}

// A lane near an edge whose t lies beyond near_limit is not handed over;
// with the limit beyond its t, it is.
TEST(Triangle4, NearLanesBeyondTheLimitAreDropped) {
    Vec3 corners[4][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                          {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                          {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                          {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
    const TriangleBlock block = make_block(corners);
    std::mt19937 rng(44);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int near_rays = 0;
    for (int r = 0; r < 2000; ++r) {
        const float s = unit(rng);
        const Vec3 o{unit(rng) * 3 - 1, unit(rng) * 3 - 1, 1 + unit(rng)};
        const Vec3 d = Vec3{s, s, 0} - o;  // at the shared diagonal, t ≈ 1
        BlockHits found;
        intersect_block(block, make_ray_lanes(o, d), INFINITY, INFINITY, found);
        if (found.near == 0) continue;
        ++near_rays;
        const int near = found.near;
        intersect_block(block, make_ray_lanes(o, d), INFINITY, 1.01f, found);
        EXPECT_EQ(found.near, near);
        intersect_block(block, make_ray_lanes(o, d), INFINITY, 0.99f, found);
        EXPECT_EQ(found.near, 0);
    }
    EXPECT_GT(near_rays, 100);
}

// Empty lanes (all zero) never hit, whatever the ray.
TEST(Triangle4, EmptyLanesNeverHit) {
    const TriangleBlock block{};
    BlockHits found;
    for (const Vec3 d : {Vec3{0, 0, 1}, Vec3{1, -2, 3}, Vec3{0, 0, -0.0f}}) {
        intersect_block(block, make_ray_lanes({0, 0, -1}, d), INFINITY, INFINITY, found);
        EXPECT_EQ(found.sure, 0);
        EXPECT_EQ(found.near, 0);
    }
}

}  // namespace
}  // namespace sombra
