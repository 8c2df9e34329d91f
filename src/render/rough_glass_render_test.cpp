// Frosted glass through the whole pipeline: a glTF slab with
// KHR_materials_transmission and KHR_materials_volume in front of an
// emissive checkerboard, rendered at increasing roughness. Rough refraction
// (Walter et al.) spreads each pixel's rays over the board, so the checker
// seen through the slab must blur more, its contrast fall, as the roughness
// grows; smooth, the slab shows it sharp (a delta refraction).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "io/gltf/gltf_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

constexpr int kSize = 48;
constexpr float kTan = 0.25f;     // the camera's tan(half field of view), at z = 5 looking down −z
constexpr float kBoardZ = -4.0f;  // the checkerboard's plane
constexpr float kSquare = 0.8f;   // its squares' side
constexpr float kSlabFront = 1.0f, kSlabBack = 0.5f;

// A quad (a, b, c, d) as two triangles of `index`, counter-clockwise as given.
void add_quad(std::vector<Vec3>& p, std::vector<std::uint32_t>& index, Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
    const auto base = static_cast<std::uint32_t>(p.size());
    p.insert(p.end(), {a, b, c, d});
    index.insert(index.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// The slab (a closed box [−6, 6]² × [kSlabBack, kSlabFront], wound
// outwards) of material 0 and the board's bright squares (facing +z,
// emitting 1) of material 1.
GltfFile scene_file(float roughness) {
    GltfFile f;
    std::vector<Vec3> p;
    std::vector<std::uint32_t> index;
    const float s = 6.0f;
    const Vec3 a{-s, -s, kSlabBack}, b{s, -s, kSlabBack}, c{s, s, kSlabBack}, e{-s, s, kSlabBack};
    const Vec3 up{0, 0, kSlabFront - kSlabBack};
    add_quad(p, index, a + up, b + up, c + up, e + up);
    add_quad(p, index, a, e, c, b);
    add_quad(p, index, a, b, b + up, a + up);
    add_quad(p, index, b, c, c + up, b + up);
    add_quad(p, index, c, e, e + up, c + up);
    add_quad(p, index, e, a, a + up, e + up);
    f.add_mesh({{"POSITION", f.add_positions(p)}}, f.add_indices(index), 0);
    p.clear();
    index.clear();
    for (int y = -6; y < 6; ++y)
        for (int x = -6; x < 6; ++x) {
            if ((x + y) % 2 != 0) continue;
            const float x0 = float(x) * kSquare, y0 = float(y) * kSquare, x1 = x0 + kSquare, y1 = y0 + kSquare;
            add_quad(p, index, {x0, y0, kBoardZ}, {x1, y0, kBoardZ}, {x1, y1, kBoardZ}, {x0, y1, kBoardZ});
        }
    f.add_mesh({{"POSITION", f.add_positions(p)}}, f.add_indices(index), 1);
    nlohmann::json glass = {
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {1, 1, 1, 1}}, {"metallicFactor", 0}, {"roughnessFactor", roughness}}}};
    glass["extensions"]["KHR_materials_transmission"] = {{"transmissionFactor", 1}};
    glass["extensions"]["KHR_materials_volume"] = {{"thicknessFactor", kSlabFront - kSlabBack}};
    const nlohmann::json light = {{"pbrMetallicRoughness", {{"baseColorFactor", {0, 0, 0, 1}}}},
                                  {"emissiveFactor", {1, 1, 1}}};
    f.doc["materials"] = {glass, light};
    f.use_extension("KHR_materials_transmission");
    f.use_extension("KHR_materials_volume");
    f.set_scene({f.add_node({{"mesh", 0}}), f.add_node({{"mesh", 1}})});
    return f;
}

Film render_slab(const TempFolder& dir, float roughness) {
    scene_file(roughness).save(dir.path / "slab.gltf");
    const std::string l = std::to_string(-kTan), u = std::to_string(kTan);
    dir.write("slab.json", R"({"render": {"width": 48, "height": 48, "spp": 64, "seed": 5, "integrator": "path",
        "max_depth": 8}, "background": [0, 0, 0],
        "camera": {"origin": [0, 0, 5], "left": [)" +
                               l + R"(, 0, 0], "up": [0, )" + u + R"(, 0], "forward": [0, 0, -1]},
        "objects": [{"file": "slab.gltf"}]})");
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(dir.path / "slab.json", diag);
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(loaded.scene, accel, loaded.settings, 2);
    RenderProgress progress;
    return render_image(job, progress).film;
}

// +1 where the ray through pixel (i, j)'s centre would meet a bright
// square with no slab in the way, −1 on a dark one (the slab only shifts
// rays sideways, by at most 0.04 here, a twentieth of a square).
double checker_sign(int i, int j) {
    const double s = 1.0 - (2.0 * i + 1) / kSize, t = 1.0 - (2.0 * j + 1) / kSize;
    const double distance = 5.0 - kBoardZ;
    const double x = -kTan * s * distance, y = kTan * t * distance;
    const auto cell = [](double v) { return static_cast<long>(std::floor(v / kSquare)); };
    return (cell(x) + cell(y)) % 2 == 0 ? 1.0 : -1.0;
}

TEST(RoughGlassRender, TheCheckerBlursMoreWithRoughness) {
    // The board's contrast as seen: the image's correlation with the sharp
    // checker over its mean, mean(I·sign)/mean(I). Linear in the pixels, so
    // the noise of 64 samples averages out over the 2304 pixels rather than
    // adding contrast, as a standard deviation would.
    TempFolder dir;
    std::vector<double> contrast;
    for (const float roughness : {0.0f, 0.2f, 0.3f, 0.4f}) {
        const Film film = render_slab(dir, roughness);
        double signed_sum = 0, sum = 0;
        for (int j = 0; j < kSize; ++j)
            for (int i = 0; i < kSize; ++i) {
                const double v = film.at(i, j).y;
                ASSERT_TRUE(std::isfinite(v));
                signed_sum += v * checker_sign(i, j);
                sum += v;
            }
        ASSERT_GT(sum, 0.0);
        contrast.push_back(signed_sum / sum);
        std::printf("roughness %.1f: mean %.4f, contrast %.4f\n", roughness, sum / (kSize * kSize), contrast.back());
    }
    // Smooth, the board is seen sharp: only the pixels on squares' edges (a
    // quarter of them, the slab shifting rays by half a pixel) mix.
    EXPECT_GT(contrast[0], 0.7);
    for (std::size_t k = 1; k < contrast.size(); ++k) EXPECT_LT(contrast[k], contrast[k - 1]) << k;
    EXPECT_LT(contrast.back(), 0.5 * contrast[0]);
}

}  // namespace
}  // namespace sombra
