// Light selection and sampling: each light is chosen in proportion to its
// power, and the density sample_light reports is the one pdf_light_* gives
// for the same point (MIS relies on the two agreeing).
#include "render/lights/lights.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "render/chi2_test_util.h"
#include "render/sampler.h"
#include "render/test_meshes.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

using testing::add_triangle;

Scene two_emitters_and_a_floor() {
    Material floor;
    floor.kd = Vec3{0.5f};
    Material bright, dim;
    bright.kd = dim.kd = Vec3{0.0f};
    bright.ke = Vec3{10.0f};
    dim.ke = Vec3{1.0f, 2.0f, 3.0f};
    dim.emits_front_only = true;
    TriangleMesh mesh;
    add_triangle(mesh, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, 0);
    add_triangle(mesh, {-1, 2, -1}, {1, 2, -1}, {0, 2.5f, 1}, 1);     // near: sampled by solid angle
    add_triangle(mesh, {5, 40, 5}, {5.5f, 40, 5}, {5, 40, 5.5f}, 2);  // far and small: by area; emits toward −y
    SceneBuilder b;
    testing::add_world_mesh(b, mesh, {floor, bright, dim});
    return b.finish();
}

TEST(Lights, EmittersArePickedInProportionToPower) {
    const Scene scene = two_emitters_and_a_floor();
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.2f}), true);
    ASSERT_EQ(lights.emitters.size(), 2u);
    ASSERT_EQ(lights.choice_probability.size(), 3u);
    // Power: luminance(ke) · area · π · sides.
    const double p_bright = 10.0 * lights.emitter_areas[0] * std::numbers::pi * 2;
    const double p_dim = luminance(Vec3{1, 2, 3}) * lights.emitter_areas[1] * std::numbers::pi;
    EXPECT_NEAR(lights.choice_probability[0] / lights.choice_probability[1], p_bright / p_dim, 1e-3 * p_bright / p_dim);
    double sum = 0;
    for (float p : lights.choice_probability) sum += p;
    EXPECT_NEAR(sum, 1.0, 1e-6);
}

TEST(Lights, AConstantEnvironmentBesideEmittersIsChosenOnceInAHundred) {
    // A constant environment is left to BSDF sampling (its exact density on
    // a diffuse surface) but keeps a 1 % share of the light samples, so that
    // both strategies still count it; alone, it takes them all. A map keeps
    // its share of the power.
    const Scene scene = two_emitters_and_a_floor();
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.2f}), true);
    ASSERT_EQ(lights.choice_probability.size(), 3u);
    EXPECT_NEAR(lights.choice_probability.back(), 0.01, 1e-6);
    EXPECT_NEAR(lights.choice_probability[0] + lights.choice_probability[1], 0.99, 1e-6);

    TriangleMesh floor_only;
    add_triangle(floor_only, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, floor_only, {Material{}});
    const LightSet alone = make_light_set(b.finish(), make_constant_environment(Vec3{0.2f}), true);
    ASSERT_EQ(alone.choice_probability.size(), 1u);
    EXPECT_EQ(alone.choice_probability[0], 1.0f);

    HdrImage grey{2, 1, std::vector<float>(6, 0.2f)};
    const LightSet mapped = make_light_set(scene, make_map_environment(grey, 1.0f, 0.0f), true);
    const float r = 0.5f * length(Vec3{20.0f, 40.0f, 20.0f});  // the scene's bounding radius
    const double p_env = 4 * std::numbers::pi * 0.2 * std::numbers::pi * r * r;
    const double p_bright = 10.0 * mapped.emitter_areas[0] * std::numbers::pi * 2;
    EXPECT_NEAR(mapped.choice_probability.back() / mapped.choice_probability[0], p_env / p_bright,
                1e-3 * p_env / p_bright);
}

TEST(Lights, SampledDensityEqualsTheDensityOfTheSampledPoint) {
    const Scene scene = two_emitters_and_a_floor();
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.2f}), true);
    const Vec3 x{0.3f, 0.0f, -0.2f};
    int counts[3] = {0, 0, 0};
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        LightSample ls;
        if (!sample_light(lights, scene, x, Vec3{0, 1, 0}, hash_to_unit(i, 1), hash_to_unit(i, 2), hash_to_unit(i, 3),
                          ls))
            continue;
        ASSERT_TRUE(std::isfinite(ls.pdf));
        ASSERT_GT(ls.pdf, 0.0f);
        EXPECT_NEAR(length(ls.wi), 1.0f, 1e-5f);
        if (ls.at_infinity) {
            ++counts[2];
            EXPECT_FLOAT_EQ(ls.pdf, pdf_light_environment(lights, ls.wi));
            continue;
        }
        const bool bright = ls.target.y < 10;
        ++counts[bright ? 0 : 1];
        const std::uint32_t triangle = bright ? 1 : 2;
        EXPECT_NEAR(ls.pdf, pdf_light_triangle(lights, scene, triangle, kNoInstance, x, Vec3{0, 1, 0}, ls.target),
                    1e-3f * ls.pdf);
        EXPECT_EQ(ls.radiance, scene.materials[bright ? 1 : 2].ke);
    }
    // How often each light is chosen: binomial, |z| < 5.
    for (int l = 0; l < 3; ++l) {
        const double p = lights.choice_probability[static_cast<std::size_t>(l)];
        EXPECT_LT(std::fabs(counts[l] - n * p), 5 * std::sqrt(n * p * (1 - p)) + 1) << "light " << l;
    }
}

TEST(Lights, SamplingAndDensityAgreeOnBothSidesOfTheStrategyChoice) {
    // Shading points from 0.05 to 20 units away from a triangle light, above
    // it and beside it: the near ones see it by solid angle, the far ones by
    // area, and some near the choice's threshold. Wherever x is, the density a
    // sample reports must be the one pdf_light_triangle gives for its point.
    Scene scene = two_emitters_and_a_floor();
    scene.materials[2].ke = Vec3{0.0f};  // only the near light remains
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    ASSERT_EQ(lights.emitters.size(), 1u);
    int checked = 0;
    for (int step = 0; step < 400; ++step) {
        const auto i = static_cast<std::uint32_t>(step);
        const float distance = 0.05f * std::pow(400.0f, static_cast<float>(step % 40) / 39.0f);
        const int row = step / 40;
        const float angle = static_cast<float>(row) * 0.15f;  // from straight below to nearly in plane
        const Vec3 x{distance * std::sin(angle), 2.0f - distance * std::cos(angle), 0.1f};
        LightSample ls;
        if (!sample_light(lights, scene, x, Vec3{0, 1, 0}, hash_to_unit(i, 4), hash_to_unit(i, 5), hash_to_unit(i, 6),
                          ls))
            continue;
        ++checked;
        const float pdf = pdf_light_triangle(lights, scene, 1, kNoInstance, x, Vec3{0, 1, 0}, ls.target);
        EXPECT_NEAR(ls.pdf, pdf, 1e-3f * ls.pdf) << "x = " << x.x << " " << x.y << " " << x.z;
    }
    EXPECT_GT(checked, 300);
}

TEST(Lights, SmallDistantTrianglesAreSampledUniformlyByArea) {
    // Seen from the floor, the far light subtends well under 1e-3 sr, so it
    // is sampled by area: every cell of its 4-fold midpoint subdivision
    // (16 equal-area triangles) gets 1/16 of the samples (χ², 15 dof).
    Scene scene = two_emitters_and_a_floor();
    scene.materials[1].ke = Vec3{0.0f};  // only the far light remains
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    ASSERT_EQ(lights.emitters.size(), 1u);
    const Vec3 p0{5, 40, 5}, p1{5.5f, 40, 5}, p2{5, 40, 5.5f};
    const int n = 4, samples = 32000;
    std::vector<double> observed(static_cast<std::size_t>(n * n), 0.0);
    for (int k = 0; k < samples; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        LightSample ls;
        ASSERT_TRUE(sample_light(lights, scene, {0, 0, 0}, Vec3{0, 1, 0}, hash_to_unit(i, 7), hash_to_unit(i, 8),
                                 hash_to_unit(i, 9), ls));
        // Barycentrics of the target in the right-angled triangle.
        const double b1 = (ls.target.x - p0.x) / (p1.x - p0.x), b2 = (ls.target.z - p0.z) / (p2.z - p0.z);
        ASSERT_GE(b1, -1e-4);
        ASSERT_GE(b2, -1e-4);
        ASSERT_LE(b1 + b2, 1 + 1e-4);
        const double f1 = std::clamp(b1 * n, 0.0, n - 1e-9), f2 = std::clamp(b2 * n, 0.0, n - 1e-9);
        int a = static_cast<int>(f1), b = static_cast<int>(f2);
        bool down = (f1 - a) + (f2 - b) > 1.0;
        if (a + b >= n) b = n - 1 - a;
        if (a + b + 1 >= n) down = false;  // rounding past the hypotenuse: the last up cell
        // Up cells (a, b) with a + b < n number n(n+1)/2, down cells n(n−1)/2.
        const int index = down ? n * (n + 1) / 2 + a * (n - 1) - a * (a - 1) / 2 + b : a * n - a * (a - 1) / 2 + b;
        observed[static_cast<std::size_t>(index)] += 1;
    }
    const std::vector<double> expected(observed.size(), static_cast<double>(samples) / (n * n));
    const chi2::Pearson test = chi2::pearson(observed, expected);
    EXPECT_EQ(test.dof, n * n - 1);
    EXPECT_GT(test.p_value, 1e-3) << "chi2 " << test.chi2;
}

TEST(Lights, OneSidedEmittersAreDarkFromBehind) {
    const Scene scene = two_emitters_and_a_floor();
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true);
    // Above the dim light (which emits toward −y) nothing of it can be sampled.
    const Vec3 above{5.1f, 50, 5.1f};
    int sampled = 0;
    for (int k = 0; k < 2000; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        LightSample ls;
        if (!sample_light(lights, scene, above, Vec3{0.0f}, hash_to_unit(i, 4), hash_to_unit(i, 5), hash_to_unit(i, 6),
                          ls))
            continue;
        EXPECT_LT(ls.target.y, 10.0f);  // only the bright, two-sided one
        ++sampled;
    }
    EXPECT_GT(sampled, 0);
}

TEST(Lights, NoSampledLightsWithoutEmittersOrEnvironment) {
    TriangleMesh mesh;
    add_triangle(mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, mesh, {Material{}});
    const Scene scene = b.finish();
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true);
    EXPECT_FALSE(lights.has_sampled_lights());
    LightSample ls;
    EXPECT_FALSE(sample_light(lights, scene, {0, 0, 1}, Vec3{0.0f}, 0.5f, 0.5f, 0.5f, ls));
    // Under direct the background is only seen, never sampled.
    const LightSet direct = make_light_set(scene, make_constant_environment(Vec3{1.0f}), false);
    EXPECT_FALSE(direct.has_sampled_lights());
}

TEST(Lights, EveryLightHasOneIdentityInTheSet) {
    // Two delta lights, then the emitters in triangle order (the bright
    // two-sided one is triangle 1, the one-sided "quad" triangle 2), then the
    // environment; sampled lights carry their identity.
    Scene scene = two_emitters_and_a_floor();
    scene.lights = {make_spot_light({0, 3, 0}, {0, -1, 0}, Vec3{1}, 30, 10),
                    make_directional_light({0, -1, 0}, Vec3{1})};
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.2f}), true);
    ASSERT_EQ(lights.light_count(), 5u);
    EXPECT_EQ(lights.first_emitter(), 2u);
    EXPECT_EQ(lights.environment_light(), 4u);
    EXPECT_EQ(light_kind(lights, scene, 0), LightKind::Delta);
    EXPECT_EQ(lights.delta[0].type, LightType::Spot);
    EXPECT_EQ(light_kind(lights, scene, 1), LightKind::Delta);
    EXPECT_EQ(lights.delta[1].type, LightType::Directional);
    EXPECT_EQ(light_kind(lights, scene, 2), LightKind::Triangle);
    EXPECT_EQ(light_kind(lights, scene, 3), LightKind::Quad);
    EXPECT_EQ(light_kind(lights, scene, 4), LightKind::Environment);
    EXPECT_EQ(emitter_light(lights, 0), kNoLight);  // the floor emits nothing
    EXPECT_EQ(emitter_light(lights, 1), 2u);
    EXPECT_EQ(emitter_light(lights, 2), 3u);
    int seen[5] = {};
    for (int k = 0; k < 2000; ++k) {
        LightSample ls;
        const float u = (static_cast<float>(k) + 0.5f) / 2000;
        if (!sample_light(lights, scene, {0, 1, 0}, {0, 1, 0}, u, 0.3f, 0.6f, ls)) continue;
        ASSERT_LT(ls.light, lights.light_count());
        ++seen[ls.light];
        if (ls.at_infinity)
            EXPECT_EQ(ls.light, lights.environment_light());
        else
            EXPECT_EQ(ls.light, emitter_light(lights, ls.triangle));
    }
    EXPECT_EQ(seen[0] + seen[1], 0) << "delta lights are never sampled";
    EXPECT_GT(seen[2], 0);
    EXPECT_GT(seen[4], 0);
}

}  // namespace
}  // namespace sombra
