// Alpha cut-outs in every backend (spec §12): a hit where the surface is cut
// out does not count, for closest hits and shadow rays alike, and the BVH
// still returns exactly the brute-force loop's hit.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_test_util.h"

namespace sombra {
namespace {

// An 8 × 1 alpha image, columns 1 1 0 0 0 0 1 1: read bilinearly between
// texel centres ((i + ½)/8), alpha falls below ½ exactly for 0.25 < u < 0.75.
Texture strip_alpha() {
    Texture t;
    t.source = "strip";
    t.encoding = TextureEncoding::Data;
    t.width = 8;
    t.height = 1;
    t.channels = 1;
    t.texels = {1, 1, 0, 0, 0, 0, 1, 1};
    return t;
}

bool cut_at(float u) { return u > 0.25f && u < 0.75f; }

Material cut_out_material(std::uint32_t texture, float factor = 1.0f) {
    Material m;
    m.textures.alpha_test = true;
    m.textures.alpha.texture = texture;
    m.textures.alpha_factor = factor;
    m.textured = true;
    return m;
}

// A floor z = 0 over [-1, 1]² (material 0, opaque) under a quad z = 1 over
// [-0.6, 0.6]² (material 1) with uv u = (x + 0.6)/1.2, v = (y + 0.6)/1.2.
struct StripScene {
    TriangleMesh mesh;
    std::vector<Material> materials{Material{}, cut_out_material(0)};
    std::vector<Texture> textures{strip_alpha()};

    StripScene() {
        mesh.positions = {{-1, -1, 0},       {1, -1, 0},       {1, 1, 0},       {-1, 1, 0},
                          {-0.6f, -0.6f, 1}, {0.6f, -0.6f, 1}, {0.6f, 0.6f, 1}, {-0.6f, 0.6f, 1}};
        mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
        mesh.material_ids = {0, 0, 1, 1};
        mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        mesh.uv_indices = {{kNoUv, kNoUv, kNoUv}, {kNoUv, kNoUv, kNoUv}, {0, 1, 2}, {0, 2, 3}};
    }
    Cutouts cutouts() const { return make_cutouts(mesh, materials, textures); }
};

std::vector<AccelKind> backends() {
    std::vector<AccelKind> kinds;
    for (std::string_view name : available_accels()) kinds.push_back(*parse_accel_kind(name));
    return kinds;
}

TEST(Cutouts, InactiveWithoutAnAlphaTest) {
    StripScene s;
    EXPECT_TRUE(s.cutouts().active());
    s.materials[1].textures.alpha_test = false;
    EXPECT_FALSE(s.cutouts().active());
}

TEST(Cutouts, RaysPassThroughTheCutStripInEveryBackend) {
    const StripScene s;
    for (const AccelKind kind : backends()) {
        const Accel accel = make_accel(s.mesh, kind, s.cutouts());
        int through = 0, stopped = 0;
        for (int i = 0; i < 40; ++i)
            for (int j = 0; j < 40; ++j) {
                const float x = -0.975f + 0.05f * static_cast<float>(i), y = -0.975f + 0.05f * static_cast<float>(j);
                const float u = (x + 0.6f) / 1.2f;
                const bool on_quad = std::fabs(x) < 0.6f && std::fabs(y) < 0.6f;
                const bool quad_there = on_quad && !cut_at(u);
                const std::string where =
                    std::string(accel_name(kind)) + " at " + std::to_string(x) + ", " + std::to_string(y);
                // Straight down from z = 2: the quad at t = 1 where it exists, else the floor at t = 2.
                Hit hit;
                ASSERT_TRUE(intersect(accel, Ray{{x, y, 2}, {0, 0, -1}}, hit)) << where;
                EXPECT_EQ(hit.triangle >= 2, quad_there) << where;
                EXPECT_NEAR(hit.t, quad_there ? 1.0f : 2.0f, 1e-5f) << where;
                // Up from just above the floor towards a light at z = 3: blocked only by the quad's remaining parts.
                EXPECT_EQ(occluded(accel, Ray{{x, y, 0.001f}, {0, 0, 1}, 2.999f}), quad_there) << where;
                (quad_there ? stopped : through) += on_quad;
            }
        EXPECT_GT(through, 100) << "rays must cross the strip";
        EXPECT_GT(stopped, 100) << "and others must stop on the quad's sides";
    }
}

TEST(Cutouts, AlphaFactorScalesTheTexture) {
    // glTF's baseColorFactor alpha multiplies the texture's: at 0.4 even the
    // opaque columns fall below the ½ cutoff, so the whole quad is gone.
    StripScene s;
    s.materials[1].textures.alpha_factor = 0.4f;
    const Accel accel = make_accel(s.mesh, AccelKind::Bvh, s.cutouts());
    Hit hit;
    ASSERT_TRUE(intersect(accel, Ray{{-0.5f, 0, 2}, {0, 0, -1}}, hit));
    EXPECT_NEAR(hit.t, 2.0f, 1e-5f);
    // And a lower cutoff brings the opaque columns back (0.4 ≥ 0.3).
    s.materials[1].textures.alpha_cutoff = 0.3f;
    const Accel lower = make_accel(s.mesh, AccelKind::Bvh, s.cutouts());
    ASSERT_TRUE(intersect(lower, Ray{{-0.5f, 0, 2}, {0, 0, -1}}, hit));
    EXPECT_NEAR(hit.t, 1.0f, 1e-5f);
}

TEST(Cutouts, BvhEqualsBruteForceOnCutOutSoup) {
    // Random triangles with random uvs, every other one on a material whose
    // alpha is 16 × 16 noise: the BVH's closest hit is the brute-force loop's,
    // bit for bit, and shadow rays agree with it.
    std::mt19937 rng(7);
    TriangleMesh mesh = testing::random_soup(3000, 11, 0.2f);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
        const auto base = static_cast<std::uint32_t>(mesh.uvs.size());
        for (int c = 0; c < 3; ++c) mesh.uvs.push_back({4 * unit(rng), 4 * unit(rng)});
        mesh.uv_indices.push_back({base, base + 1, base + 2});
        mesh.material_ids.push_back(static_cast<std::uint32_t>(i % 2));
    }
    Texture noise;
    noise.encoding = TextureEncoding::Data;
    noise.width = noise.height = 16;
    noise.channels = 1;
    for (int k = 0; k < 256; ++k) noise.texels.push_back(unit(rng));
    const std::vector<Material> materials{Material{}, cut_out_material(0)};
    const std::vector<Texture> textures{noise};
    const Cutouts cutouts = make_cutouts(mesh, materials, textures);
    const Accel bvh = make_accel(mesh, AccelKind::Bvh, cutouts);
    const Accel brute = make_accel(mesh, AccelKind::Brute, cutouts);
    const Accel opaque = make_accel(mesh, AccelKind::Bvh);

    int differs_from_opaque = 0, hits = 0;
    for (int r = 0; r < 4000; ++r) {
        const Vec3 o = testing::random_point(rng, Vec3{-0.5f}, Vec3{1.5f});
        const Vec3 target = testing::random_point(rng, Vec3{0.0f}, Vec3{1.0f});
        const Ray ray{o, target - o};
        Hit a, b, c;
        const bool ha = intersect(bvh, ray, a), hb = intersect(brute, ray, b), hc = intersect(opaque, ray, c);
        ASSERT_EQ(ha, hb) << "ray " << r;
        EXPECT_EQ(occluded(bvh, ray), ha) << "ray " << r;
        EXPECT_EQ(occluded(brute, ray), hb) << "ray " << r;
        if (!ha) continue;
        ++hits;
        EXPECT_EQ(a.triangle, b.triangle) << "ray " << r;
        EXPECT_EQ(a.t, b.t) << "ray " << r;
        EXPECT_EQ(a.b1, b.b1) << "ray " << r;
        EXPECT_EQ(a.b2, b.b2) << "ray " << r;
        EXPECT_TRUE(surface_exists(cutouts, a.triangle, a.b1, a.b2)) << "ray " << r;
        differs_from_opaque += !hc || c.triangle != a.triangle;
    }
    EXPECT_GT(hits, 1000);
    EXPECT_GT(differs_from_opaque, 100) << "the cut-outs should change many hits";
}

}  // namespace
}  // namespace sombra
