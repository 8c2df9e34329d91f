// A glTF file's orthographic camera (spec §24) through the whole pipeline:
// the image shows exactly the pixels whose centres the parallel rays from
// the camera's z = 0 plane send onto a rectangle of known size, the way
// round a perspective camera at the same node shows it, also when the
// file's animation moves the rectangle; and a bad ymag is an error naming
// the member.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "io/gltf/gltf_test_files.h"
#include "io/polygon_test_files.h"
#include "io/quicklook.h"
#include "render/render.h"
#include "scene/animation.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

constexpr int kWidth = 40, kHeight = 20;

// An emissive rectangle x ∈ [−0.5, 1.5], y ∈ [0, 0.5] in z = 0 facing +z,
// and a camera node at `at` looking down −z with camera 0 `camera`.
GltfFile rectangle_file(const nlohmann::json& camera, Vec3 at = {0.5f, 0.2f, 3}) {
    GltfFile f;
    const int p = f.add_positions({{-0.5f, 0, 0}, {1.5f, 0, 0}, {1.5f, 0.5f, 0}, {-0.5f, 0.5f, 0}});
    f.add_mesh({{"POSITION", p}}, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {{{"emissiveFactor", {1, 1, 1}}}};
    f.doc["cameras"] = {camera};
    f.add_node({{"mesh", 0}});
    f.add_node({{"camera", 0}, {"translation", {at.x, at.y, at.z}}});
    f.set_scene({0, 1});
    return f;
}

nlohmann::json orthographic(double ymag, double xmag = 1) {
    return {{"type", "orthographic"}, {"orthographic", {{"xmag", xmag}, {"ymag", ymag}, {"znear", 0.1}, {"zfar", 9}}}};
}

// Which pixels see the rectangle (emission 1 against the dark background),
// row-major, top row first; rendered at one sample per pixel (its centre),
// at `time` when given (an animated file).
std::vector<bool> seen(const GltfFile& f, std::optional<double> time = std::nullopt) {
    TempFolder dir;
    f.save(dir.path / "m.gltf");
    Diagnostics diag;
    LoadedScene loaded = make_quicklook_scene(dir.path / "m.gltf", diag);
    if (time) set_scene_time(loaded.scene, *time, "m.gltf");
    const bool orthographic = f.doc["cameras"][0]["type"] == "orthographic";
    EXPECT_EQ(loaded.scene.camera.projection == CameraSpec::Projection::Orthographic, orthographic);
    loaded.settings.width = kWidth;
    loaded.settings.height = kHeight;
    loaded.settings.spp = 1;
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    RenderProgress progress;
    const Film film = render_image(make_render_job(loaded.scene, accel, loaded.settings, 1), progress).film;
    std::vector<bool> out;
    for (std::size_t p = 0; p < film.rgb.size(); p += 3) out.push_back(film.rgb[p + 1] > 0.5f);
    return out;
}

bool at(const std::vector<bool>& image, int i, int j) {
    return image[static_cast<std::size_t>(j) * kWidth + static_cast<std::size_t>(i)];
}

TEST(GltfOrthographic, TheRectangleCoversExactlyThePixelsItsSizeSays) {
    // ymag 1 on a 2:1 image: the view is 4 × 2, 0.1 per pixel, centred on
    // the camera at (0.5, 0.2). Pixel (i, j)'s centre is x = −1.5 + 0.1(i + ½)
    // (s = +1, the left edge, is −x), y = 1.2 − 0.1(j + ½): the rectangle's
    // are i = 10 … 29, j = 7 … 11. xmag, which disagrees with the image's
    // aspect, is not used.
    const std::vector<bool> image = seen(rectangle_file(orthographic(1, 7)));
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i)
            EXPECT_EQ(at(image, i, j), i >= 10 && i <= 29 && j >= 7 && j <= 11) << "pixel (" << i << ", " << j << ")";
}

TEST(GltfOrthographic, AnAnimatedFileKeepsTheOrthographicView) {
    // The rectangle's node moves 1 along +x in the first second: at 1 s it
    // covers the pixels 10 columns (1 / 0.1) right of the still one's.
    GltfFile f = rectangle_file(orthographic(1));
    const std::vector<float> times{0, 1}, moves{0, 0, 0, 1, 0, 0};
    const int in = f.add_array(times, gltf_test::kFloat, 2, "SCALAR");
    const int out = f.add_array(moves, gltf_test::kFloat, 2, "VEC3");
    const nlohmann::json sampler = {{"input", in}, {"output", out}};
    const nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}};
    f.doc["animations"] = nlohmann::json::array(
        {{{"samplers", nlohmann::json::array({sampler})}, {"channels", nlohmann::json::array({channel})}}});
    const std::vector<bool> image = seen(f, 1.0);
    for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i)
            EXPECT_EQ(at(image, i, j), i >= 20 && i <= 39 && j >= 7 && j <= 11) << "pixel (" << i << ", " << j << ")";
}

TEST(GltfOrthographic, TheImageIsTheWayRoundAPerspectiveCamerasIs) {
    // From (0, 0, 3) the rectangle (centre (0.5, 0.25)) is right of and
    // above the view's axis: for a perspective camera at the same node too.
    const auto centroid = [](const std::vector<bool>& image, double& x, double& y) {
        int n = 0;
        x = y = 0;
        for (int j = 0; j < kHeight; ++j)
            for (int i = 0; i < kWidth; ++i)
                if (at(image, i, j)) x += i + 0.5, y += j + 0.5, ++n;
        ASSERT_GT(n, 0);
        x /= n, y /= n;
    };
    double ox = 0, oy = 0, px = 0, py = 0;
    const Vec3 at{0, 0, 3};
    centroid(seen(rectangle_file(orthographic(1), at)), ox, oy);
    centroid(seen(rectangle_file({{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}}, at)), px,
             py);
    EXPECT_GT(ox, kWidth / 2.0);
    EXPECT_LT(oy, kHeight / 2.0);
    EXPECT_GT(px, kWidth / 2.0);
    EXPECT_LT(py, kHeight / 2.0);
}

TEST(GltfOrthographic, AYmagThatIsNotAPositiveFiniteNumberIsAnError) {
    for (const double ymag : {0.0, -1.0, 1e300}) {
        SCOPED_TRACE(ymag);
        TempFolder dir;
        rectangle_file(orthographic(ymag)).save(dir.path / "m.gltf");
        Diagnostics diag;
        try {
            (void)make_quicklook_scene(dir.path / "m.gltf", diag);
            ADD_FAILURE() << "no error";
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind((dir.path / "m.gltf").string() + ": /cameras/0/orthographic/ymag: ", 0), 0u) << what;
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

}  // namespace
}  // namespace sombra
