// The camera of scene files (spec §3, §17): the basis form kept as written,
// and the thin lens.
#include <gtest/gtest.h>

#include <string>

#include "io/scene_json/scene_file.h"
#include "io/scene_json/scene_file_fixture.h"

namespace sombra {
namespace {

class SceneCamera : public testing::SceneFileTest {};

TEST_F(SceneCamera, BasisCameraIsKeptAsWritten) {
    const Scene s = load(with_camera(R"({"origin": [1,2,3], "left": [-2,0,0], "up": [0,1.5,0], "forward": [0,0,-1]})"));
    ASSERT_TRUE(s.camera.basis.has_value());
    EXPECT_FALSE(s.camera.look_at.has_value());
    EXPECT_EQ(s.camera.basis->origin, Vec3(1, 2, 3));
    EXPECT_EQ(s.camera.basis->left, Vec3(-2, 0, 0));
    EXPECT_EQ(s.camera.basis->up, Vec3(0, 1.5f, 0));
    EXPECT_EQ(s.camera.basis->forward, Vec3(0, 0, -1));
}

TEST_F(SceneCamera, ThinLensIsReadAndDefaultsToTheLookAtDistance) {
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

}  // namespace
}  // namespace sombra
