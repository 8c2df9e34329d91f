// KHR_materials_sheen through the whole pipeline: a glTF sphere of a dark
// rough base, with and without a white sheen, in a white furnace (the path
// integrator's constant background of radiance 1, direct light only). There
// the sheen lobe alone returns its albedo E(cos θ_o) at every pixel, so the
// rim, seen at grazing angles where E is large, must brighten by about E
// while the centre, seen head on where E is ~0, must not change.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "io/gltf/gltf_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/bsdf/sheen.h"
#include "render/render.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

constexpr int kSize = 48;
constexpr float kTan = 0.25f;  // the camera's tan(half field of view)
constexpr float kSheenRoughness = 0.5f;

// A unit sphere at the origin, 96 × 48 quads in longitude and latitude,
// with its exact normals, and `material`.
GltfFile sphere(const nlohmann::json& material) {
    constexpr int nu = 96, nv = 48;
    std::vector<Vec3> p;
    std::vector<std::uint32_t> index;
    for (int j = 0; j <= nv; ++j)
        for (int i = 0; i <= nu; ++i) {
            const float theta = std::numbers::pi_v<float> * float(j) / nv;
            const float phi = 2 * std::numbers::pi_v<float> * float(i) / nu;
            p.push_back({std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)});
        }
    for (int j = 0; j < nv; ++j)
        for (int i = 0; i < nu; ++i) {
            const auto at = [](int a, int b) { return static_cast<std::uint32_t>(b * (nu + 1) + a); };
            for (const std::uint32_t k :
                 {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i + 1, j)})
                index.push_back(k);
        }
    GltfFile f;
    f.add_mesh({{"POSITION", f.add_positions(p)}, {"NORMAL", f.add_normals(p)}}, f.add_indices(index), 0);
    f.doc["materials"] = {material};
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    return f;
}

Film render_sphere(const TempFolder& dir, const nlohmann::json& material) {
    GltfFile f = sphere(material);
    f.use_extension("KHR_materials_sheen");
    f.save(dir.path / "s.gltf");
    const std::string l = std::to_string(-kTan), u = std::to_string(kTan);
    dir.write("s.json", R"({"render": {"width": 48, "height": 48, "spp": 64, "seed": 3, "integrator": "path",
        "max_depth": 1}, "background": [1, 1, 1],
        "camera": {"origin": [0, 0, 5], "left": [)" +
                            l + R"(, 0, 0], "up": [0, )" + u + R"(, 0], "forward": [0, 0, -1]},
        "objects": [{"file": "s.gltf"}]})");
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(dir.path / "s.json", diag);
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(loaded.scene, accel, loaded.settings, 2);
    RenderProgress progress;
    return render_image(job, progress).film;
}

// cos θ_o where the ray through image point (s, t) meets the unit sphere;
// −1 for a miss, or for a ray within 1% of the silhouette (whose samples
// the tessellation may let through to the background).
float view_cosine(float s, float t) {
    const Vec3 d = normalize(Vec3{-kTan * s, kTan * t, -1});
    const Vec3 o{0, 0, 5};
    const float b = dot(o, d);
    if (b * b - (dot(o, o) - 0.99f * 0.99f) < 0.0f) return -1.0f;
    const Vec3 x = o + (-b - std::sqrt(b * b - (dot(o, o) - 1.0f))) * d;
    return dot(normalize(x), -d);
}

// The smallest view cosine over pixel (i, j)'s corners and centre: where all
// its samples meet the sphere, how grazing the most grazing one is.
float pixel_cosine(int i, int j) {
    float c = 2.0f;
    for (const float di : {0.0f, 0.5f, 1.0f})
        for (const float dj : {0.0f, 0.5f, 1.0f}) {
            const float v = view_cosine(1.0f - 2.0f * (float(i) + di) / kSize, 1.0f - 2.0f * (float(j) + dj) / kSize);
            c = v < 0.0f ? -1.0f : std::min(c, v);
            if (c < 0.0f) return c;
        }
    return c;
}

TEST(SheenRender, ASheenBrightensTheGrazingRimByItsAlbedo) {
    TempFolder dir;
    const nlohmann::json base = {
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {0.05, 0.05, 0.05, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.8}}}};
    nlohmann::json velvet = base;
    velvet["extensions"]["KHR_materials_sheen"] = {{"sheenColorFactor", {1, 1, 1}},
                                                   {"sheenRoughnessFactor", kSheenRoughness}};
    const Film plain = render_sphere(dir, base), sheen = render_sphere(dir, velvet);
    // Per region: the mean of each image and the bounds on the gain.
    struct Region {
        int pixels = 0;
        double plain = 0, sheen = 0, albedo = 0, gain_low = 0, gain_high = 0;
    } rim, centre;
    for (int j = 0; j < kSize; ++j)
        for (int i = 0; i < kSize; ++i) {
            const float c = pixel_cosine(i, j);
            if (c < 0.0f || (c >= 0.35f && c <= 0.9f)) continue;
            Region& r = c < 0.35f ? rim : centre;
            const double e =
                sheen_albedo(view_cosine(1.0f - (2.0f * float(i) + 1) / kSize, 1.0f - (2.0f * float(j) + 1) / kSize),
                             kSheenRoughness);
            const double p = plain.at(i, j).y;
            ++r.pixels;
            r.plain += p;
            r.sheen += sheen.at(i, j).y;
            r.albedo += e;
            r.gain_low += e - p;
            r.gain_high += e * (1.0 - p);
        }
    for (Region* r : {&rim, &centre}) {
        ASSERT_GT(r->pixels, 50);
        for (double* x : {&r->plain, &r->sheen, &r->albedo, &r->gain_low, &r->gain_high}) *x /= r->pixels;
    }
    std::printf("rim: plain %.4f sheen %.4f (mean E %.4f, %d px); centre: plain %.4f sheen %.4f (mean E %.4f, %d px)\n",
                rim.plain, rim.sheen, rim.albedo, rim.pixels, centre.plain, centre.sheen, centre.albedo, centre.pixels);
    // In the furnace the sheen returns E(cos θ_o) and leaves the base at
    // most 1 − E of its share, at least nothing: per pixel the gain lies in
    // [E − plain, E·(1 − plain)], E at the pixel's centre (10% and 0.01
    // allowed for E's change across a pixel and the noise of 64 samples).
    for (const Region* r : {&rim, &centre}) {
        EXPECT_GT(r->sheen - r->plain, 0.9 * r->gain_low - 0.01) << (r == &rim ? "rim" : "centre");
        EXPECT_LT(r->sheen - r->plain, 1.1 * r->gain_high + 0.01) << (r == &rim ? "rim" : "centre");
    }
    // The rim brightens by a larger factor than the centre.
    EXPECT_GT(rim.sheen / rim.plain, 1.5 * centre.sheen / centre.plain);
}

}  // namespace
}  // namespace sombra
