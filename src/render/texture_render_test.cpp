// Textures through the whole pipeline (spec §12): files written here, loaded
// by the scene loader, rendered by render_image at one sample per pixel
// centre. A 2×2 texture lands on an OBJ quad the right way up (v = 0 at the
// image's bottom row); a constant normal map shades exactly like a plane
// whose vertex normals are the mapped normal; bump maps tilt the normal as
// the height's slope says.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/images/image_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"
#include "render/shading.h"

namespace sombra {
namespace {

using testing::TempFolder;

// A camera framing the square [-1, 1]² of the plane z = 0 exactly: pixel
// (i, j) of W × H looks at x = (2i + 1)/W − 1, y = 1 − (2j + 1)/H.
const std::string kCamera =
    R"("camera": {"origin": [0, 0, 4], "left": [-1, 0, 0], "up": [0, 1, 0], "forward": [0, 0, -4]})";
// That square, counter-clockwise seen from the camera, uv (0, 0) at its bottom left.
const std::string kQuadObj = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n";

Film render_file(const std::filesystem::path& scene_file) {
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(scene_file, diag);
    const Scene& scene = loaded.scene;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, loaded.settings, 1);
    RenderProgress progress;
    return render_image(job, progress).film;
}

void expect_near(Vec3 got, Vec3 want, float tolerance, const std::string& what) {
    EXPECT_NEAR(got.x, want.x, tolerance) << what;
    EXPECT_NEAR(got.y, want.y, tolerance) << what;
    EXPECT_NEAR(got.z, want.z, tolerance) << what;
}

class TextureRender : public ::testing::Test {
protected:
    void SetUp() override {
        // Top row red, green; bottom row blue, white: no two corners alike.
        testing::write_png_file(tmp.path / "corners.png", 2, 2, 3, 8, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255});
    }
    TempFolder tmp;
};

TEST_F(TextureRender, ObjQuadShowsEachTexelWhereTheGeometryPutsIt) {
    // Emission textured by map_Ke, no lights: each pixel is the texture at its uv.
    tmp.write("quad.obj", "mtllib quad.mtl\n" + kQuadObj + "usemtl glow\nf 1/1 2/2 3/3 4/4\n");
    tmp.write("quad.mtl", "newmtl glow\nKd 0 0 0\nKe 1 1 1\nmap_Ke corners.png\n");
    tmp.write("s.json",
              R"({"render": {"width": 4, "height": 4}, )" + kCamera + R"(, "objects": [{"file": "quad.obj"}]})");
    const Film film = render_file(tmp.path / "s.json");
    // Pixel (0, 0) sees uv (1/8, 7/8): ¾·¾ of the top-left texel (red), ¼·¾
    // of green (right of it), ¾·¼ of blue (below), ¼·¼ of white; repeat wraps
    // the other way at the edges. Worked out by hand for the four corners:
    expect_near(film.at(0, 0), {0.625f, 0.25f, 0.25f}, 1e-4f, "top left: mostly red");
    expect_near(film.at(3, 0), {0.375f, 0.75f, 0.25f}, 1e-4f, "top right: mostly green");
    expect_near(film.at(0, 3), {0.375f, 0.25f, 0.75f}, 1e-4f, "bottom left: mostly blue");
    expect_near(film.at(3, 3), {0.625f, 0.75f, 0.75f}, 1e-4f, "bottom right: mostly white");
    // And every pixel as the lookup predicts for its uv.
    Texture expected;
    expected.width = expected.height = 2;
    expected.channels = 3;
    expected.texels = {1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i) {
            const Vec2 uv{(static_cast<float>(i) + 0.5f) / 4, 1 - (static_cast<float>(j) + 0.5f) / 4};
            expect_near(film.at(i, j), rgb_of(eval_texture(expected, uv)), 1e-4f,
                        "pixel " + std::to_string(i) + ", " + std::to_string(j));
        }
    // Light sampling reads the same texture at a sampled point: (0.6, −0.4)
    // on the first triangle of the fan is uv (0.8, 0.3).
    Diagnostics diag;
    const Scene scene = load_scene_file(tmp.path / "s.json", diag).scene;
    ASSERT_EQ(scene.geometry.triangle_count(), 2u);
    const Material& glow = scene.materials[scene.geometry.material_ids[0]];
    expect_near(emission_at(scene, glow, 0, {0.6f, -0.4f, 0.0f}), rgb_of(eval_texture(expected, {0.8f, 0.3f})), 1e-5f,
                "emission at a sampled point");
}

TEST_F(TextureRender, TexturedKdScalesTheLitImageByTheTexture) {
    tmp.write("quad.obj", kQuadObj + "f 1/1 2/2 3/3 4/4\n");
    const auto scene = [&](const std::string& kd) {
        return R"({"render": {"width": 4, "height": 4}, )" + kCamera +
               R"(, "materials": {"m": {"type": "diffuse", "kd": )" + kd +
               R"(}}, "lights": [{"position": [0.3, 0.2, 2], "intensity": [5, 5, 5]}],
                  "objects": [{"file": "quad.obj", "material": "m"}]})";
    };
    tmp.write("plain.json", scene("[1, 1, 1]"));
    tmp.write("textured.json", scene(R"({"texture": "corners.png", "scale": [0.5, 1, 1]})"));
    const Film plain = render_file(tmp.path / "plain.json");
    const Film textured = render_file(tmp.path / "textured.json");
    const Vec3 top_left = textured.at(0, 0) / plain.at(0, 0).x;
    expect_near(top_left, {0.5f * 0.625f, 0.25f, 0.25f}, 1e-4f, "top left, red channel scaled by 0.5");
    const Vec3 bottom_left = textured.at(0, 3) / plain.at(0, 3).x;
    expect_near(bottom_left, {0.5f * 0.375f, 0.25f, 0.75f}, 1e-4f, "bottom left");
}

// The tangent-space normal (0.36, −0.48, 0.8) as a 16-bit normal map, and
// what the renderer reads back from it.
// NOLINTNEXTLINE(bugprone-incorrect-roundings): constexpr, which std::lround is not; n >= -1, so never negative
constexpr std::uint16_t code(float n) { return static_cast<std::uint16_t>((n + 1) * 0.5f * 65535 + 0.5f); }
Vec3 decoded_normal() {
    const auto back = [](float n) { return 2 * static_cast<float>(code(n)) / 65535 - 1; };
    return normalize(Vec3{back(0.36f), back(-0.48f), back(0.8f)});
}

TEST_F(TextureRender, ConstantNormalMapShadesLikeAPlaneWithThatNormal) {
    testing::write_png_file(tmp.path / "n.png", 1, 1, 3, 16, {code(0.36f), code(-0.48f), code(0.8f)});
    // On this quad dp/du = +x, dp/dv = +y and the front normal +z: tangent space is world space.
    tmp.write("mapped.obj", kQuadObj + "f 1/1 2/2 3/3 4/4\n");
    const Vec3 n = decoded_normal();
    char normal_line[128];
    std::snprintf(normal_line, sizeof normal_line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
    tmp.write("tilted.obj",
              "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\n" + std::string(normal_line) + "f 1//1 2//1 3//1 4//1\n");
    const auto scene = [&](const std::string& file, const std::string& extra) {
        return R"({"render": {"width": 8, "height": 8}, )" + kCamera +
               R"(, "materials": {"m": {"type": "phong", "kd": [0.5, 0.5, 0.5], "ks": [0.4, 0.4, 0.4], "shininess": 20)" +
               extra + R"(}}, "lights": [{"position": [0.5, 0.8, 1.5], "intensity": [4, 4, 4]}],
                  "objects": [{"file": ")" +
               file + R"(", "material": "m"}]})";
    };
    tmp.write("mapped.json", scene("mapped.obj", R"(, "normal_map": "n.png")"));
    tmp.write("tilted.json", scene("tilted.obj", ""));
    tmp.write("flat.json", scene("mapped.obj", ""));
    const Film mapped = render_file(tmp.path / "mapped.json");
    const Film tilted = render_file(tmp.path / "tilted.json");
    const Film flat = render_file(tmp.path / "flat.json");
    float largest_difference_from_flat = 0;
    for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 8; ++i) {
            const Vec3 want = tilted.at(i, j);
            expect_near(mapped.at(i, j), want, 1e-5f + 1e-4f * max_component(want),
                        "pixel " + std::to_string(i) + ", " + std::to_string(j));
            largest_difference_from_flat =
                std::max(largest_difference_from_flat, max_component(abs(flat.at(i, j) - want)));
        }
    EXPECT_GT(largest_difference_from_flat, 0.01f) << "the tilt must show, or this test proves nothing";
}

TEST_F(TextureRender, NormalMapsAreIgnoredOnFacesWithoutUvs) {
    testing::write_png_file(tmp.path / "n.png", 1, 1, 3, 16, {code(0.36f), code(-0.48f), code(0.8f)});
    tmp.write("bare.obj", "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n");
    const auto scene = [&](const std::string& extra) {
        return R"({"render": {"width": 4, "height": 4}, )" + kCamera +
               R"(, "materials": {"m": {"type": "diffuse", "kd": [0.5, 0.5, 0.5])" + extra +
               R"(}}, "lights": [{"position": [0.5, 0.8, 1.5], "intensity": [4, 4, 4]}],
                  "objects": [{"file": "bare.obj", "material": "m"}]})";
    };
    tmp.write("mapped.json", scene(R"(, "normal_map": "n.png")"));
    tmp.write("flat.json", scene(""));
    const Film mapped = render_file(tmp.path / "mapped.json");
    const Film flat = render_file(tmp.path / "flat.json");
    EXPECT_EQ(mapped.rgb, flat.rgb);
}

TEST(Shading, NormalAndBumpMapsTiltAsTheirFramesSay) {
    const Vec3 z{0, 0, 1};
    // Flat normal-map value: the normal itself, whatever the frame.
    expect_near(apply_normal_map(z, {2, 0, 0}, {0, 3, 0}, z), z, 1e-6f, "flat");
    // +x of the map along dp/du, +y along dp/dv, orthonormalised against n.
    const Vec3 n = normalize(Vec3{0.6f, 0.0f, 0.8f});
    expect_near(apply_normal_map(z, {1, 0, 0.5f}, {0, 1, 0}, n), n, 1e-6f, "dp/du tilted out of the plane");
    expect_near(apply_normal_map(z, {0, 1, 0}, {-1, 0, 0}, n), Vec3{0, 0.6f, 0.8f}, 1e-6f, "rotated frame");
    expect_near(apply_normal_map(z, {1, 0, 0}, {0, -1, 0}, Vec3{0, 0.6f, 0.8f}), Vec3{0, -0.6f, 0.8f}, 1e-6f,
                "v running down the surface");
    // Degenerate uvs leave the normal alone.
    expect_near(apply_normal_map(z, {0, 0, 1}, {0, 1, 0}, n), z, 0.0f, "dp/du along n");
    // A height rising along u by 1 per unit of u: the normal leans back, to −x.
    expect_near(apply_bump(z, {1, 0, 0}, {0, 1, 0}, 1, 0), normalize(Vec3{-1, 0, 1}), 1e-6f, "bump along u");
    expect_near(apply_bump(z, {1, 0, 0}, {0, 1, 0}, 0, -0.5f), normalize(Vec3{0, 0.5f, 1}), 1e-6f, "bump along v");
    expect_near(apply_bump(z, {2, 0, 0}, {0, 2, 0}, 0, 0), z, 1e-6f, "flat height");
}

}  // namespace
}  // namespace sombra
