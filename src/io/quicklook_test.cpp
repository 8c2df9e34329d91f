// The quick look's framing (spec §7, docs/cli.md "Quick look at a model"):
// a three-quarter view from the front (+z), its left and above, with the
// whole model in the default frame, whatever the model's size and place.
#include "io/quicklook.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "io/polygon_test_files.h"

namespace sombra {
namespace {

using testing::TempFolder;

// An OBJ box with corners lo and hi (12 triangles).
std::string box_obj(Vec3 lo, Vec3 hi) {
    std::string obj;
    for (int i = 0; i < 8; ++i) {
        const Vec3 p{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
        obj += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
    return obj;
}

TEST(QuickLook, FramesTheWholeModelInAThreeQuarterViewFromTheFrontLeftAbove) {
    // Long, flat and far from the origin: the framing must follow the model.
    const Vec3 lo{97, -3, 40}, hi{105, -1, 43};
    TempFolder dir;
    Diagnostics diag;
    const LoadedScene loaded = make_quicklook_scene(dir.write("box.obj", box_obj(lo, hi)), diag);
    const CameraSpec& camera = loaded.scene.camera;
    ASSERT_TRUE(camera.look_at);
    const CameraLookAt& c = *camera.look_at;
    const Vec3 centre = 0.5f * (lo + hi);
    EXPECT_NEAR(length(c.look_at - centre), 0.0f, 1e-4f);
    EXPECT_EQ(c.up, (Vec3{0, 1, 0}));
    const Vec3 back = normalize(c.origin - c.look_at);  // from the model toward the camera
    EXPECT_GT(back.z, 0.8f);                            // in front (+z) …
    EXPECT_LT(back.x, -0.3f);                           // … and to its left, a three-quarter view …
    const float elevation = std::asin(back.y) * 180.0f / std::numbers::pi_v<float>;
    EXPECT_GT(elevation, 15.0f);  // … from above
    EXPECT_LT(elevation, 35.0f);

    // Every corner projects inside the default frame.
    const float aspect = static_cast<float>(loaded.settings.width) / static_cast<float>(loaded.settings.height);
    const float tan_half = std::tan(0.5f * c.fov_degrees * std::numbers::pi_v<float> / 180.0f);
    const Vec3 forward = -1.0f * back;
    const Vec3 right = normalize(cross(forward, c.up));
    const Vec3 up = cross(right, forward);
    for (int i = 0; i < 8; ++i) {
        const Vec3 p{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
        const Vec3 d = p - c.origin;
        const float depth = dot(d, forward);
        ASSERT_GT(depth, 0.0f);
        EXPECT_LT(std::fabs(dot(d, right)) / depth, tan_half * aspect) << "corner " << i;
        EXPECT_LT(std::fabs(dot(d, up)) / depth, tan_half) << "corner " << i;
    }
}

}  // namespace
}  // namespace sombra
