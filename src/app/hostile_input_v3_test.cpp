// Hostile values of the version-3 keys through the real executable: spot
// and directional lights (spec §16), the thin lens (spec §17), and glTF
// spot cone angles. Each is one "sombra: error:" line, exit 1, no image.
#include <gtest/gtest.h>

#include "cli_test_fixture.h"

namespace {

using namespace sombra::cli_test;

const std::string kRender = R"({"width": 16, "height": 12})";
const std::string kCamera = R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "fov": 40})";

class HostileV3 : public CliFixture {
protected:
    std::string light_scene(const std::string& light, const std::string& camera = kCamera) {
        return R"({"render": )" + kRender + R"(, "camera": )" + camera +
               R"(, "materials": {"grey": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}}, "lights": [)" + light +
               R"(], "objects": [{"file": "square.obj", "material": "grey"}]})";
    }
    RunResult render(const std::string& scene_text) {
        write_text(dir_ / "s.json", scene_text);
        return run("render s.json -o out.png --quiet --threads 2");
    }
    void expect_error_at(const RunResult& r, const std::string& where, const std::string& what) {
        expect_input_error(r, what);
        EXPECT_EQ(r.err.rfind("sombra: error: " + where + ": ", 0), 0u) << "expected WHERE " << where << ": " << r.err;
    }
};

TEST_F(HostileV3, BadSpotDirectionalAndLensValuesAreOneLineErrors) {
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

TEST_F(HostileV3, SpotAndDirectionalLightsRenderWithALens) {
    const RunResult ok = render(light_scene(
        R"({"type": "spot", "position": [0, 0, 2], "direction": [0, 0, -1], "intensity": [3, 3, 3], "outer_angle": 30},
           {"type": "directional", "direction": [0, 0, -1], "irradiance": [1, 1, 1]})",
        R"({"origin": [0, 0, 4], "look_at": [0, 0, 0], "aperture_radius": 0.05})"));
    EXPECT_EQ(ok.status, 0) << ok.err;
    EXPECT_TRUE(ok.err.empty()) << ok.err;
    EXPECT_TRUE(fs::exists(dir_ / "out.png"));
}

}  // namespace
