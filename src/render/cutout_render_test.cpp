// Cut-outs through the whole pipeline (spec §12): a scene file whose leaf
// quad has an alpha map, loaded and rendered by the direct integrator. Camera
// rays see the floor through the cut strip, the leaf neither shows nor emits
// there, and its shadow on the floor has the outline that projecting the
// remaining parts from the point light predicts, pixel by pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/images/image_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"

namespace sombra {
namespace {

using testing::TempFolder;

constexpr int kSide = 64;
// The camera frames the square [-1, 1]² of the plane z = 0 from z = 4: pixel
// (i, j) looks at x = (2i + 1)/W − 1, y = 1 − (2j + 1)/H.
const std::string kScene = R"({
  "render": {"width": 64, "height": 64},
  "camera": {"origin": [0, 0, 4], "left": [-1, 0, 0], "up": [0, 1, 0], "forward": [0, 0, -4]},
  "materials": {"floor": {"type": "diffuse", "kd": [1, 1, 1]},
                "leaf": {"type": "diffuse", "kd": [0, 0, 0], "ke": [0, 0, 1], "alpha": {"texture": "strip.png"}}},
  "lights": [{"position": [-0.9, 0.2, 3], "intensity": [5, 5, 5]}],
  "objects": [{"file": "floor.obj", "material": "floor"}, {"file": "leaf.obj", "material": "leaf"}]})";
const Vec3 kLight{-0.9f, 0.2f, 3.0f};

// The leaf: z = 1 over [-0.6, 0.6]², u = (x + 0.6)/1.2. Its alpha (8 × 1
// texels 1 1 0 0 0 0 1 1, bilinear) is below the ½ cutoff exactly for
// 0.25 < u < 0.75, i.e. |x| < 0.3. `margin`: how close to an outline a point
// may come and still count as decided (rounding of the geometry).
enum class Leaf { There, Missing, Undecided };
Leaf leaf_at(double x, double y) {
    constexpr double margin = 2e-3;
    const double edge = std::max(std::fabs(x), std::fabs(y));
    if (std::fabs(edge - 0.6) < margin || (std::fabs(y) < 0.6 + margin && std::fabs(std::fabs(x) - 0.3) < margin))
        return Leaf::Undecided;
    return edge < 0.6 && std::fabs(x) > 0.3 ? Leaf::There : Leaf::Missing;
}

TEST(CutoutRender, CameraRaysSeeThroughTheStripAndTheShadowHasItsOutline) {
    TempFolder tmp;
    testing::write_png_file(tmp.path / "strip.png", 8, 1, 1, 8, {255, 255, 0, 0, 0, 0, 255, 255});
    tmp.write("floor.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    tmp.write("leaf.obj",
              "v -0.6 -0.6 1\nv 0.6 -0.6 1\nv 0.6 0.6 1\nv -0.6 0.6 1\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
    tmp.write("s.json", kScene);
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(tmp.path / "s.json", diag);
    const Scene& scene = loaded.scene;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, loaded.settings, 1);
    RenderProgress progress;
    const Film film = render_image(job, progress).film;

    int leaf = 0, lit = 0, shadow = 0;
    for (int j = 0; j < kSide; ++j)
        for (int i = 0; i < kSide; ++i) {
            const double x = (2.0 * i + 1) / kSide - 1, y = 1 - (2.0 * j + 1) / kSide;
            const Vec3 c = film.at(i, j);
            const std::string where = "pixel " + std::to_string(i) + ", " + std::to_string(j);
            // The camera ray from (0, 0, 4) crosses the leaf's plane at ¾ of the way.
            const Leaf seen = leaf_at(0.75 * x, 0.75 * y);
            if (seen == Leaf::Undecided) continue;
            if (seen == Leaf::There) {
                EXPECT_EQ(c.x, 0.0f) << where << ": the leaf emits blue only";
                EXPECT_EQ(c.z, 1.0f) << where;
                ++leaf;
                continue;
            }
            // The floor point (x, y, 0); its shadow ray meets z = 1 a third of the way to the light.
            const Leaf blocker = leaf_at(x + (kLight.x - x) / 3, y + (kLight.y - y) / 3);
            if (blocker == Leaf::Undecided) continue;
            if (blocker == Leaf::There) {
                EXPECT_EQ(c, Vec3{0.0f}) << where << ": in the leaf's shadow";
                ++shadow;
            } else {
                EXPECT_GT(c.x, 0.0f) << where << ": lit";
                EXPECT_EQ(c.z, c.x) << where << ": white floor, no blue from the cut strip";
                ++lit;
            }
        }
    // Each kind fills a good part of the image, so none is decided vacuously.
    EXPECT_GT(leaf, 300);
    EXPECT_GT(lit, 1000);
    EXPECT_GT(shadow, 300);
}

}  // namespace
}  // namespace sombra
