// A scene file's "media" and the render's medium (spec §26): the values read,
// scaled, and every bad value refused in one line naming its key.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneMedia : public testing::SceneFileTest {
protected:
    // A scene whose "media" holds `media` and whose render section is `render`.
    static std::string with_media(const std::string& media, const std::string& render = "{}") {
        return scene(R"("media": )" + media + R"(, "render": )" + render);
    }
    void expect_error(const std::string& text, const std::string& where, const std::string& what) {
        try {
            load(text);
            ADD_FAILURE() << "no error for " << text;
        } catch (const Error& e) {
            EXPECT_EQ(e.where(), scene_path.string() + where) << text;
            EXPECT_NE(e.message().find(what), std::string::npos) << e.message();
        }
    }
};

TEST_F(SceneMedia, ReadsAHomogeneousMediumAndTheRendersMedium) {
    const Scene s = load(with_media(
        R"({"fog": {"type": "homogeneous", "sigma_a": [0.1, 0.2, 0.3], "sigma_s": [1, 2, 3], "g": 0.5,
                    "emission": [0.01, 0, 0], "scale": 2},
            "air": {"type": "homogeneous"}})",
        R"({"medium": "fog", "integrator": "path", "max_volume_depth": 7})"));
    ASSERT_EQ(s.media.size(), 2u);
    ASSERT_NE(s.render_medium, kNoMedium);
    const Medium& fog = s.media[s.render_medium];
    EXPECT_EQ(fog.name, "fog");
    EXPECT_FLOAT_EQ(fog.sigma_a.y, 0.4f);  // scaled
    EXPECT_FLOAT_EQ(fog.sigma_s.z, 6.0f);
    EXPECT_FLOAT_EQ(fog.g, 0.5f);
    EXPECT_FLOAT_EQ(fog.emission.x, 0.01f);  // emission is not scaled (spec §26)
    EXPECT_FLOAT_EQ(extinction(fog).x, 2.2f);
    const Medium& air = s.media[s.render_medium == 0 ? 1 : 0];
    EXPECT_EQ(air.name, "air");
    EXPECT_EQ(max_component(extinction(air)), 0.0f);
    EXPECT_EQ(
        settings_of(with_media(R"({"fog": {"type": "homogeneous"}})", R"({"max_volume_depth": 7})")).max_volume_depth,
        7);
}

TEST_F(SceneMedia, WithoutMediaTheSceneIsInVacuum) {
    const Scene s = load(scene(""));
    EXPECT_TRUE(s.media.empty());
    EXPECT_EQ(s.render_medium, kNoMedium);
    EXPECT_EQ(settings_of(scene("")).max_volume_depth, 256);
}

TEST_F(SceneMedia, BadValuesNameTheirKey) {
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "sigma_a": [-1, 0, 0]}})"), ": /media/fog/sigma_a",
                 "non-negative");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "sigma_s": [0, 0]}})"), ": /media/fog/sigma_s", "3");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "g": 1}})"), ": /media/fog/g", "between -1 and 1");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "g": -1.5}})"), ": /media/fog/g", "between -1 and 1");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "scale": -2}})"), ": /media/fog/scale", "non-negative");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "sigma_s": [10, 10, 10], "scale": 1e38}})"),
                 ": /media/fog/scale", "overflow");
    expect_error(with_media(R"({"fog": {"type": "homogeneous", "colour": [1, 1, 1]}})"), ": /media/fog/colour",
                 "unknown key 'colour'");
    expect_error(with_media(R"({"fog": {"sigma_s": [1, 1, 1]}})"), ": /media/fog/type", "missing required key");
    expect_error(with_media(R"({"fog": {"type": "smoke"}})"), ": /media/fog/type", "unknown medium type 'smoke'");
    expect_error(with_media(R"({"fog": {"type": "grid", "file": "smoke.vdb"}})"), ": /media/fog/type",
                 "not supported yet");
    expect_error(with_media(R"([1, 2])"), ": /media", "expected an object");
    expect_error(with_media(R"({"fog": {"type": "homogeneous"}})", R"({"medium": "smoke"})"), ": /render/medium",
                 "no medium 'smoke' in /media");
    expect_error(scene(R"("render": {"medium": "fog"})"), ": /render/medium", "no medium 'fog' in /media");
    expect_error(scene(R"("render": {"max_volume_depth": -1})"), ": /render/max_volume_depth", "between 0 and 65536");
}

}  // namespace
}  // namespace sombra
