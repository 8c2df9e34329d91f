// Scene files, version 3: spot and directional lights (spec §16) and the
// thin lens (spec §17), as read, and every hostile value as one error that
// names where and what.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneV3 : public testing::SceneFileTest {
protected:
    static void SetUpTestSuite() { make_folder("scene_v3_test"); }
};

constexpr const char* kCamera = R"("camera": {"origin": [0, 0, 5], "look_at": [0, 0, 0]})";

std::string with_light(const std::string& light) {
    return std::string(R"({"lights": [)") + light + "], " + kCamera + R"(, "objects": [{"file": "tri.obj"}]})";
}
std::string with_camera(const std::string& camera) {
    return std::string(R"({"camera": )") + camera + R"(, "objects": [{"file": "tri.obj"}]})";
}

TEST_F(SceneV3, SpotAndDirectionalLightsAreRead) {
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

TEST_F(SceneV3, SpotFalloffFollowsTheSpec) {
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

TEST_F(SceneV3, ThinLensIsReadAndDefaultsToTheLookAtDistance) {
    const Scene pinhole = load(with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0]})"));
    EXPECT_EQ(pinhole.camera.aperture_radius, 0.0f);
    EXPECT_FALSE(pinhole.camera.focus_distance);
    const Scene lens = load(with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "aperture_radius": 0.1})"));
    EXPECT_EQ(lens.camera.aperture_radius, 0.1f);
    EXPECT_FALSE(lens.camera.focus_distance);  // |look_at − origin| at render time
    const Scene basis = load(with_camera(R"({"origin": [0, 0, 5], "left": [-1, 0, 0], "up": [0, 1, 0],
        "forward": [0, 0, -1], "aperture_radius": 0.2, "focus_distance": 3})"));
    EXPECT_EQ(basis.camera.aperture_radius, 0.2f);
    ASSERT_TRUE(basis.camera.focus_distance);
    EXPECT_EQ(*basis.camera.focus_distance, 3.0f);
}

TEST_F(SceneV3, HostileValuesNameWhereAndWhat) {
    const std::string spot = R"("type": "spot", "position": [0, 0, 0], "intensity": [1, 1, 1])";
    const std::string sun = R"("type": "directional")";
    expect_errors({
        {with_light("{" + spot + R"(, "direction": [0, 0, 0]})"), ": /lights/0/direction: direction is zero"},
        {with_light("{" + spot + "}"), ": /lights/0/direction: missing required key 'direction'"},
        {with_light("{" + spot + R"(, "direction": [0, 0, "x"]})"),
         ": /lights/0/direction: expected an array of 3 numbers"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 0})"),
         ": /lights/0/outer_angle: a spot light's outer_angle must be greater than 0 degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 91})"),
         ": /lights/0/outer_angle: angle 91 is outside (0, 90] degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": -5})"),
         ": /lights/0/outer_angle: angle -5 is outside (0, 90] degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "inner_angle": -1})"),
         ": /lights/0/inner_angle: angle -1 is outside [0, 90] degrees"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 30, "inner_angle": 40})"),
         ": /lights/0/inner_angle: inner_angle 40 is larger than outer_angle 30"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "outer_angle": 1e39})"),
         ": /lights/0/outer_angle: number out of range"},
        {with_light("{" + spot + R"(, "direction": [0, 0, -1], "cone": 3})"), ": /lights/0/cone: unknown key 'cone'"},
        {with_light(R"({"type": "spot", "position": [0, 0, 0], "direction": [0, 0, -1], "intensity": [1, -1, 1]})"),
         ": /lights/0/intensity: colour components must be non-negative"},
        {with_light("{" + sun + R"(, "direction": [0, 0, 0], "irradiance": [1, 1, 1]})"),
         ": /lights/0/direction: direction is zero"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1], "irradiance": [1, 1, -1]})"),
         ": /lights/0/irradiance: colour components must be non-negative"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1]})"),
         ": /lights/0/irradiance: missing required key 'irradiance'"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1], "intensity": [1, 1, 1]})"),
         ": /lights/0/intensity: unknown key 'intensity'"},
        {with_light("{" + sun + R"(, "direction": [0, 0, -1], "irradiance": [1, 1, 1], "position": [0, 0, 0]})"),
         ": /lights/0/position: unknown key 'position'"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "aperture_radius": -0.1})"),
         ": /camera/aperture_radius: aperture_radius must be >= 0"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "aperture_radius": "wide"})"),
         ": /camera/aperture_radius: expected a number"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "focus_distance": 0})"),
         ": /camera/focus_distance: focus_distance must be > 0"},
        {with_camera(R"({"origin": [0, 0, 5], "look_at": [0, 0, 0], "focus_distance": -2})"),
         ": /camera/focus_distance: focus_distance must be > 0"},
        {with_camera(R"({"origin": [0, 0, 5], "left": [-1, 0, 0], "up": [0, 1, 0], "forward": [0, 0, -1],
            "aperture_radius": 0.1})"),
         ": /camera: a basis-form camera with 'aperture_radius' > 0 needs 'focus_distance'"},
    });
}

}  // namespace
}  // namespace sombra
