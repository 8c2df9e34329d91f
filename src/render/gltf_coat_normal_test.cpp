// KHR_materials_clearcoat's clearcoatNormalTexture through the whole
// pipeline (spec §24): resolve_material gives the coat its own normal
// (si.n_c) from that texture, with its scale and texCoord, in the mesh's
// tangent frame as the base's normal map, or the surface's normal without
// the base's map when the coat has none; and a rendered quad whose black
// base carries a strong normal map shows the smooth coat's reflection of an
// emitter exactly where a flat mirror puts it, pixel by pixel, while a coat
// normal map moves it where the mapped mirror puts it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "io/gltf/gltf_test_files.h"
#include "io/images/image_test_files.h"
#include "io/polygon_test_files.h"
#include "io/scene_json/scene_file.h"
#include "render/camera.h"
#include "render/interaction.h"
#include "render/render.h"
#include "render/shading.h"

namespace sombra {
namespace {

using gltf_test::GltfFile;
using testing::TempFolder;

// The tangent-space normal (0.36, −0.48, 0.8) as 16-bit texels.
// NOLINTNEXTLINE(bugprone-incorrect-roundings): constexpr, which std::lround is not; n >= -1, so never negative
constexpr std::uint16_t code(float n) { return static_cast<std::uint16_t>((n + 1) * 0.5f * 65535 + 0.5f); }
Vec3 decoded(float scale) {
    const auto back = [](float n) { return 2 * static_cast<float>(code(n)) / 65535 - 1; };
    return normalize(Vec3{back(0.36f) * scale, back(-0.48f) * scale, back(0.8f)});
}

// The 2×2 quad in z = 0 facing +z, uvs putting the tangent along +x and the
// bitangent along +y (TEXCOORD_0 and TEXCOORD_1 alike), with `material`;
// image 0 (n.png) is texture 0.
GltfFile coat_quad(const nlohmann::json& material, bool second_set = true) {
    GltfFile f;
    nlohmann::json attributes = {{"POSITION", f.add_positions({{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}})},
                                 {"NORMAL", f.add_normals(std::vector<Vec3>(4, Vec3{0, 0, 1}))},
                                 {"TEXCOORD_0", f.add_uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}})}};
    if (second_set) attributes["TEXCOORD_1"] = f.add_uvs({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
    f.add_mesh(attributes, f.add_indices({0, 1, 2, 0, 2, 3}), 0);
    f.doc["materials"] = {material};
    f.doc["images"] = {{{"uri", "n.png"}}};
    f.doc["textures"] = {{{"source", 0}}};
    f.use_extension("KHR_materials_clearcoat");
    f.use_extension("KHR_materials_specular");
    f.add_node({{"mesh", 0}});
    f.set_scene({0});
    return f;
}

// A black base (no diffuse, no dielectric reflection: specularFactor 0)
// under a smooth full coat; `base_map` puts n.png on the base,
// `coat_info` (if not null) is the clearcoatNormalTexture.
nlohmann::json material(bool base_map, const nlohmann::json& coat_info) {
    nlohmann::json m = {{"pbrMetallicRoughness",
                         {{"baseColorFactor", {0, 0, 0, 1}}, {"metallicFactor", 0}, {"roughnessFactor", 0.5}}},
                        {"extensions",
                         {{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}, {"clearcoatRoughnessFactor", 0.0}}},
                          {"KHR_materials_specular", {{"specularFactor", 0.0}}}}}};
    if (base_map) m["normalTexture"] = {{"index", 0}};
    if (!coat_info.is_null()) m["extensions"]["KHR_materials_clearcoat"]["clearcoatNormalTexture"] = coat_info;
    return m;
}

// The emitter: x in [0.4, 1.2], y in [−0.4, 0.4] at z = 2, radiance 10.
constexpr float kEmitterZ = 2, kRadiance = 10;
bool on_emitter(Vec3 o, Vec3 d) {
    if (!(d.z > 0.0f)) return false;
    const float t = (kEmitterZ - o.z) / d.z;
    const float x = o.x + t * d.x, y = o.y + t * d.y;
    return x >= 0.4f && x <= 1.2f && y >= -0.4f && y <= 0.4f;
}

class GltfCoatNormal : public ::testing::Test {
protected:
    void SetUp() override {
        testing::write_png_file(dir.path / "n.png", 1, 1, 3, 16, {code(0.36f), code(-0.48f), code(0.8f)});
        dir.write("light.obj", "v 0.4 -0.4 2\nv 1.2 -0.4 2\nv 1.2 0.4 2\nv 0.4 0.4 2\nf 1 2 3 4\n");
    }
    LoadedScene load(const GltfFile& f, std::size_t* warnings = nullptr) {
        f.save(dir.path / "q.gltf");
        dir.write("s.json", R"({"render": {"width": 48, "height": 48, "spp": 16, "integrator": "path", "max_depth": 3},
            "camera": {"origin": [0, 0, 3], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov": 40},
            "materials": {"lamp": {"type": "diffuse", "kd": [0, 0, 0], "ke": [10, 10, 10]}},
            "objects": [{"file": "q.gltf"}, {"file": "light.obj", "material": "lamp"}]})");
        Diagnostics diag;
        LoadedScene loaded = load_scene_file(dir.path / "s.json", diag);
        if (warnings) *warnings = diag.warnings.size();
        return loaded;
    }
    // The hit straight down at (x, y), resolved.
    SurfaceInteraction resolved(const Scene& scene, float x, float y) {
        const Accel accel = make_accel(scene.geometry, AccelKind::Bvh);
        const Ray ray{{x, y, 1}, {0, 0, -1}};
        Hit hit;
        EXPECT_TRUE(intersect(accel, ray, hit));
        SurfaceInteraction si = make_surface_interaction(scene.geometry, ray, hit);
        Material scratch;
        resolve_material(scene, si, scratch);
        return si;
    }
    TempFolder dir;
};

void expect_near(Vec3 got, Vec3 want, const std::string& what) {
    EXPECT_NEAR(got.x, want.x, 1e-5f) << what;
    EXPECT_NEAR(got.y, want.y, 1e-5f) << what;
    EXPECT_NEAR(got.z, want.z, 1e-5f) << what;
}

TEST_F(GltfCoatNormal, TheCoatGetsItsOwnNormalOrNone) {
    std::size_t warnings = 0;
    // The base's map alone: the coat keeps the unmapped normal.
    SurfaceInteraction si = resolved(load(coat_quad(material(true, nullptr)), &warnings).scene, 0.3f, -0.2f);
    expect_near(si.n_s, decoded(1), "base map");
    expect_near(si.n_c, Vec3{0, 0, 1}, "coat without a map");
    EXPECT_EQ(warnings, 0u);
    // The coat's map alone, with its scale and on TEXCOORD_1: the base stays flat.
    si = resolved(load(coat_quad(material(false, {{"index", 0}, {"scale", 0.3}, {"texCoord", 1}}))).scene, 0.3f, -0.2f);
    expect_near(si.n_s, Vec3{0, 0, 1}, "base without a map");
    expect_near(si.n_c, decoded(0.3f), "coat map, scale 0.3");
    // Both maps, the coat's flattened to its scale 0.
    si = resolved(load(coat_quad(material(true, {{"index", 0}, {"scale", 0.0}}))).scene, 0.3f, -0.2f);
    expect_near(si.n_s, decoded(1), "base map");
    expect_near(si.n_c, Vec3{0, 0, 1}, "coat map, scale 0");
    // KHR_texture_transform's texCoord override naming a set the mesh lacks:
    // no coat map, so the coat shares the unmapped n_s (n_c zero).
    nlohmann::json info = {{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}};
    GltfFile lacking = coat_quad(material(false, info), false);
    lacking.use_extension("KHR_texture_transform");
    si = resolved(load(lacking).scene, 0.3f, -0.2f);
    EXPECT_EQ(si.n_c, Vec3{});
    // No maps: nothing to tell apart.
    si = resolved(load(coat_quad(material(false, nullptr))).scene, 0.3f, -0.2f);
    EXPECT_EQ(si.n_c, Vec3{});
}

// What a rendered image says against a mirror about the normal `n`: pixels
// whose every part reflects onto the emitter (lit) or wholly off it (dark),
// those that disagree (a dark one not exactly 0, a lit one below half of
// k·F_c·L_e or not grey), and the lit ones' mean over k·F_c·L_e. The coat is
// chosen with probability 0.9 (the base is black), so a lit pixel's value
// is binomial around k·F_c·L_e: its mean over many is tested, not each.
struct MirrorCheck {
    int lit = 0, dark = 0, wrong = 0;
    double mean_ratio = 0;
};

MirrorCheck check_mirror(const Film& film, const Camera& camera, Vec3 n) {
    MirrorCheck out;
    for (int j = 0; j < film.height; ++j)
        for (int i = 0; i < film.width; ++i) {
            // A 5 × 5 grid over the pixel and a quarter pixel around it.
            int on = 0;
            for (int a = 0; a < 5; ++a)
                for (int b = 0; b < 5; ++b) {
                    const float x = static_cast<float>(i) - 0.25f + 0.375f * static_cast<float>(a);
                    const float y = static_cast<float>(j) - 0.25f + 0.375f * static_cast<float>(b);
                    const Ray r = camera_ray(camera, image_plane_s(x, film.width), image_plane_t(y, film.height));
                    const Vec3 d = normalize(r.dir);
                    const Vec3 p = r.origin + (-r.origin.z / d.z) * d;
                    const bool quad = std::fabs(p.x) < 1.0f && std::fabs(p.y) < 1.0f;
                    on += quad && on_emitter(p, d - 2.0f * dot(d, n) * n) ? 1 : 0;
                }
            const Vec3 c = film.at(i, j);
            if (on == 25) {
                const Ray r = camera_ray(camera, image_plane_s(static_cast<float>(i) + 0.5f, film.width),
                                         image_plane_t(static_cast<float>(j) + 0.5f, film.height));
                const float cos_o = -dot(normalize(r.dir), n);
                const double expected = kRadiance * (0.04 + 0.96 * std::pow(1.0 - cos_o, 5.0));
                out.wrong += c.x < 0.5 * expected || c.x != c.z ? 1 : 0;
                out.mean_ratio += c.x / expected;
                ++out.lit;
            } else if (on == 0) {
                out.wrong += c == Vec3{0.0f} ? 0 : 1;
                ++out.dark;
            }
        }
    if (out.lit > 0) out.mean_ratio /= out.lit;
    return out;
}

// `loaded` rendered, and its camera.
Film render(const LoadedScene& loaded, Camera& camera) {
    const Accel accel = make_accel(loaded.scene, AccelKind::Bvh);
    RenderProgress progress;
    Film film = render_image(make_render_job(loaded.scene, accel, loaded.settings, 1), progress).film;
    camera = make_camera(loaded.scene.camera, film.width, film.height);
    return film;
}

TEST_F(GltfCoatNormal, AFlatCoatOverABumpyBaseMirrorsLikeAFlatMirror) {
    Camera camera;
    const Film film = render(load(coat_quad(material(true, nullptr))), camera);
    const MirrorCheck flat = check_mirror(film, camera, Vec3{0, 0, 1});
    EXPECT_GT(flat.lit, 40);
    EXPECT_GT(flat.dark, 1000);
    EXPECT_EQ(flat.wrong, 0);
    // 16 samples a pixel, each 0.9 likely to find the emitter at weight
    // 1/0.9: over 40+ pixels the mean ratio's σ is under 1.2 %; 5σ.
    EXPECT_NEAR(flat.mean_ratio, 1.0, 0.06);
}

TEST_F(GltfCoatNormal, TheCoatsOwnMapMovesTheReflection) {
    Camera camera;
    const Film film = render(load(coat_quad(material(false, {{"index", 0}, {"scale", 0.3}}))), camera);
    const MirrorCheck mapped = check_mirror(film, camera, decoded(0.3f));
    EXPECT_GT(mapped.lit, 40);
    EXPECT_GT(mapped.dark, 1000);
    EXPECT_EQ(mapped.wrong, 0);
    EXPECT_NEAR(mapped.mean_ratio, 1.0, 0.06);
    // Not where the flat mirror would put it.
    EXPECT_GT(check_mirror(film, camera, Vec3{0, 0, 1}).wrong, 20);
}

}  // namespace
}  // namespace sombra
