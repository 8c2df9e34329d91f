// Light selection and sampling: each light is chosen in proportion to its
// power, and the density sample_light reports is the one pdf_light_* gives
// for the same point (MIS relies on the two agreeing).
#include "render/lights.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "render/sampler.h"

namespace sombra {
namespace {

void add_triangle(Scene& scene, Vec3 a, Vec3 b, Vec3 c, std::uint32_t material) {
    TriangleMesh& mesh = scene.geometry;
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.material_ids.push_back(material);
}

Scene two_emitters_and_a_floor() {
    Scene scene;
    Material floor;
    floor.kd = Vec3{0.5f};
    Material bright, dim;
    bright.kd = dim.kd = Vec3{0.0f};
    bright.ke = Vec3{10.0f};
    dim.ke = Vec3{1.0f, 2.0f, 3.0f};
    dim.emits_front_only = true;
    scene.materials = {floor, bright, dim};
    add_triangle(scene, {-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, 0);
    add_triangle(scene, {-1, 2, -1}, {1, 2, -1}, {0, 2.5f, 1}, 1);   // near: sampled by solid angle
    add_triangle(scene, {5, 40, 5}, {5.5f, 40, 5}, {5, 40, 5.5f}, 2);  // far and small: by area; emits toward −y
    return scene;
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

TEST(Lights, SampledDensityEqualsTheDensityOfTheSampledPoint) {
    const Scene scene = two_emitters_and_a_floor();
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.2f}), true);
    const Vec3 x{0.3f, 0.0f, -0.2f};
    int counts[3] = {0, 0, 0};
    const int n = 20000;
    for (int k = 0; k < n; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        LightSample ls;
        if (!sample_light(lights, scene, x, Vec3{0, 1, 0}, hash_to_unit(i, 1), hash_to_unit(i, 2), hash_to_unit(i, 3), ls)) continue;
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
        EXPECT_NEAR(ls.pdf, pdf_light_triangle(lights, scene, triangle, x, Vec3{0, 1, 0}, ls.target), 1e-3f * ls.pdf);
        EXPECT_EQ(ls.radiance, scene.materials[bright ? 1 : 2].ke);
    }
    // How often each light is chosen: binomial, |z| < 5.
    for (int l = 0; l < 3; ++l) {
        const double p = lights.choice_probability[static_cast<std::size_t>(l)];
        EXPECT_LT(std::fabs(counts[l] - n * p), 5 * std::sqrt(n * p * (1 - p)) + 1) << "light " << l;
    }
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
        if (!sample_light(lights, scene, above, Vec3{0.0f}, hash_to_unit(i, 4), hash_to_unit(i, 5), hash_to_unit(i, 6), ls))
            continue;
        EXPECT_LT(ls.target.y, 10.0f);  // only the bright, two-sided one
        ++sampled;
    }
    EXPECT_GT(sampled, 0);
}

TEST(Lights, NoSampledLightsWithoutEmittersOrEnvironment) {
    Scene scene;
    scene.materials.push_back(Material{});
    add_triangle(scene, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true);
    EXPECT_FALSE(lights.has_sampled_lights());
    LightSample ls;
    EXPECT_FALSE(sample_light(lights, scene, {0, 0, 1}, Vec3{0.0f}, 0.5f, 0.5f, 0.5f, ls));
    // Under direct the background is only seen, never sampled.
    const LightSet direct = make_light_set(scene, make_constant_environment(Vec3{1.0f}), false);
    EXPECT_FALSE(direct.has_sampled_lights());
}

}  // namespace
}  // namespace sombra
