// Environment maps of scene files (spec §10): the map as read, and its
// negative pixels, an error unless "clamp_negative" reads them as 0.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneEnvironment : public testing::SceneFileTest {};

TEST_F(SceneEnvironment, NegativeEnvironmentPixelIsAnErrorThatHintsAtTheOptIn) {
    const std::string message = error_of(with_environment(R"({"file": "ringing.exr"})"));
    EXPECT_EQ(message, (dir / "ringing.exr").string() +
                           ": pixel (1, 1) is negative (-2.5); add \"clamp_negative\": true to the environment "
                           "to read negative values as 0");
}

TEST_F(SceneEnvironment, EnvironmentIsRead) {
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

TEST_F(SceneEnvironment, ClampNegativeReadsNegativesAsZeroWithOneWarning) {
    const Scene s = load(with_environment(R"({"file": "ringing.exr", "clamp_negative": true})"));
    ASSERT_TRUE(s.environment);
    for (const float v : s.environment->image.rgb) EXPECT_GE(v, 0.0f);
    EXPECT_EQ(s.environment->image.rgb[3 * 5 + 1], 0.0f);
    ASSERT_EQ(diag.warnings.size(), 1u);
    EXPECT_NE(diag.warnings[0].find("2 negative values read as 0"), std::string::npos) << diag.warnings[0];
}

}  // namespace
}  // namespace sombra
