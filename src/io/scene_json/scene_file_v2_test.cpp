// Scene files, version 2 (spec §10, §11): render.integrator and max_depth,
// mirror, dielectric, conductor and pbr materials, quad lights, environment maps
// (with the clamp_negative extension), and winding under mirroring transforms.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/images/exr_test_file.h"
#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

using testing::write_exr;

class SceneV2 : public testing::SceneFileTest {
protected:
    static void SetUpTestSuite() {
        make_folder("scene_v2_test");
        // Each corner's normal points along its position (all distinct), and a uv per corner.
        write(dir / "normals.obj",
              "v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1 0 0\nvn 0 1 0\nvn 0 0 1\nvt 0 0\nvt 1 0\nvt 0 1\n"
              "f 1/1/1 2/2/2 3/3/3\n");
        write_exr(dir / "sky.exr", 4, 2, std::vector<float>(4 * 2 * 3, 0.5f));
        std::vector<float> ringing(4 * 2 * 3, 0.5f);
        ringing[3 * 5 + 1] = -2.5f;  // pixel (1, 1)
        ringing[3 * 6 + 0] = -0.5f;
        write_exr(dir / "ringing.exr", 4, 2, ringing);
    }
};

constexpr const char* kCamera = R"("camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]})";

// A valid scene with `members` and objects `objects` (default: tri.obj).
std::string scene(const std::string& members, const std::string& objects = R"([{"file": "tri.obj"}])") {
    return "{" + members + (members.empty() ? "" : ", ") + kCamera + ", \"objects\": " + objects + "}";
}
std::string with_material(const std::string& material) {
    return scene(R"("materials": {"m": )" + material + "}", R"([{"file": "tri.obj", "material": "m"}])");
}
std::string with_light(const std::string& light) { return scene(R"("lights": [)" + light + "]"); }
std::string with_environment(const std::string& env, const std::string& more = "") {
    return scene(R"("environment": )" + env + more);
}

Vec3 winding_normal(const TriangleMesh& m, std::size_t t) {
    const Index3& c = m.triangles[t];
    return cross(m.positions[c[1]] - m.positions[c[0]], m.positions[c[2]] - m.positions[c[0]]);
}

TEST_F(SceneV2, RenderIntegratorAndMaxDepth) {
    const RenderSettings path = settings_of(scene(R"("render": {"integrator": "path", "max_depth": 1024})"));
    EXPECT_EQ(path.integrator, IntegratorKind::Path);
    EXPECT_EQ(path.max_depth, 1024);
    const RenderSettings direct = settings_of(scene(R"("render": {"integrator": "direct", "max_depth": 0})"));
    EXPECT_EQ(direct.integrator, IntegratorKind::Direct);
    EXPECT_EQ(direct.max_depth, 0);
    const RenderSettings defaults = settings_of(scene(""));
    EXPECT_EQ(defaults.integrator, IntegratorKind::Direct);
    EXPECT_EQ(defaults.max_depth, 8);
}

TEST_F(SceneV2, RenderTextureFilter) {
    EXPECT_EQ(settings_of(scene("")).texture_filter, TextureFilter::Bilinear);
    EXPECT_EQ(settings_of(scene(R"("render": {"texture_filter": "bilinear"})")).texture_filter,
              TextureFilter::Bilinear);
    EXPECT_EQ(settings_of(scene(R"("render": {"texture_filter": "mipmap"})")).texture_filter, TextureFilter::Mipmap);
}

TEST_F(SceneV2, MaterialsOfVersionTwo) {
    const Scene s = load(scene(R"("materials": {
        "mirror": {"type": "mirror", "kr": [0.9, 0.8, 0.7], "ke": [1, 0, 0]},
        "glass": {"type": "dielectric"},
        "water": {"type": "dielectric", "ior": 1.33, "kt": [0.5, 1, 1]},
        "gold": {"type": "conductor", "ks": [1, 0.78, 0.34], "roughness": 0.25}})"));
    ASSERT_EQ(s.materials.size(), 5u);  // in name order, then tri.obj's default
    const Material& glass = s.materials[0];
    EXPECT_EQ(glass.type, MaterialType::Dielectric);
    EXPECT_EQ(glass.ior, 1.5f);
    EXPECT_EQ(glass.kt, Vec3{1.0f});
    const Material& gold = s.materials[1];
    EXPECT_EQ(gold.type, MaterialType::Conductor);
    EXPECT_EQ(gold.ks, (Vec3{1, 0.78f, 0.34f}));
    EXPECT_EQ(gold.roughness, 0.25f);
    const Material& mirror = s.materials[2];
    EXPECT_EQ(mirror.type, MaterialType::Mirror);
    EXPECT_EQ(mirror.kr, (Vec3{0.9f, 0.8f, 0.7f}));
    EXPECT_EQ(mirror.ke, (Vec3{1, 0, 0}));
    const Material& water = s.materials[3];
    EXPECT_EQ(water.ior, 1.33f);
    EXPECT_EQ(water.kt, (Vec3{0.5f, 1, 1}));
}

TEST_F(SceneV2, PbrMaterialIsRead) {
    const Scene s = load(scene(R"("materials": {
        "plastic": {"type": "pbr", "base_color": [0.8, 0.1, 0.1], "metallic": 0, "roughness": 0.3},
        "steel": {"type": "pbr", "base_color": [0.6, 0.6, 0.65], "metallic": 1, "roughness": 0.5, "ior": 2.5,
                  "ke": [0.1, 0, 0]}})"));
    ASSERT_EQ(s.materials.size(), 3u);  // in name order, then tri.obj's default
    const Material& plastic = s.materials[0];
    EXPECT_EQ(plastic.name, "plastic");
    EXPECT_EQ(plastic.type, MaterialType::Pbr);
    EXPECT_EQ(plastic.base_color, (Vec3{0.8f, 0.1f, 0.1f}));
    EXPECT_EQ(plastic.metallic, 0.0f);
    EXPECT_EQ(plastic.roughness, 0.3f);
    EXPECT_EQ(plastic.ior, 1.5f);  // the default
    EXPECT_EQ(plastic.ke, Vec3{0.0f});
    const Material& steel = s.materials[1];
    EXPECT_EQ(steel.type, MaterialType::Pbr);
    EXPECT_EQ(steel.metallic, 1.0f);
    EXPECT_EQ(steel.roughness, 0.5f);
    EXPECT_EQ(steel.ior, 2.5f);
    EXPECT_EQ(steel.ke, (Vec3{0.1f, 0, 0}));
    EXPECT_TRUE(diag.warnings.empty());
    // The ends of the ranges are allowed, and a pbr material does not ask for the path integrator.
    const Scene ends =
        load(with_material(R"({"type": "pbr", "base_color": [0, 0, 1], "metallic": 1, "roughness": 0})"));
    EXPECT_EQ(ends.materials[0].roughness, 0.0f);
    EXPECT_FALSE(needs_path_integrator(ends));
}

TEST_F(SceneV2, HostileValuesNameWhereAndWhat) {
    expect_errors({
        {scene(R"("render": {"max_depth": 1025})"), ": /render/max_depth: must be between 0 and 1024"},
        {scene(R"("render": {"max_depth": -1})"), ": /render/max_depth: must be between 0 and 1024"},
        {scene(R"("render": {"max_depth": 2.5})"), ": /render/max_depth: expected an integer"},
        {scene(R"("render": {"integrator": "bdpt"})"),
         ": /render/integrator: unknown integrator 'bdpt' (expected 'direct' or 'path')"},
        {scene(R"("render": {"integrator": 1})"), ": /render/integrator: expected a string"},
        {scene(R"("render": {"texture_filter": "trilinear"})"),
         ": /render/texture_filter: unknown texture filter 'trilinear' (expected 'bilinear' or 'mipmap')"},
        {scene(R"("render": {"texture_filter": true})"), ": /render/texture_filter: expected a string"},
        {with_material(R"({"type": "dielectric", "ior": 1})"), ": /materials/m/ior: ior must be greater than 1"},
        {with_material(R"({"type": "dielectric", "ior": 0.5})"), ": /materials/m/ior: ior must be greater than 1"},
        {with_material(R"({"type": "dielectric", "ior": "NaN"})"), ": /materials/m/ior: expected a number"},
        {with_material(R"({"type": "dielectric", "ior": 1e39})"), ": /materials/m/ior: number out of range"},
        {with_material(R"({"type": "dielectric", "kt": [1.1, 1, 1]})"),
         ": /materials/m/kt: kt components must lie in [0, 1]"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": -0.1})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 1.5})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1]})"),
         ": /materials/m/roughness: missing required key 'roughness'"},
        {with_material(R"({"type": "mirror", "kr": [1.5, 0, 0]})"),
         ": /materials/m/kr: kr components must lie in [0, 1]"},
        {with_material(R"({"type": "mirror"})"), ": /materials/m/kr: missing required key 'kr'"},
        {with_material(R"({"type": "mirror", "kr": [1, 1, 1], "kd": [1, 1, 1]})"),
         ": /materials/m/kd: 'kd' applies only to diffuse and phong materials, not mirror"},
        {with_material(R"({"type": "mirror", "kr": [1, 1, 1], "shine": 1})"),
         ": /materials/m/shine: unknown key 'shine'"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1]})"),
         ": /materials/m/metallic: missing required key 'metallic'"},
        {with_material(R"({"type": "pbr", "metallic": 0, "roughness": 0.5})"),
         ": /materials/m/base_color: missing required key 'base_color'"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0})"),
         ": /materials/m/roughness: missing required key 'roughness'"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1.2, 1], "metallic": 0, "roughness": 0.5})"),
         ": /materials/m/base_color: base_color components must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1], "metallic": 0, "roughness": 0.5})"),
         ": /materials/m/base_color: "},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 1.01, "roughness": 0.5})"),
         ": /materials/m/metallic: metallic must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": -0.5, "roughness": 0.5})"),
         ": /materials/m/metallic: metallic must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": "1", "roughness": 0.5})"),
         ": /materials/m/metallic: expected a number"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 2})"),
         ": /materials/m/roughness: roughness must lie in [0, 1]"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ior": 1})"),
         ": /materials/m/ior: ior must be greater than 1"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ior": 1e39})"),
         ": /materials/m/ior: number out of range"},
        {with_material(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "kd": [1, 1, 1]})"),
         ": /materials/m/kd: 'kd' applies only to diffuse and phong materials, not pbr"},
        {with_material(
             R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "emissive": [1, 1, 1]})"),
         ": /materials/m/emissive: unknown key 'emissive'"},
        {with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 0.5, "metallic": 1})"),
         ": /materials/m/metallic: 'metallic' applies only to pbr materials, not conductor"},
        {with_material(R"({"type": "dielectric", "roughness": 0.5})"),
         ": /materials/m/roughness: 'roughness' applies only to conductor and pbr materials, not dielectric"},
        {with_material(R"({"type": "metal"})"),
         ": /materials/m/type: unknown material type 'metal' (expected 'diffuse', 'phong', 'mirror', 'dielectric', "
         "'conductor' or 'pbr')"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [2, 0, 0], "radiance": [1, 1, 1]})"),
         ": /lights/0: quad light edges 'edge1' and 'edge2' are parallel"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [0, 0, 0], "edge2": [0, 1, 0], "radiance": [1, 1, 1]})"),
         ": /lights/0/edge1: quad light edge 'edge1' is zero"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [1, -1, 1]})"),
         ": /lights/0/radiance: colour components must be non-negative"},
        {with_light(R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0]})"),
         ": /lights/0/radiance: missing required key 'radiance'"},
        {with_light(
             R"({"type": "quad", "corner": [0, 0, 0], "edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [1, 1, 1], "position": [0, 0, 0]})"),
         ": /lights/0/position: unknown key 'position'"},
        {with_light(R"({"type": "area", "position": [0, 0, 0]})"), ": /lights/0/type: unknown light type 'area'"},
        {with_environment(R"({"file": "sky.exr"})", R"(, "background": [0, 0, 0])"),
         ": /environment: give either 'background' or 'environment', not both"},
        {with_environment(R"({"file": "nothing.exr"})"),
         ": /environment/file: cannot open 'nothing.exr': no such file"},
        {with_environment(R"({"file": "sky.exr", "scale": -1})"), ": /environment/scale: scale must be non-negative"},
        {with_environment(R"({"file": "sky.exr", "scale": "NaN"})"), ": /environment/scale: expected a number"},
        {with_environment(R"({"file": "sky.exr", "rotate_y": 1e39})"), ": /environment/rotate_y: number out of range"},
        {with_environment(R"({"file": "sky.exr", "clamp_negative": 1})"),
         ": /environment/clamp_negative: expected true or false"},
        {with_environment(R"({"file": "sky.exr", "exposure": 1})"), ": /environment/exposure: unknown key 'exposure'"},
    });
}

TEST_F(SceneV2, NegativeEnvironmentPixelIsAnErrorThatHintsAtTheOptIn) {
    const std::string message = error_of(with_environment(R"({"file": "ringing.exr"})"));
    EXPECT_EQ(message, (dir / "ringing.exr").string() +
                           ": pixel (1, 1) is negative (-2.5); add \"clamp_negative\": true to the environment "
                           "to read negative values as 0");
}

TEST_F(SceneV2, EnvironmentIsRead) {
    const Scene s = load(with_environment(R"({"file": "sky.exr", "scale": 2, "rotate_y": -30})"));
    ASSERT_TRUE(s.environment);
    EXPECT_EQ(s.environment->file, "sky.exr");
    EXPECT_EQ(s.environment->scale, 2.0f);
    EXPECT_EQ(s.environment->rotate_y_degrees, -30.0f);
    EXPECT_EQ(s.environment->image.width, 4);
    EXPECT_EQ(s.environment->image.height, 2);
    EXPECT_TRUE(diag.warnings.empty());
    const Scene defaults = load(with_environment(R"({"file": "sky.exr"})"));
    EXPECT_EQ(defaults.environment->scale, 1.0f);
    EXPECT_EQ(defaults.environment->rotate_y_degrees, 0.0f);
    EXPECT_FALSE(load(scene("")).environment);
}

TEST_F(SceneV2, ClampNegativeReadsNegativesAsZeroWithOneWarning) {
    const Scene s = load(with_environment(R"({"file": "ringing.exr", "clamp_negative": true})"));
    ASSERT_TRUE(s.environment);
    for (const float v : s.environment->image.rgb) EXPECT_GE(v, 0.0f);
    EXPECT_EQ(s.environment->image.rgb[3 * 5 + 1], 0.0f);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("2 negative values read as 0"), std::string::npos) << diag.warnings[0];
}

TEST_F(SceneV2, QuadLightBecomesTwoFrontEmittingTriangles) {
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

TEST_F(SceneV2, QuadLightsKeepNormalAndUvArraysConsistent) {
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

// Spec §11: the outside of glass is the winding normal's side, negated under
// a mirroring transform; sombra swaps two corners so the world winding keeps
// pointing to the same side of the surface.
TEST_F(SceneV2, MirroringTransformKeepsTheWindingSide) {
    const Scene plain = load(scene(""));
    EXPECT_EQ(plain.geometry.triangles[0], (Index3{0, 1, 2}));
    const Vec3 n = winding_normal(plain.geometry, 0);  // (1, 1, 1): away from the origin

    const Scene mirrored = load(scene("", R"([{"file": "tri.obj", "transform": [{"scale": [-1, 1, 1]}]}])"));
    EXPECT_EQ(mirrored.geometry.triangles[0], (Index3{0, 2, 1}));
    const Vec3 m = winding_normal(mirrored.geometry, 0);
    EXPECT_EQ(m, (Vec3{-n.x, n.y, n.z}));  // the mirror image of n: still away from the origin

    // Two mirrors make a rotation: no swap.
    const Scene twice = load(scene("", R"([{"file": "tri.obj", "transform": [{"scale": [-1, -1, 1]}]}])"));
    EXPECT_EQ(twice.geometry.triangles[0], (Index3{0, 1, 2}));
}

TEST_F(SceneV2, MirroringTransformSwapsNormalAndUvCornersAlong) {
    const Scene s = load(scene("", R"([{"file": "normals.obj", "transform": [{"scale": [-2, 1, 1]}]}])"));
    const TriangleMesh& g = s.geometry;
    ASSERT_EQ(g.triangle_count(), 1u);
    const Vec2 uv_of_vertex[3] = {{0, 0}, {1, 0}, {0, 1}};
    for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = g.triangles[0][c];
        // Each corner's normal still points along its own (mirrored) position.
        EXPECT_EQ(g.normals[g.normal_indices[0][c]], normalize(g.positions[v])) << c;
        EXPECT_EQ(g.uvs[g.uv_indices[0][c]], uv_of_vertex[v]) << c;
    }
}

TEST_F(SceneV2, WhatNeedsThePathIntegrator) {
    EXPECT_FALSE(needs_path_integrator(load(scene(""))));
    // Emission of version 1 does not.
    EXPECT_FALSE(
        needs_path_integrator(load(with_material(R"({"type": "diffuse", "kd": [0, 0, 0], "ke": [5, 5, 5]})"))));
    EXPECT_FALSE(
        needs_path_integrator(load(with_material(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 0.5})"))));
    EXPECT_TRUE(needs_path_integrator(load(with_material(R"({"type": "mirror", "kr": [1, 1, 1]})"))));
    EXPECT_TRUE(needs_path_integrator(load(with_material(R"({"type": "dielectric"})"))));
    EXPECT_TRUE(needs_path_integrator(load(with_environment(R"({"file": "sky.exr"})"))));
    // A mirror no triangle uses does not.
    EXPECT_FALSE(needs_path_integrator(load(scene(R"("materials": {"m": {"type": "mirror", "kr": [1, 1, 1]}})"))));
}

}  // namespace
}  // namespace sombra
