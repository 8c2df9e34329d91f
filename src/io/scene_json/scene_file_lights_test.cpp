// Lights of scene files (spec §10, §16): spot and directional lights
// and the spot's falloff, and quad lights as two emitting triangles.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

using testing::winding_normal;

class SceneLights : public testing::SceneFileTest {};

TEST_F(SceneLights, SpotAndDirectionalLightsAreRead) {
    const Scene s = load(with_light(R"({"type": "spot", "position": [1, 2, 3], "direction": [0, -2, 0],
        "intensity": [4, 5, 6], "outer_angle": 60, "inner_angle": 30},
        {"type": "spot", "position": [0, 0, 0], "direction": [1, 0, 0], "intensity": [1, 1, 1]},
        {"type": "directional", "direction": [0, 0, -3], "irradiance": [2, 2, 2]},
        {"position": [0, 1, 0], "intensity": [1, 1, 1]})"));
    ASSERT_EQ(s.lights.size(), 4u);
    const PunctualLight& spot = s.lights[0];
    EXPECT_EQ(spot.type, LightType::Spot);
    EXPECT_EQ(spot.position, (Vec3{1, 2, 3}));
    EXPECT_EQ(spot.direction, (Vec3{0, -1, 0}));
    EXPECT_EQ(spot.intensity, (Vec3{4, 5, 6}));
    EXPECT_NEAR(spot.cos_outer, 0.5, 1e-6);
    EXPECT_NEAR(spot.cos_inner, std::sqrt(3.0) / 2, 1e-6);
    // Defaults: outer 45°, inner 0°.
    EXPECT_NEAR(s.lights[1].cos_outer, std::sqrt(0.5), 1e-6);
    EXPECT_EQ(s.lights[1].cos_inner, 1.0f);
    EXPECT_EQ(s.lights[2].type, LightType::Directional);
    EXPECT_EQ(s.lights[2].direction, (Vec3{0, 0, -1}));
    EXPECT_EQ(s.lights[2].intensity, (Vec3{2, 2, 2}));
    EXPECT_EQ(s.lights[3].type, LightType::Point);
}

TEST_F(SceneLights, SpotFalloffFollowsTheSpec) {
    const PunctualLight spot = make_spot_light({0, 0, 0}, {0, 0, -1}, Vec3{1}, 60, 30);
    const float c_out = 0.5f, c_in = std::sqrt(3.0f) / 2;
    EXPECT_EQ(spot_falloff(spot, 1.0f), 1.0f);           // on the axis
    EXPECT_EQ(spot_falloff(spot, c_in + 1e-4f), 1.0f);   // inside the inner cone
    EXPECT_EQ(spot_falloff(spot, c_out - 1e-4f), 0.0f);  // outside the outer cone
    const float mid = 0.5f * (c_in + c_out);
    EXPECT_NEAR(spot_falloff(spot, mid), 0.25f, 1e-5f);  // halfway: s = 1/2, s² = 1/4
    // Equal angles: a hard edge softened over 10⁻³ in cos θ.
    const PunctualLight hard = make_spot_light({0, 0, 0}, {0, 0, -1}, Vec3{1}, 60, 60);
    EXPECT_EQ(spot_falloff(hard, hard.cos_outer + 2e-3f), 1.0f);
    EXPECT_NEAR(spot_falloff(hard, hard.cos_outer + 0.5e-3f), 0.25f, 1e-3f);
    EXPECT_EQ(spot_falloff(hard, hard.cos_outer), 0.0f);
}

TEST_F(SceneLights, QuadLightBecomesTwoFrontEmittingTriangles) {
    const Scene s = load(with_light(
        R"({"type": "quad", "corner": [1, 2, 3], "edge1": [2, 0, 0], "edge2": [0, 0, -1], "radiance": [4, 5, 6]},
           {"position": [0, 3, 0], "intensity": [1, 1, 1]})"));
    ASSERT_EQ(s.lights.size(), 1u);  // the point light
    const TriangleMesh& g = s.geometry;
    ASSERT_EQ(g.triangle_count(), 3u);  // the object's, then the quad's two
    const Vec3 p{1, 2, 3}, a{2, 0, 0}, b{0, 0, -1};
    const Vec3 expected[2][3] = {{p, p + a, p + a + b}, {p, p + a + b, p + b}};
    for (int t = 0; t < 2; ++t)
        for (int c = 0; c < 3; ++c) EXPECT_EQ(g.positions[g.triangles[1 + t][c]], expected[t][c]) << t << c;
    // Both wind toward a × b (here +y), the side that emits.
    for (int t = 1; t < 3; ++t) EXPECT_GT(dot(winding_normal(g, t), cross(a, b)), 0.0f);
    ASSERT_EQ(g.material_ids[1], g.material_ids[2]);
    const Material& m = s.materials.at(g.material_ids[1]);
    EXPECT_EQ(m.type, MaterialType::Diffuse);
    EXPECT_EQ(m.kd, Vec3{0.0f});
    EXPECT_EQ(m.ke, (Vec3{4, 5, 6}));
    EXPECT_TRUE(m.emits_front_only);
    EXPECT_FALSE(g.has_normals());
    EXPECT_FALSE(g.has_uvs());
    EXPECT_TRUE(needs_path_integrator(s));
}

TEST_F(SceneLights, QuadLightsKeepNormalAndUvArraysConsistent) {
    const Scene s = load(scene(
        R"("lights": [{"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [1, 1, 1]},
                      {"type": "quad", "corner": [0, 0, 1], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [2, 2, 2]}])",
        R"([{"file": "normals.obj"}])"));
    const TriangleMesh& g = s.geometry;
    ASSERT_EQ(g.triangle_count(), 5u);
    ASSERT_EQ(g.normal_indices.size(), 5u);
    ASSERT_EQ(g.uv_indices.size(), 5u);
    ASSERT_EQ(g.material_ids.size(), 5u);
    for (std::size_t t = 1; t < 5; ++t) {
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(g.normal_indices[t][c], kNoNormal);
            EXPECT_EQ(g.uv_indices[t][c], kNoUv);
        }
    }
    EXPECT_NE(g.material_ids[1], g.material_ids[3]);  // one material per quad light
    EXPECT_EQ(s.materials.at(g.material_ids[3]).ke, Vec3{2.0f});
}

}  // namespace
}  // namespace sombra
