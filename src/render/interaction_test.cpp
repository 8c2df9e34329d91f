#include "render/interaction.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "accel/accel.h"
#include "scene/corner_attributes.h"

namespace sombra {
namespace {

bool same_bits(const SurfaceInteraction& a, const SurfaceInteraction& b) {
    const auto vec = [](Vec3 x, Vec3 y) { return std::memcmp(&x, &y, sizeof x) == 0; };
    return vec(a.position, b.position) && vec(a.position_error, b.position_error) && vec(a.n_g, b.n_g) &&
           vec(a.n_s, b.n_s) && a.outside == b.outside && a.has_uv == b.has_uv &&
           std::memcmp(&a.uv, &b.uv, sizeof a.uv) == 0 && a.triangle == b.triangle && a.material == b.material;
}

// 200 random triangles whose corners have normals and uvs in every
// combination: all three, some, none (like a scene mixing a scan without
// normals and a floor with them).
TriangleMesh mixed_mesh() {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    TriangleMesh mesh;
    for (std::uint32_t t = 0; t < 200; ++t) {
        Index3 tri, normals, uvs;
        for (int c = 0; c < 3; ++c) {
            tri[c] = static_cast<std::uint32_t>(mesh.positions.size());
            mesh.positions.push_back({u(rng), u(rng), u(rng)});
            mesh.normals.push_back(normalize(Vec3{u(rng), u(rng), 2.0f}));
            mesh.uvs.push_back({u(rng), u(rng)});
            normals[c] = (t % 3 == 0 || (t % 3 == 1 && c != 1)) ? tri[c] : kNoNormal;
            uvs[c] = (t % 5 < 2 || (t % 5 == 2 && c == 0)) ? tri[c] : kNoUv;
        }
        mesh.triangles.push_back(tri);
        mesh.normal_indices.push_back(normals);
        mesh.uv_indices.push_back(uvs);
        mesh.material_ids.push_back(t % 4);
    }
    return mesh;
}

// What shading makes of a hit is the same, bit for bit, whether the mesh's
// complete-corner bits are derived or not and whether the hit carries its
// corners (the BVH's) or not.
TEST(SurfaceInteraction, SameWithAndWithoutDerivedBitsAndCarriedCorners) {
    const TriangleMesh plain = mixed_mesh();
    TriangleMesh marked = plain;
    mark_complete_corners(marked);
    int smooth = 0, textured = 0;
    for (std::uint32_t t = 0; t < plain.triangle_count(); ++t) {
        const auto [p0, p1, p2] = triangle_corners(plain, t);
        const Vec3 target = 0.2f * p0 + 0.3f * p1 + 0.5f * p2;
        const Ray ray{target + Vec3{0.1f, 0.2f, 3.0f}, Vec3{-0.1f, -0.2f, -3.0f}};
        Hit hit;
        hit.t = 1.0f;
        hit.b1 = 0.3f;
        hit.b2 = 0.5f;
        hit.triangle = t;
        const SurfaceInteraction want = make_surface_interaction(plain, ray, hit);
        EXPECT_TRUE(same_bits(make_surface_interaction(marked, ray, hit), want)) << t;
        hit.corners = triangle_corners(plain, t);
        hit.has_corners = true;
        EXPECT_TRUE(same_bits(make_surface_interaction(marked, ray, hit), want)) << t;
        smooth += !(want.n_s == want.n_g);
        textured += want.has_uv;
    }
    EXPECT_GT(smooth, 50);  // the comparison covered smooth and flat triangles
    EXPECT_GT(textured, 50);
}

}  // namespace
}  // namespace sombra
