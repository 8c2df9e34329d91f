// The AOVs of spec §18 on a scene with known answers: a diffuse plane of
// known albedo at a known distance, covering the left half of the view.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "render/first_hit.h"
#include "render/render.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

constexpr float kDistance = 4.0f;
constexpr int kWidth = 16, kHeight = 8;
const Vec3 kAlbedo{0.2f, 0.4f, 0.6f};

// Camera at the origin looking down −z; the plane z = −kDistance spans
// x ≤ 0, so image columns 0 … 7 (the left half) see it.
Scene half_plane_scene() {
    TriangleMesh plane;
    const float z = -kDistance;
    testing::add_quad(plane, {-20, -20, z}, {0, -20, z}, {0, 20, z}, {-20, 20, z}, 0);
    Material m = default_material();
    m.kd = kAlbedo;
    SceneBuilder b;
    testing::add_world_mesh(b, plane, {m});
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60};
    b.set_camera(camera);
    b.add_light(make_point_light({0, 0, 0}, Vec3{10.0f}));
    return b.finish();
}

struct Rendered {
    RenderOutput out;
    RenderJob job;
};

Rendered render_with_aovs(const Scene& scene, const Accel& accel, IntegratorKind integrator, int spp, AovSet aovs) {
    Rendered r;
    r.job = make_render_job(scene, accel, RenderSettings{kWidth, kHeight, spp, 3, integrator, 4});
    r.job.aovs = aovs;
    RenderProgress progress;
    r.out = render_image(r.job, progress);
    return r;
}

const AovSet kAll{true, true, true, true, true};

Vec3 at3(const std::vector<float>& image, int i, int j) {
    const std::size_t p = static_cast<std::size_t>(j) * static_cast<std::size_t>(kWidth) + static_cast<std::size_t>(i);
    return {image[3 * p], image[3 * p + 1], image[3 * p + 2]};
}

// Where the corner (x, y) of the image (pixel units) sees the plane.
Vec3 plane_point(const Camera& camera, float x, float y) {
    const Ray r = camera_ray(camera, image_plane_s(x, kWidth), image_plane_t(y, kHeight));
    return r.dir * (-kDistance / r.dir.z);
}

TEST(Aov, KnownAlbedoNormalDepthPositionAndSpp) {
    const Scene scene = half_plane_scene();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    for (int spp : {1, 8}) {
        const Rendered r = render_with_aovs(scene, accel, IntegratorKind::Direct, spp, kAll);
        const AovImages& a = r.out.aovs;
        ASSERT_EQ(a.albedo.size(), 3u * kWidth * kHeight);
        ASSERT_EQ(a.depth.size(), 1u * kWidth * kHeight);
        for (int j = 0; j < kHeight; ++j) {
            for (int i = 0; i < kWidth; ++i) {
                SCOPED_TRACE(::testing::Message() << "spp " << spp << ", pixel (" << i << ", " << j << ")");
                const std::size_t p =
                    static_cast<std::size_t>(j) * static_cast<std::size_t>(kWidth) + static_cast<std::size_t>(i);
                EXPECT_EQ(a.spp[p], static_cast<float>(spp));
                if (i <= 6) {  // every sample hits the plane
                    const Vec3 albedo = at3(a.albedo, i, j);
                    EXPECT_NEAR(albedo.x, kAlbedo.x, 1e-6f);
                    EXPECT_NEAR(albedo.y, kAlbedo.y, 1e-6f);
                    EXPECT_NEAR(albedo.z, kAlbedo.z, 1e-6f);
                    const Vec3 n = at3(a.normal, i, j);  // faces the camera at the origin
                    EXPECT_NEAR(n.x, 0.0f, 1e-6f);
                    EXPECT_NEAR(n.y, 0.0f, 1e-6f);
                    EXPECT_NEAR(n.z, 1.0f, 1e-6f);
                    // The mean position lies in the pixel's footprint on the
                    // plane (parallel to the image: a box), at z = −d; the
                    // mean depth between d and the farthest corner's distance.
                    const Vec3 c0 = plane_point(r.job.camera, static_cast<float>(i), static_cast<float>(j));
                    const Vec3 c1 = plane_point(r.job.camera, static_cast<float>(i + 1), static_cast<float>(j + 1));
                    const Vec3 pos = at3(a.position, i, j);
                    EXPECT_GE(pos.x, std::min(c0.x, c1.x) - 1e-4f);
                    EXPECT_LE(pos.x, std::max(c0.x, c1.x) + 1e-4f);
                    EXPECT_GE(pos.y, std::min(c0.y, c1.y) - 1e-4f);
                    EXPECT_LE(pos.y, std::max(c0.y, c1.y) + 1e-4f);
                    EXPECT_NEAR(pos.z, -kDistance, 1e-5f);
                    float farthest = 0;
                    for (int corner = 0; corner < 4; ++corner)
                        farthest =
                            std::max(farthest, length(plane_point(r.job.camera, static_cast<float>(i + corner % 2),
                                                                  static_cast<float>(j + (corner >= 2 ? 1 : 0)))));
                    EXPECT_GE(a.depth[p], kDistance * (1.0f - 1e-6f));
                    EXPECT_LE(a.depth[p], farthest * (1.0f + 1e-6f));
                    if (spp == 1) {  // one ray through the pixel centre: exact
                        const Vec3 centre =
                            plane_point(r.job.camera, static_cast<float>(i) + 0.5f, static_cast<float>(j) + 0.5f);
                        EXPECT_NEAR(a.depth[p], length(centre), 1e-5f * kDistance);
                        EXPECT_NEAR(pos.x, centre.x, 1e-5f);
                        EXPECT_NEAR(pos.y, centre.y, 1e-5f);
                    }
                } else if (i >= 9) {  // every sample misses
                    EXPECT_EQ(at3(a.albedo, i, j), Vec3{0.0f});
                    EXPECT_EQ(at3(a.normal, i, j), Vec3{0.0f});
                    EXPECT_EQ(at3(a.position, i, j), Vec3{0.0f});
                    EXPECT_EQ(a.depth[p], std::numeric_limits<float>::infinity());
                }
            }
        }
    }
}

TEST(Aov, PartlyCoveredPixelsAverageWithZeroForMisses) {
    // Column 8's left edge is the plane's edge: some samples of the pixels
    // on the boundary column may miss. Albedo scales with the share that
    // hits, and depth stays the mean over the hits alone.
    const Scene scene = half_plane_scene();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Rendered r = render_with_aovs(scene, accel, IntegratorKind::Direct, 16, kAll);
    for (int j = 0; j < kHeight; ++j) {
        for (int i = 7; i <= 8; ++i) {
            const Vec3 albedo = at3(r.out.aovs.albedo, i, j);
            const float share = albedo.x / kAlbedo.x;
            EXPECT_NEAR(albedo.y, share * kAlbedo.y, 1e-5f);
            EXPECT_NEAR(at3(r.out.aovs.normal, i, j).z, share, 1e-5f);
            if (share > 0.0f) {
                EXPECT_NEAR(at3(r.out.aovs.position, i, j).z / share, -kDistance, 1e-4f);
            }
        }
    }
}

TEST(Aov, GatheringThemLeavesTheImageAsItWas) {
    // Both integrators: the AOVs come from the first hit they already shade,
    // so the image is the same bytes with and without them, and both
    // integrators report the same first hits.
    const Scene scene = half_plane_scene();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Rendered direct_aovs = render_with_aovs(scene, accel, IntegratorKind::Direct, 4, kAll);
    for (IntegratorKind integrator : {IntegratorKind::Direct, IntegratorKind::Path}) {
        const Rendered plain = render_with_aovs(scene, accel, integrator, 4, AovSet{});
        const Rendered with = render_with_aovs(scene, accel, integrator, 4, kAll);
        ASSERT_EQ(plain.out.film.rgb.size(), with.out.film.rgb.size());
        EXPECT_EQ(std::memcmp(plain.out.film.rgb.data(), with.out.film.rgb.data(), plain.out.film.rgb.size() * 4), 0);
        EXPECT_TRUE(plain.out.aovs.albedo.empty());
        EXPECT_EQ(with.out.aovs.albedo, direct_aovs.out.aovs.albedo);
        EXPECT_EQ(with.out.aovs.position, direct_aovs.out.aovs.position);
    }
}

TEST(Aov, AlbedoOfEachMaterial) {
    // Spec §18's list: diffuse kd; phong kd + ks; mirror kr; dielectric kt;
    // conductor ks; pbr base_color.
    Material m = default_material();
    m.kd = {0.1f, 0.2f, 0.3f};
    m.ks = {0.4f, 0.3f, 0.2f};
    m.kr = {0.9f, 0.8f, 0.7f};
    m.kt = {0.6f, 0.5f, 0.4f};
    m.base_color = {0.3f, 0.6f, 0.9f};
    m.type = MaterialType::Diffuse;
    EXPECT_EQ(material_albedo(m), m.kd);
    m.type = MaterialType::Phong;
    EXPECT_EQ(material_albedo(m), m.kd + m.ks);
    m.type = MaterialType::Mirror;
    EXPECT_EQ(material_albedo(m), m.kr);
    m.type = MaterialType::Dielectric;
    EXPECT_EQ(material_albedo(m), m.kt);
    m.type = MaterialType::Conductor;
    EXPECT_EQ(material_albedo(m), m.ks);
    m.type = MaterialType::Pbr;
    EXPECT_EQ(material_albedo(m), m.base_color);
}

}  // namespace
}  // namespace sombra
