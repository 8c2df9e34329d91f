// Mip-mapping by ray footprint (--texture-filter mipmap, render/ray_cone.h)
// through the whole renderer. A camera looks straight at an emissive quad
// whose texture's levels are painted with their own index, so that each
// pixel shows the level of detail λ its sample chose; λ is predicted by hand
// from the pixel's size, the distance, the quad's size and texel count, and
// the sample's angle off the axis, directly and through a mirror. A far-away
// checkerboard is its mean grey at one sample per pixel with mip-mapping and
// black-and-white without. With the option off, or with every footprint
// under a texel, the image is the bilinear one bit for bit; with it on, the
// same for any thread count, and explain's re-traced samples are the render's.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "render/render.h"
#include "render/test_meshes.h"
#include "scene/texture_mipmap.h"

namespace sombra {
namespace {

// A square quad of side `side` centred at `centre`, spanned by the unit
// vectors u_dir and v_dir, with uv (0, 0) at centre − (u_dir + v_dir)·side/2
// and uv (1, 1) at the opposite corner.
void add_uv_quad(Scene& scene, Vec3 centre, Vec3 u_dir, Vec3 v_dir, float side, std::uint32_t material) {
    TriangleMesh& m = scene.geometry;
    const Vec3 du = u_dir * (0.5f * side), dv = v_dir * (0.5f * side);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    const auto uv_base = static_cast<std::uint32_t>(m.uvs.size());
    m.positions.insert(m.positions.end(), {centre - du - dv, centre + du - dv, centre + du + dv, centre - du + dv});
    m.uvs.insert(m.uvs.end(), {Vec2{0, 0}, Vec2{1, 0}, Vec2{1, 1}, Vec2{0, 1}});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
    m.uv_indices.push_back({uv_base, uv_base + 1, uv_base + 2});
    m.uv_indices.push_back({uv_base, uv_base + 2, uv_base + 3});
    m.material_ids.insert(m.material_ids.end(), {material, material});
}

// An n × n grey texture whose mip pyramid is built and then painted: the
// full-resolution texels read 0 and every texel of level l reads l, so that
// a trilinear lookup at λ (between 0 and the coarsest level) reads λ itself.
Texture level_coded_texture(int n) {
    Texture t;
    t.source = "levels";
    t.encoding = TextureEncoding::Data;
    t.width = t.height = n;
    t.channels = 1;
    t.texels.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(n), 0.0f);
    build_mip_pyramid(t);
    for (std::size_t l = 0; l < t.mip_levels.size(); ++l)
        for (float& v : t.mip_levels[l].texels) v = static_cast<float>(l + 1);
    return t;
}

// An n × n checkerboard of black and white squares `check` texels wide.
Texture checkerboard(int n, int check) {
    Texture t;
    t.source = "checks";
    t.encoding = TextureEncoding::Data;
    t.width = t.height = n;
    t.channels = 1;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) t.texels.push_back(static_cast<float>((x / check + y / check) % 2));
    return t;
}

// A material that emits its texture (ke = texel) and reflects nothing: a
// pixel that sees it shows the texel.
Material glowing_texture() {
    Material m;
    m.name = "glow";
    m.kd = Vec3{0.0f};
    m.ke = Vec3{1.0f};
    m.textures.ke.texture = 0;
    m.textured = true;
    return m;
}

// A scene whose camera sits at the origin looking down −z; its image plane
// at distance 1 is 2·half_view wide and high.
Scene camera_scene(float half_view, Texture texture) {
    Scene scene;
    scene.camera.basis = CameraBasis{Vec3{0.0f}, Vec3{-half_view, 0, 0}, Vec3{0, half_view, 0}, Vec3{0, 0, -1}};
    scene.materials.push_back(glowing_texture());
    scene.textures.push_back(std::move(texture));
    return scene;
}

void finish(Scene& scene) {
    scene.objects = {SceneObject{"everything", "", 0, static_cast<std::uint32_t>(scene.geometry.triangle_count())}};
}

RenderSettings settings(int size, int spp, IntegratorKind integrator, TextureFilter filter) {
    RenderSettings s{size, size, spp, 7};
    s.integrator = integrator;
    s.texture_filter = filter;
    return s;
}

Film render(const Scene& scene, const RenderSettings& s, int threads = 1) {
    const Accel accel = make_accel(scene.geometry, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, s, threads);
    RenderProgress progress;
    return render_image(job, progress).film;
}

// Every pixel's sample re-traced as `sombra explain` does, its value equal
// to the film's (one sample per pixel), and the λ that `predicted` says for
// its camera ray (image-plane s, t) within `tolerance`.
template <class Predict>
void expect_levels(const Scene& scene, const RenderSettings& s, Predict predicted, float tolerance) {
    const Film film = render(scene, s);
    const Accel accel = make_accel(scene.geometry, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, s, 1);
    for (int j = 0; j < s.height; ++j)
        for (int i = 0; i < s.width; ++i) {
            SampleRecord record;
            RayCounters counters;
            const Vec3 value = trace_pixel_sample(job, i, j, 0, counters, record);
            const std::string where = "pixel " + std::to_string(i) + ", " + std::to_string(j);
            EXPECT_EQ(value.x, film.at(i, j).x) << where << ": explain's sample is the render's";
            EXPECT_NEAR(value.x, predicted(record.s, record.t), tolerance) << where;
        }
}

// λ for a camera ray through image-plane point (s, t) of camera_scene that
// meets, `distance` along the axis, a plane facing the camera squarely (or
// its mirror image) that carries `texels` per `side` world units: the cone's
// spread is the pixel's angular size p = 2·half_view/W times cos^{3/2} θ (its
// solid angle shrinks as cos³ θ off the axis), the hit is distance/cos θ away
// and the footprint stretches by 1/cos θ on the plane, so the footprint is
// p·distance/√cos θ world units, texels/side times that in texels.
float predicted_lod(float s, float t, float half_view, int width, float distance, float texels, float side) {
    const double p = 2.0 * half_view / width;
    const double cos_theta = 1.0 / std::sqrt(1.0 + (s * s + t * t) * double{half_view} * half_view);
    return static_cast<float>(std::log2(texels / side * p * distance) - 0.5 * std::log2(cos_theta));
}

TEST(Mipmap, LevelFollowsTheFootprintOfEachPixel) {
    // 90° field of view, 32 × 32 pixels: p = 1/16. A 512-texel quad 8 units
    // wide, 1.75 away: λ = log2(512/8 · 1/16 · 1.75) = log2 7 ≈ 2.807 on the
    // axis, up to ≈ 3.19 in the corners (θ ≈ 54°): levels 2, 3 and 4 blend.
    Scene scene = camera_scene(1.0f, level_coded_texture(512));
    add_uv_quad(scene, {0, 0, -1.75f}, {1, 0, 0}, {0, 1, 0}, 8.0f, 0);
    finish(scene);
    const auto predicted = [](float s, float t) { return predicted_lod(s, t, 1.0f, 32, 1.75f, 512.0f, 8.0f); };
    EXPECT_NEAR(predicted(0, 0), std::log2(7.0f), 1e-6f);
    // Tolerance: float rounding of the cone, the hit distance and log2 at λ ≈ 3, a few ulps.
    expect_levels(scene, settings(32, 1, IntegratorKind::Direct, TextureFilter::Mipmap), predicted, 1e-4f);
    expect_levels(scene, settings(32, 1, IntegratorKind::Path, TextureFilter::Mipmap), predicted, 1e-4f);
}

TEST(Mipmap, MirrorPassesTheConeOn) {
    // A flat mirror at 45° one unit in front of the camera turns its view
    // toward +x, onto the quad 1.5 further on: the quad's mirror image lies
    // squarely 2.5 away, so λ is the direct view's at distance 2.5.
    Scene scene = camera_scene(0.1f, level_coded_texture(512));
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    scene.materials.push_back(mirror);
    const float r = std::sqrt(0.5f);
    add_uv_quad(scene, {0, 0, -1}, {r, 0, -r}, {0, 1, 0}, 1.5f, 1);
    add_uv_quad(scene, {1.5f, 0, -1}, {0, 0, 1}, {0, 1, 0}, 2.0f, 0);
    finish(scene);
    const auto predicted = [](float s, float t) { return predicted_lod(s, t, 0.1f, 17, 2.5f, 512.0f, 2.0f); };
    EXPECT_GT(predicted(0, 0), 2.5f);
    EXPECT_LT(predicted(0, 0), 3.0f);
    // Tolerance: as above, and the bounce's origin moved off the mirror by its rounding bound (~1e-6 of 2.5).
    expect_levels(scene, settings(17, 1, IntegratorKind::Path, TextureFilter::Mipmap), predicted, 1e-4f);
}

TEST(Mipmap, FarCheckerboardIsItsMeanGreyAtOneSamplePerPixel) {
    // 256 texels, checks 4 texels wide, on a quad 2 units wide 8.5 away, seen
    // with p = 1/64: 17 texels per pixel, λ >= 4.09, where every level (from
    // 3 on, 8-texel blocks holding two checks of each colour) is exactly 0.5.
    // (17, not 16, and the quad a little off centre, so that pixel centres do
    // not fall on the checks' edges in step with the pixel grid.)
    Scene scene = camera_scene(0.25f, checkerboard(256, 4));
    add_uv_quad(scene, {0.0123f, 0.0071f, -8.5f}, {1, 0, 0}, {0, 1, 0}, 2.0f, 0);
    finish(scene);
    build_mip_pyramids(scene.textures);
    const Film mipmapped = render(scene, settings(32, 1, IntegratorKind::Direct, TextureFilter::Mipmap));
    const Film bilinear = render(scene, settings(32, 1, IntegratorKind::Direct, TextureFilter::Bilinear));
    // Pixels 9 … 22 see only the quad (|s|, |t| < 1/2.125 there).
    float darkest = 1, brightest = 0;
    for (int j = 9; j <= 22; ++j)
        for (int i = 9; i <= 22; ++i) {
            // 0.5 up to the rounding of the trilinear weights' sum, (1 − f) + f.
            EXPECT_NEAR(mipmapped.at(i, j).x, 0.5f, 1e-6f) << "pixel " << i << ", " << j;
            darkest = std::min(darkest, bilinear.at(i, j).x);
            brightest = std::max(brightest, bilinear.at(i, j).x);
        }
    // Without: each sample sees the one check it lands in, black or white
    // (bilinear blends only within half a texel of a check's edge).
    // (Up to the rounding of the bilinear weights' sums.)
    EXPECT_LT(darkest, 1e-6f);
    EXPECT_GT(brightest, 1.0f - 1e-6f);
}

// A lit scene with every kind of lookup: a diffuse floor textured with
// small checks (minified more and more toward the horizon), the glowing
// texture on a wall behind it, and a mirror; a point light.
Scene lit_scene(int texels) {
    Scene scene = camera_scene(0.3f, checkerboard(texels, 3));
    Material mirror;
    mirror.name = "mirror";
    mirror.type = MaterialType::Mirror;
    scene.materials.push_back(mirror);
    Material floor;
    floor.name = "floor";
    floor.textures.kd.texture = 0;
    floor.textured = true;
    scene.materials.push_back(floor);
    const float r = std::sqrt(0.5f);
    add_uv_quad(scene, {0, -0.4f, -3}, {1, 0, 0}, {0, 0, -1}, 6.0f, 2);
    add_uv_quad(scene, {0, 0.6f, -5}, {1, 0, 0}, {0, 1, 0}, 2.0f, 0);
    add_uv_quad(scene, {0.8f, 0.1f, -3}, {r, 0, r}, {0, 1, 0}, 1.0f, 1);
    scene.lights.push_back(make_point_light({0.5f, 1.0f, -1.5f}, Vec3{4.0f}));
    finish(scene);
    return scene;
}

bool same_bits(const Film& a, const Film& b) { return a.rgb == b.rgb; }

TEST(Mipmap, OffIsTheBilinearImageWithOrWithoutPyramids) {
    Scene scene = lit_scene(256);
    const RenderSettings s = settings(24, 2, IntegratorKind::Path, TextureFilter::Bilinear);
    const Film bare = render(scene, s);
    build_mip_pyramids(scene.textures);
    EXPECT_TRUE(same_bits(render(scene, s), bare));
    const Film mipmapped = render(scene, settings(24, 2, IntegratorKind::Path, TextureFilter::Mipmap));
    EXPECT_FALSE(same_bits(mipmapped, bare)) << "mip-mapping a minified texture changes the image";
}

TEST(Mipmap, FootprintsUnderATexelReadFullResolution) {
    // The first test's view of an 8-texel checkerboard: λ = log2(8/8 · 1/16 ·
    // 1.75) − ½·log2 cos θ < −2 everywhere, and mip-mapping reads the
    // full-resolution texture, as the bilinear render does.
    Scene scene = camera_scene(1.0f, checkerboard(8, 2));
    add_uv_quad(scene, {0, 0, -1.75f}, {1, 0, 0}, {0, 1, 0}, 8.0f, 0);
    finish(scene);
    build_mip_pyramids(scene.textures);
    for (const IntegratorKind integrator : {IntegratorKind::Direct, IntegratorKind::Path})
        EXPECT_TRUE(same_bits(render(scene, settings(32, 2, integrator, TextureFilter::Mipmap)),
                              render(scene, settings(32, 2, integrator, TextureFilter::Bilinear))));
}

TEST(Mipmap, SameImageForAnyThreadCount) {
    Scene scene = lit_scene(256);
    build_mip_pyramids(scene.textures);
    const RenderSettings s = settings(40, 3, IntegratorKind::Path, TextureFilter::Mipmap);
    const Film one = render(scene, s, 1);
    EXPECT_TRUE(same_bits(render(scene, s, 3), one));
    EXPECT_TRUE(same_bits(render(scene, s, 8), one));
}

}  // namespace
}  // namespace sombra
