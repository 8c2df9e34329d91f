// Spherical rectangle sampling: the solid angle against the two spherical
// triangles that make up the rectangle, and the samples uniform over it by a
// χ² test whose cells are sub-rectangles with exactly known probabilities
// (their own solid angles).
#include "render/lights/spherical_rectangle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "render/chi2_test_util.h"
#include "render/lights/spherical_triangle.h"
#include "render/sampler.h"

namespace sombra {
namespace {

double two_triangles_solid_angle(Vec3 x, Vec3 corner, Vec3 e1, Vec3 e2) {
    return make_spherical_triangle(x, corner, corner + e1, corner + e1 + e2).solid_angle +
           make_spherical_triangle(x, corner, corner + e1 + e2, corner + e2).solid_angle;
}

TEST(SphericalRectangle, SolidAngleOfACubeFaceSeenFromItsCentreIsTwoThirdsPi) {
    // Six faces share the sphere's 4π.
    const SphericalRectangle r = make_spherical_rectangle({0, 0, 0}, {-1, -1, 1}, {2, 0, 0}, {0, 2, 0});
    EXPECT_NEAR(r.solid_angle, 4 * std::numbers::pi / 6, 1e-12);
}

TEST(SphericalRectangle, SolidAngleIsTheSumOfItsTwoTriangles) {
    const Vec3 xs[] = {{0.3f, 0.2f, 2}, {3, -1, 0.5f}, {-0.2f, 0.1f, -0.7f}, {0.5f, 0.5f, 1e-3f}};
    for (const Vec3 x : xs) {
        const Vec3 corner{0, 0, 0}, e1{1.5f, 0, 0}, e2{0, 1, 0};
        const double expected = two_triangles_solid_angle(x, corner, e1, e2);
        EXPECT_NEAR(make_spherical_rectangle(x, corner, e1, e2).solid_angle, expected, 1e-9 + 1e-7 * expected)
            << x.x << " " << x.y << " " << x.z;
    }
}

TEST(SphericalRectangle, SeenEdgeOnOrDegenerateItHasNoSolidAngle) {
    EXPECT_EQ(make_spherical_rectangle({3, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}).solid_angle, 0.0);
    EXPECT_EQ(make_spherical_rectangle({0, 0, 1}, {0, 0, 0}, {0, 0, 0}, {0, 1, 0}).solid_angle, 0.0);
}

// χ² over the n × n cells (sub-rectangles) of the rectangle.
double uniformity_p_value(Vec3 x, Vec3 corner, Vec3 e1, Vec3 e2, int samples, std::uint64_t seed) {
    const int n = 8;
    const SphericalRectangle r = make_spherical_rectangle(x, corner, e1, e2);
    EXPECT_GT(r.solid_angle, 0.0);
    std::vector<double> expected(n * n, 0.0), observed(n * n, 0.0);
    const float step = 1.0f / n;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const Vec3 cell = corner + (static_cast<float>(i) * step) * e1 + (static_cast<float>(j) * step) * e2;
            expected[i * n + j] = two_triangles_solid_angle(x, cell, step * e1, step * e2) / r.solid_angle * samples;
        }
    for (int k = 0; k < samples; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        const Vec3 y = sample_spherical_rectangle(r, hash_to_unit(i, seed), hash_to_unit(i, seed ^ 0xabcdefull));
        const double s = dot(y - corner, e1) / dot(e1, e1), t = dot(y - corner, e2) / dot(e2, e2);
        // On the rectangle: in its plane and inside its edges.
        const Vec3 normal = normalize(cross(e1, e2));
        EXPECT_NEAR(dot(y - corner, normal), 0.0f, 1e-4f * (1.0f + length(y - corner)));
        EXPECT_GT(s, -1e-5);
        EXPECT_LT(s, 1 + 1e-5);
        EXPECT_GT(t, -1e-5);
        EXPECT_LT(t, 1 + 1e-5);
        const int a = std::clamp(static_cast<int>(s * n), 0, n - 1), b = std::clamp(static_cast<int>(t * n), 0, n - 1);
        observed[a * n + b] += 1;
    }
    return chi2::pearson(observed, expected).p_value;
}

TEST(SphericalRectangle, SamplesAreUniformOverTheSolidAngle) {
    struct Case {
        Vec3 x, corner, e1, e2;
    };
    const Case cases[] = {
        {{0.5f, 0.5f, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},               // above its centre
        {{0.1f, 0.9f, 0.2f}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},            // near a corner, close
        {{2.5f, -1, 0.3f}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},              // beside it, nearly in its plane
        {{0.3f, 0.4f, -0.8f}, {0, 0, 0}, {0, 1, 0}, {1, 0, 0}},           // from the other side
        {{1, 2, 3}, {-0.5f, 0.2f, 0.1f}, {0.6f, 0, 0.8f}, {0, 2.5f, 0}},  // tilted, long
        {{0, 0, 0}, {4, 0.2f, -0.3f}, {0, 0.3f, 0}, {0, 0, 0.2f}},        // small and far
        {{0.5f, 0.5f, 0.01f}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}},           // almost on it (near 2π sr)
    };
    const double significance = 1e-3 / std::size(cases);
    std::uint64_t seed = 1;
    for (const Case& c : cases) {
        const double p = uniformity_p_value(c.x, c.corner, c.e1, c.e2, 100000, seed++);
        EXPECT_GT(p, significance) << "case " << seed - 1;
    }
}

}  // namespace
}  // namespace sombra
