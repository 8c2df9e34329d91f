// Quad lights sampled as one rectangle (EmitterRectangle): which pairs of
// emitting triangles are rectangles, the density sample_light reports
// against pdf_light_triangle for the triangle its point falls in, and the
// points uniform over the rectangle's solid angle near it and over its area
// far from it (χ² over sub-rectangles whose probabilities are known).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "render/chi2_test_util.h"
#include "render/lights/emitter_sampling.h"
#include "render/lights/lights.h"
#include "render/lights/spherical_triangle.h"
#include "render/sampler.h"
#include "render/test_meshes.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

using testing::add_quad;
using testing::add_triangle;

// The rectangle [−1, 1] × [−0.5, 0.5] at y = 2, shining down, as a quad
// light's two triangles (0: below the diagonal z = x/2, 1: above it); a
// parallelogram that is no rectangle (2, 3); a rectangle whose halves have
// different materials (4, 5); a floor (6).
Scene rectangle_and_others(bool others_emit) {
    Material light, floor;
    light.kd = Vec3{0.0f};
    light.ke = Vec3{5.0f, 4.0f, 3.0f};
    light.emits_front_only = true;
    floor.kd = Vec3{0.5f};
    Material other = light;
    if (!others_emit) other.ke = Vec3{0.0f};
    TriangleMesh mesh;
    add_quad(mesh, {-1, 2, -0.5f}, {1, 2, -0.5f}, {1, 2, 0.5f}, {-1, 2, 0.5f}, 0);
    add_quad(mesh, {3, 2, 0}, {4, 2, 0}, {4.5f, 2, 1}, {3.5f, 2, 1}, 1);
    add_triangle(mesh, {6, 2, 0}, {7, 2, 0}, {7, 2, 1}, 1);
    add_triangle(mesh, {6, 2, 0}, {7, 2, 1}, {6, 2, 1}, 2);
    add_triangle(mesh, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, 3);
    Material other_too = other;
    other_too.name = "another material";
    SceneBuilder b;
    testing::add_world_mesh(b, mesh, {light, other, other_too, floor});
    return b.finish();
}

TEST(RectangleLights, OnlyRectanglesOfOneMaterialArePaired) {
    const Scene scene = rectangle_and_others(true);
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    ASSERT_EQ(lights.emitters.size(), 6u);
    ASSERT_EQ(lights.rectangles.size(), 1u);
    const EmitterRectangle& r = lights.rectangles[0];
    EXPECT_EQ(r.near, 0u);
    EXPECT_EQ(r.far, 1u);
    EXPECT_NEAR(r.area, 2.0f, 1e-6f);
    EXPECT_NEAR(r.unit_normal.y, -1.0f, 1e-6f);
    EXPECT_NEAR(std::fabs(dot(r.edge1, r.edge2)), 0.0f, 1e-6f);
    const std::vector<std::uint32_t> expected{0, 0, kNoRectangle, kNoRectangle, kNoRectangle, kNoRectangle};
    EXPECT_EQ(lights.emitter_rectangle, expected);
}

TEST(RectangleLights, TheDensityOfASampleIsThatOfTheTriangleItFallsIn) {
    // Shading points from 0.02 to 30 units below the light, under it and
    // beside it, so that both its solid-angle and its area sampling are
    // used; with power selection and with the light tree (which weighs the
    // two triangles differently from each point).
    const Scene scene = rectangle_and_others(true);
    for (const LightSelection selection : {LightSelection::Power, LightSelection::Tree}) {
        const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, selection);
        int checked = 0, in_each[2] = {0, 0};
        for (int step = 0; step < 600; ++step) {
            const auto i = static_cast<std::uint32_t>(step);
            const float depth = 0.02f * std::pow(1500.0f, static_cast<float>(step % 30) / 29.0f);
            const int column = step / 30;
            const float aside = static_cast<float>(column) * 0.2f - 1.5f;
            const Vec3 x{aside, 2.0f - depth, 0.1f};
            LightSample ls;
            if (!sample_light(lights, scene, x, Vec3{0, 1, 0}, hash_to_unit(i, 1), hash_to_unit(i, 2),
                              hash_to_unit(i, 3), ls))
                continue;
            if (ls.triangle > 1) continue;  // another light
            ++checked;
            // The triangle it reports is the one the point lies in.
            const float above_diagonal = ls.target.z - 0.5f * ls.target.x;
            if (ls.triangle == 0)
                EXPECT_LE(above_diagonal, 1e-5f);
            else
                EXPECT_GE(above_diagonal, -1e-5f);
            ++in_each[ls.triangle];
            EXPECT_EQ(ls.light, emitter_light(lights, ls.triangle));
            EXPECT_EQ(ls.radiance, Vec3(5.0f, 4.0f, 3.0f));
            const float pdf = pdf_light_triangle(lights, scene, ls.triangle, kNoInstance, x, Vec3{0, 1, 0}, ls.target);
            EXPECT_NEAR(ls.pdf, pdf, 1e-3f * ls.pdf) << "x = " << x.x << " " << x.y << " " << x.z;
        }
        EXPECT_GT(checked, 150);
        EXPECT_GT(in_each[0], 30);
        EXPECT_GT(in_each[1], 30);
    }
}

// χ² of sample_light's points over the light's 8 × 8 sub-rectangles, each
// expected with probability `cell_probability(corner, e1, e2)`.
template <class CellProbability>
double cells_p_value(const Scene& scene, const LightSet& lights, Vec3 x, std::uint64_t seed,
                     CellProbability cell_probability) {
    const int n = 8, samples = 64000;
    const Vec3 corner{-1, 2, -0.5f}, e1{2.0f / n, 0, 0}, e2{0, 0, 1.0f / n};
    std::vector<double> expected(n * n), observed(n * n, 0.0);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            expected[a * n + b] =
                samples * cell_probability(corner + static_cast<float>(a) * e1 + static_cast<float>(b) * e2, e1, e2);
    for (int k = 0; k < samples; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        LightSample ls;
        EXPECT_TRUE(sample_light(lights, scene, x, Vec3{0, 1, 0}, hash_to_unit(i, seed), hash_to_unit(i, seed + 1),
                                 hash_to_unit(i, seed + 2), ls));
        const int a = std::clamp(static_cast<int>((ls.target.x + 1.0f) / e1.x), 0, n - 1);
        const int b = std::clamp(static_cast<int>((ls.target.z + 0.5f) / e2.z), 0, n - 1);
        observed[a * n + b] += 1;
    }
    return chi2::pearson(observed, expected).p_value;
}

TEST(RectangleLights, NearPointsSampleItsSolidAngleAndFarOnesItsArea) {
    const Scene scene = rectangle_and_others(false);
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    ASSERT_EQ(lights.emitters.size(), 2u);
    auto solid_angle = [](Vec3 x, Vec3 p, Vec3 e1, Vec3 e2) {
        return make_spherical_triangle(x, p, p + e1, p + e1 + e2).solid_angle +
               make_spherical_triangle(x, p, p + e1 + e2, p + e2).solid_angle;
    };
    // 0.2 below the light, off centre: the farthest corner is 7 times as far as the nearest point.
    const Vec3 near{0.3f, 1.8f, 0.1f};
    const double omega = solid_angle(near, {-1, 2, -0.5f}, {2, 0, 0}, {0, 0, 1});
    EXPECT_GT(cells_p_value(scene, lights, near, 10,
                            [&](Vec3 p, Vec3 e1, Vec3 e2) { return solid_angle(near, p, e1, e2) / omega; }),
              1e-3);
    // 30 below: every point of it nearly as far; uniform by area.
    EXPECT_GT(cells_p_value(scene, lights, {0.2f, -28, 0}, 20, [](Vec3, Vec3, Vec3) { return 1.0 / 64; }), 1e-3);
}

TEST(RectangleLights, TheReachShortcutChangesNoDensity) {
    // solid_angle_pays turns away points farther from the centre than
    // solid_angle_reach2 before its full test; the density must be the one
    // the full test alone gives, for points around that reach, near and far.
    const std::array<Vec3, 3> shapes[][2] = {
        {{{{0, 0, 0}, {1, 0, 0}, {1, 0, 1}}}, {{{0, 0, 0}, {1, 0, 1}, {0, 0, 1}}}},              // a unit square
        {{{{0, 0, 0}, {10, 0, 0}, {10, 0.1f, 0}}}, {{{0, 0, 0}, {10, 0.1f, 0}, {0, 0.1f, 0}}}},  // long and thin
        {{{{0, 0, 0}, {1, 1, 0}, {1, 1, 2}}}, {{{0, 0, 0}, {1, 1, 2}, {0, 0, 2}}}},              // tilted
    };
    int by_solid_angle = 0;
    for (const auto& shape : shapes) {
        EmitterRectangle r;
        ASSERT_TRUE(find_rectangle(shape[0], shape[1], r));
        EmitterRectangle without_shortcut = r;
        without_shortcut.solid_angle_reach2 = std::numeric_limits<float>::infinity();
        const float reach = std::sqrt(r.solid_angle_reach2);
        for (std::uint32_t i = 0; i < 4000; ++i) {
            const float z = 1.0f - 2.0f * hash_to_unit(i, 1), phi = 6.2831853f * hash_to_unit(i, 2);
            const float rho = std::sqrt(std::max(0.0f, 1.0f - z * z));
            const Vec3 x =
                r.centre + 1.3f * reach * hash_to_unit(i, 3) * Vec3{rho * std::cos(phi), rho * std::sin(phi), z};
            const Vec3 y1 = r.corner + 0.2f * r.edge1 + 0.7f * r.edge2, y2 = r.corner + 0.9f * r.edge1 + 0.1f * r.edge2;
            const float full1 = pdf_emitter_rectangle(without_shortcut, x, y1);
            const float full2 = pdf_emitter_rectangle(without_shortcut, x, y2);
            EXPECT_EQ(pdf_emitter_rectangle(r, x, y1), full1) << i;
            EXPECT_EQ(pdf_emitter_rectangle(r, x, y2), full2) << i;
            if (full1 == full2 && full1 > 0.0f) ++by_solid_angle;  // uniform over the solid angle
        }
    }
    EXPECT_GT(by_solid_angle, 100);  // the points exercise both ways of sampling
}

}  // namespace
}  // namespace sombra
