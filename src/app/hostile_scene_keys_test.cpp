// Hostile values of a scene's materials, lights, environment and camera
// (spec §10, §11, §16, §17) through the real executable, one case per row of
// docs/robustness.md's tables: one "sombra: error:" line, exit 1, no image;
// and the negative environment pixels "clamp_negative" reads as 0.
#include <gtest/gtest.h>

#include <vector>

#include "hostile_test_fixture.h"
#include "io/images/exr_test_file.h"

namespace {

using namespace sombra::cli_test;
using sombra::testing::write_exr;

class HostileSceneKeys : public HostileFixture {};

TEST_F(HostileSceneKeys, BadRenderMaterialLightAndEnvironmentValuesAreOneLineErrors) {
    const std::string quad = R"({"type": "quad", "corner": [0, 0, 1], )";
    const struct {
        std::string text, where, what;
    } cases[] = {
        {material_scene(R"({"type": "dielectric", "ior": 1})"), "s.json: /materials/m/ior", "greater than 1"},
        {material_scene(R"({"type": "dielectric", "ior": "NaN"})"), "s.json: /materials/m/ior", "expected a number"},
        {material_scene(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": -0.1})"),
         "s.json: /materials/m/roughness", "must lie in [0, 1]"},
        {material_scene(R"({"type": "conductor", "ks": [1, 1, 1], "roughness": 1.5})"),
         "s.json: /materials/m/roughness", "must lie in [0, 1]"},
        {material_scene(R"({"type": "mirror", "kr": [1.2, 1, 1]})"), "s.json: /materials/m/kr", "must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "roughness": 0.5})"),
         "s.json: /materials/m/metallic", "missing required key 'metallic'"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 1.5, "roughness": 0.5})"),
         "s.json: /materials/m/metallic", "metallic must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": "NaN", "roughness": 0.5})"),
         "s.json: /materials/m/metallic", "expected a number"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": -0.1})"),
         "s.json: /materials/m/roughness", "roughness must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [-0.1, 1, 1], "metallic": 0, "roughness": 0.5})"),
         "s.json: /materials/m/base_color", "base_color components must lie in [0, 1]"},
        {material_scene(R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ior": 0.9})"),
         "s.json: /materials/m/ior", "greater than 1"},
        {material_scene(
             R"({"type": "pbr", "base_color": [1, 1, 1], "metallic": 0, "roughness": 0.5, "ks": [1, 1, 1]})"),
         "s.json: /materials/m/ks", "'ks' applies only to phong and conductor materials, not pbr"},
        {scene_with("", R"({"width": 16, "height": 12, "max_depth": 1025})"), "s.json: /render/max_depth",
         "between 0 and 1024"},
        {scene_with("", R"({"width": 16, "height": 12, "max_depth": -1})"), "s.json: /render/max_depth",
         "between 0 and 1024"},
        {scene_with("", R"({"width": 16, "height": 12, "max_depth": 2.5})"), "s.json: /render/max_depth",
         "expected an integer"},
        {scene_with("", R"({"width": 16, "height": 12, "integrator": "photon"})"), "s.json: /render/integrator",
         "unknown integrator 'photon' (expected 'direct' or 'path')"},
        {light_scene(quad + R"("edge1": [1, 0, 0], "edge2": [-3, 0, 0], "radiance": [1, 1, 1]})"), "s.json: /lights/0",
         "parallel"},
        {light_scene(quad + R"("edge1": [1, 0, 0], "edge2": [0, 0, 0], "radiance": [1, 1, 1]})"),
         "s.json: /lights/0/edge2", "is zero"},
        {light_scene(quad + R"("edge1": [1, 0, 0], "edge2": [0, 1, 0], "radiance": [-1, 1, 1]})"),
         "s.json: /lights/0/radiance", "non-negative"},
        {scene_with(R"(, "background": [0, 0, 0], "environment": {"file": "sky.exr"})"), "s.json: /environment",
         "not both"},
        {scene_with(R"(, "environment": {"file": "missing.exr"})"), "s.json: /environment/file", "no such file"},
        {scene_with(R"(, "environment": {"file": "sky.exr", "scale": "NaN"})"), "s.json: /environment/scale",
         "expected a number"},
    };
    write_exr(dir_ / "sky.exr", 2, 1, {1, 1, 1, 1, 1, 1});
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        expect_error_at(render(c.text), c.where, c.what);
    }
}

TEST_F(HostileSceneKeys, NegativeEnvironmentPixelNeedsTheOptIn) {
    write_exr(dir_ / "ringing.exr", 2, 1, {1, 1, 1, 1, -0.25f, 1});
    const RunResult bad = render(scene_with(R"(, "environment": {"file": "ringing.exr"})"));
    expect_error_at(bad, "ringing.exr",
                    "pixel (1, 0) is negative (-0.25); add \"clamp_negative\": true to the environment to read "
                    "negative values as 0");

    const RunResult ok = render(scene_with(R"(, "environment": {"file": "ringing.exr", "clamp_negative": true})"),
                                "--integrator path --spp 1");
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_EQ(count(ok.err, "sombra: warning: "), 1u) << ok.err;
    EXPECT_NE(ok.err.find("ringing.exr: 1 negative values read as 0"), std::string::npos) << ok.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

TEST_F(HostileSceneKeys, BadSpotDirectionalAndLensValuesAreOneLineErrors) {
    const std::string spot = R"({"type": "spot", "position": [0, 0, 2], "intensity": [1, 1, 1], )";
    const std::string sun = R"({"type": "directional", )";
    const std::string lens = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], )";
    const struct {
        std::string text, where, what;
    } cases[] = {
        {light_scene(spot + R"("direction": [0, 0, 0]})"), "s.json: /lights/0/direction", "direction is zero"},
        {light_scene(spot + R"("direction": [0, 0, "NaN"]})"), "s.json: /lights/0/direction", "expected an array"},
        {light_scene(spot + R"("direction": [0, 0, -1], "outer_angle": 0})"), "s.json: /lights/0/outer_angle",
         "greater than 0"},
        {light_scene(spot + R"("direction": [0, 0, -1], "outer_angle": 120})"), "s.json: /lights/0/outer_angle",
         "outside (0, 90]"},
        {light_scene(spot + R"("direction": [0, 0, -1], "inner_angle": 50})"), "s.json: /lights/0/inner_angle",
         "larger than outer_angle 45"},
        {light_scene(spot + R"("direction": [0, 0, -1], "inner_angle": -3})"), "s.json: /lights/0/inner_angle",
         "outside [0, 90]"},
        {light_scene(spot + R"("direction": [0, 0, -1], "outer_angle": 1e39})"), "s.json: /lights/0/outer_angle",
         "out of range"},
        {light_scene(R"({"type": "spot", "position": [0, 0, 2], "direction": [0, 0, -1], "intensity": [1, -1, 1]})"),
         "s.json: /lights/0/intensity", "non-negative"},
        {light_scene(sun + R"("direction": [0, 0, 0], "irradiance": [1, 1, 1]})"), "s.json: /lights/0/direction",
         "direction is zero"},
        {light_scene(sun + R"("direction": [0, 0, -1], "irradiance": [1, 1, -2]})"), "s.json: /lights/0/irradiance",
         "non-negative"},
        {light_scene(sun + R"("direction": [0, 0, -1], "irradiance": 5})"), "s.json: /lights/0/irradiance",
         "expected an array of 3 numbers"},
        {light_scene(R"({"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]})",
                     lens + R"("aperture_radius": -1})"),
         "s.json: /camera/aperture_radius", "must be >= 0"},
        {light_scene(R"({"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]})",
                     lens + R"("aperture_radius": 0.1, "focus_distance": 0})"),
         "s.json: /camera/focus_distance", "must be > 0"},
        {light_scene(
             R"({"type": "point", "position": [0, 0, 2], "intensity": [1, 1, 1]})",
             R"({"origin": [0, 0, 4], "left": [-1, 0, 0], "up": [0, 1, 0], "forward": [0, 0, -1], "aperture_radius": 0.1})"),
         "s.json: /camera", "needs 'focus_distance'"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.text);
        expect_error_at(render(c.text), c.where, c.what);
    }
}

TEST_F(HostileSceneKeys, SpotAndDirectionalLightsRenderWithALens) {
    const RunResult ok = render(light_scene(
        R"({"type": "spot", "position": [0, 0, 2], "direction": [0, 0, -1], "intensity": [3, 3, 3], "outer_angle": 30},
           {"type": "directional", "direction": [0, 0, -1], "irradiance": [1, 1, 1]})",
        R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "aperture_radius": 0.05})"));
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_TRUE(ok.err.empty()) << ok.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

}  // namespace
