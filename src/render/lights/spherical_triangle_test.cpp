// Spherical triangle sampling: the solid angle against closed forms, and the
// samples uniform over it by a χ² test whose cells are the triangle's own
// sub-triangles, whose probabilities are known exactly (their solid angles).
#include "render/lights/spherical_triangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "render/chi2_test_util.h"
#include "render/sampler.h"

namespace sombra {
namespace {

Vec3 lerp3(Vec3 p0, Vec3 p1, Vec3 p2, double b1, double b2) {
    return static_cast<float>(1.0 - b1 - b2) * p0 + static_cast<float>(b1) * p1 + static_cast<float>(b2) * p2;
}

TEST(SphericalTriangle, SolidAngleOfAnOctantIsHalfPi) {
    const SphericalTriangle t = make_spherical_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
    EXPECT_NEAR(t.solid_angle, std::numbers::pi / 2, 1e-12);
    EXPECT_NEAR(t.alpha, std::numbers::pi / 2, 1e-12);
}

TEST(SphericalTriangle, SmallTriangleSolidAngleIsAreaTimesCosOverDistanceSquared) {
    const float h = 1e-3f;
    const SphericalTriangle t = make_spherical_triangle({0, 0, 0}, {0, 0, 10}, {h, 0, 10}, {0, h, 10});
    EXPECT_NEAR(t.solid_angle, 0.5 * h * h / 100.0, 1e-6 * 0.5 * h * h / 100.0);
}

TEST(SphericalTriangle, DegenerateOrEdgeOnHasNoSolidAngle) {
    EXPECT_EQ(make_spherical_triangle({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}).solid_angle, 0.0);
    EXPECT_EQ(make_spherical_triangle({0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}).solid_angle, 0.0);
}

// χ² over the n² cells of the triangle's n-fold midpoint subdivision.
double uniformity_p_value(Vec3 x, Vec3 p0, Vec3 p1, Vec3 p2, int samples, std::uint64_t seed) {
    const int n = 8;
    const SphericalTriangle t = make_spherical_triangle(x, p0, p1, p2);
    EXPECT_GT(t.solid_angle, 0.0);
    std::vector<double> expected(2 * n * n, 0.0), observed(2 * n * n, 0.0);
    // Cell (i, j, up/down) in barycentric steps of 1/n.
    for (int i = 0; i < n; ++i)
        for (int j = 0; i + j < n; ++j) {
            const double b1 = double(i) / n, b2 = double(j) / n, s = 1.0 / n;
            const Vec3 a = lerp3(p0, p1, p2, b1, b2), b = lerp3(p0, p1, p2, b1 + s, b2),
                       c = lerp3(p0, p1, p2, b1, b2 + s);
            expected[2 * (i * n + j)] = make_spherical_triangle(x, a, b, c).solid_angle / t.solid_angle * samples;
            if (i + j + 1 < n) {
                const Vec3 d = lerp3(p0, p1, p2, b1 + s, b2 + s);
                expected[2 * (i * n + j) + 1] =
                    make_spherical_triangle(x, b, d, c).solid_angle / t.solid_angle * samples;
            }
        }
    const Vec3 e1 = p1 - p0, e2 = p2 - p0, normal = cross(e1, e2);
    for (int k = 0; k < samples; ++k) {
        const Vec3 d = sample_spherical_triangle(t, hash_to_unit(static_cast<std::uint32_t>(k), seed),
                                                 hash_to_unit(static_cast<std::uint32_t>(k), seed ^ 0xabcdefull));
        // Where d meets the plane, in barycentric coordinates (double).
        const double tt = double(dot(p0 - x, normal)) / double(dot(d, normal));
        const double hx = x.x + tt * d.x - p0.x, hy = x.y + tt * d.y - p0.y, hz = x.z + tt * d.z - p0.z;
        const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
        const double h1 = hx * e1.x + hy * e1.y + hz * e1.z, h2 = hx * e2.x + hy * e2.y + hz * e2.z;
        const double det = d11 * d22 - d12 * d12;
        const double b1 = (d22 * h1 - d12 * h2) / det, b2 = (d11 * h2 - d12 * h1) / det;
        EXPECT_GT(tt, 0.0);
        EXPECT_GT(b1, -1e-4);
        EXPECT_GT(b2, -1e-4);
        EXPECT_LT(b1 + b2, 1 + 1e-4);
        const double f1 = std::clamp(b1 * n, 0.0, n - 1e-9), f2 = std::clamp(b2 * n, 0.0, n - 1e-9);
        int i = static_cast<int>(f1), j = static_cast<int>(f2);
        bool down = (f1 - i) + (f2 - j) > 1.0;
        if (i + j >= n) {  // rounding past the hypotenuse: the last up cell
            j = n - 1 - i;
            down = false;
        }
        observed[2 * (i * n + j) + (down ? 1 : 0)] += 1;
    }
    // Slots for cells outside the triangle expect 0 and must stay empty.
    return chi2::pearson(observed, expected).p_value;
}

TEST(SphericalTriangle, SamplesAreUniformOverTheSolidAngle) {
    struct Case {
        Vec3 x, p0, p1, p2;
    };
    const Case cases[] = {
        {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},                 // an octant
        {{0.1f, 0.2f, 0}, {-1, -1, 2}, {1.5f, -0.5f, 2}, {0, 1, 2}},  // ahead, large
        {{0, 0, 0}, {5, 0.2f, 1}, {5, 0.3f, 1.2f}, {5.1f, 0.9f, 1}},  // small and thin
        {{0, 0.01f, 0}, {-1, 0, -1}, {1, 0, -1}, {0, 0, 1}},          // almost on its plane
        {{3, 2, 1}, {0, 0, 0}, {0.2f, 0, 0}, {0, 0, 4}},              // long sliver, oblique
    };
    const double significance = 1e-3 / std::size(cases);
    std::uint64_t seed = 1;
    for (const Case& c : cases) {
        const double p = uniformity_p_value(c.x, c.p0, c.p1, c.p2, 100000, seed++);
        EXPECT_GT(p, significance) << "case " << seed - 1;
    }
}

}  // namespace
}  // namespace sombra
