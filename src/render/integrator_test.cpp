// The direct integrator against closed-form radiance, pixel by pixel.
#include "render/integrator.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/scene_json/scene_file.h"
#include "render/plane_view_test_util.h"
#include "render/render.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

using testing::add_quad;
using testing::camera_looking_down;
using testing::plane_hit;

constexpr double kPi = 3.14159265358979323846;

// The direct integrator for one ray of `scene`, its lights gathered as a render would.
Vec3 trace_direct(const Scene& scene, const Accel& accel, const Ray& ray, RayCounters& counters) {
    const LightSet lights = make_light_set(scene, make_constant_environment(scene.background), false);
    return sombra::trace_direct(IntegratorContext{&scene, &accel, &lights}, ray, counters);
}

RenderOutput render(const Scene& scene, AccelKind kind, const Camera& camera, int w, int h, int spp = 1,
                    int threads = 0) {
    const Accel accel = make_accel(scene, kind);
    RenderJob job;
    job.scene = &scene;
    job.accel = &accel;
    job.camera = camera;
    job.settings = RenderSettings{w, h, spp, 0};
    job.threads = threads;
    job.lights = make_light_set(scene, make_constant_environment(scene.background), false);
    RenderProgress progress;
    return render_image(job, progress);
}

Scene plane_under_point_light(Vec3 light_pos, Vec3 intensity, Vec3 kd) {
    const float e = 1000;
    TriangleMesh plane;
    add_quad(plane, {-e, 0, -e}, {e, 0, -e}, {e, 0, e}, {-e, 0, e}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, plane, {Material{"plane", MaterialType::Diffuse, kd, {}, 1, {}}});
    b.add_light(make_point_light(light_pos, intensity));
    return b.finish();
}

TEST(Integrator, PlaneUnderPointLightMatchesInverseSquareCosineLaw) {
    // Every pixel: L = I · kd/π · h / r³ (cos θ = h/r, falloff 1/r²).
    const Vec3 light{0.3f, 2.0f, -0.2f};
    const Vec3 intensity{10, 20, 5};
    const Vec3 kd{0.8f, 0.5f, 0.25f};
    const Scene scene = plane_under_point_light(light, intensity, kd);
    const int w = 64, h = 48;
    const Camera camera = camera_looking_down(3.0f, 1.5f);
    const Film film = render(scene, AccelKind::Bvh, camera, w, h).film;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            double x, z;
            plane_hit(camera, i, j, w, h, x, z);
            const double dx = light.x - x, dy = light.y, dz = light.z - z;
            const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
            const double geometric = dy / (r * r * r) / kPi;
            const Vec3 got = film.at(i, j);
            for (int c = 0; c < 3; ++c) {
                const double expected = intensity[c] * kd[c] * geometric;
                ASSERT_NEAR(got[c], expected, 1e-4 * expected) << "pixel " << i << "," << j << " channel " << c;
            }
        }
}

TEST(Integrator, LightBelowThePlaneLightsNothingAndMissesShowTheBackground) {
    Scene scene = plane_under_point_light({0, -1, 0}, {10, 10, 10}, Vec3{0.8f});
    scene.background = {0.1f, 0.2f, 0.3f};
    RayCounters counters;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    // From above: the light is behind the surface, no shadow ray is even traced.
    EXPECT_EQ(trace_direct(scene, accel, Ray{{0, 1, 0}, {0, -1, 0}}, counters), Vec3{0.0f});
    EXPECT_EQ(counters.shadow_rays, 0u);
    // Looking up, away from the plane: background.
    EXPECT_EQ(trace_direct(scene, accel, Ray{{0, 1, 0}, {0, 1, 0}}, counters), scene.background);
    EXPECT_EQ(counters.camera_rays, 2u);
}

TEST(Integrator, SurfacesAreTwoSided) {
    // Seen from below with the light below, the plane is lit just the same.
    const Scene scene = plane_under_point_light({0, -2, 0}, {10, 10, 10}, Vec3{0.5f});
    RayCounters counters;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Vec3 l = trace_direct(scene, accel, Ray{{0, -1, 0}, {0, 1, 0}}, counters);
    EXPECT_NEAR(l.x, 10 * 0.5 / kPi / 4, 1e-6);
}

TEST(Integrator, OccluderDarkensExactlyThePixelsGeometryPredicts) {
    Scene scene = plane_under_point_light({0, 2, 0}, {10, 10, 10}, Vec3{0.8f});
    // A square occluder at height 1, x ∈ [-0.25, 0.35], z ∈ [-0.3, 0.2]; its
    // shadow on y = 0 from the light at height 2 is the square scaled by 2.
    add_quad(scene.geometry, {-0.25f, 1, -0.3f}, {0.35f, 1, -0.3f}, {0.35f, 1, 0.2f}, {-0.25f, 1, 0.2f}, 0);
    const int w = 96, h = 96;
    const float eye = 0.9f;  // below the occluder: the camera sees the plane only
    const Camera camera = camera_looking_down(eye, 1.2f);
    const Film film = render(scene, AccelKind::Bvh, camera, w, h).film;
    int shadowed = 0, lit = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            double x, z;
            plane_hit(camera, i, j, w, h, x, z);
            // Inside the shadow iff (x/2, z/2) is inside the square; skip a
            // band of half a percent around its edge (spec §9 allows contact noise).
            const double sx = x / 2, sz = z / 2;
            const double inside = std::min({sx + 0.25, 0.35 - sx, sz + 0.3, 0.2 - sz});
            if (std::fabs(inside) < 0.005) continue;
            const float value = film.at(i, j).x;
            if (inside > 0) {
                EXPECT_EQ(value, 0.0f) << i << "," << j;
                ++shadowed;
            } else {
                EXPECT_GT(value, 0.0f) << i << "," << j;
                ++lit;
            }
        }
    EXPECT_GT(shadowed, 500);
    EXPECT_GT(lit, 500);
}

TEST(Integrator, PhongHighlightMatchesTheFormula) {
    // Camera straight above a point lit from a light straight above: ωi = ωo = n.
    Scene scene = plane_under_point_light({0, 2, 0}, {10, 10, 10}, Vec3{0.3f});
    scene.materials[0] = Material{"p", MaterialType::Phong, Vec3{0.3f}, Vec3{0.5f}, 40, {}};
    RayCounters counters;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Vec3 l = trace_direct(scene, accel, Ray{{0, 1, 0}, {0, -1, 0}}, counters);
    const double f = 0.3 / kPi + 0.5 * 42 / (2 * kPi);
    EXPECT_NEAR(l.x, 10.0 / 4.0 * f, 1e-5);
}

TEST(Integrator, PbrHighlightMatchesAppendixB) {
    // ωi = ωo = n: h = n, so D = 1/(πα²), V = 1/4 and both Fresnel factors
    // are their f0: f = (1 − m)((1 − 0.04)·c/π + 0.04·V·D) + m·c·V·D.
    Scene scene = plane_under_point_light({0, 2, 0}, {10, 10, 10}, Vec3{0.3f});
    Material& m = scene.materials[0];
    m.type = MaterialType::Pbr;
    m.base_color = {0.9f, 0.5f, 0.2f};
    m.metallic = 0.3f;
    m.roughness = 0.4f;
    RayCounters counters;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Vec3 l = trace_direct(scene, accel, Ray{{0, 1, 0}, {0, -1, 0}}, counters);
    const double alpha = 0.16, vd = 0.25 / (kPi * alpha * alpha);
    for (int c = 0; c < 3; ++c) {
        const double base = m.base_color[c];
        const double f = 0.7 * (0.96 * base / kPi + 0.04 * vd) + 0.3 * base * vd;
        EXPECT_NEAR(l[c], 10.0 / 4.0 * f, 1e-5 * f);
    }
}

TEST(Integrator, EmissionIsSeenDirectlyFromBothSides) {
    Scene scene = plane_under_point_light({0, 5, 0}, {0, 0, 0}, Vec3{0.5f});
    scene.materials[0].ke = {1, 2, 3};
    RayCounters counters;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    EXPECT_EQ(trace_direct(scene, accel, Ray{{0, 1, 0}, {0, -1, 0}}, counters), (Vec3{1, 2, 3}));
    EXPECT_EQ(trace_direct(scene, accel, Ray{{0, -1, 0}, {0, 1, 0}}, counters), (Vec3{1, 2, 3}));
}

TEST(Integrator, ShadingNormalsAreInterpolated) {
    // One triangle in y = 0 whose corners all carry the normal tilted 60°
    // from +y (in the xy-plane), lit from straight above: |n_s·ωi| = cos 60°.
    Scene scene;
    scene.materials.push_back(Material{"d", MaterialType::Diffuse, Vec3{1.0f}, {}, 1, {}});
    TriangleMesh& m = scene.geometry;
    m.positions = {{-1, 0, -1}, {1, 0, -1}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}};
    m.material_ids = {0};
    const Vec3 tilted{std::sin(1.0471976f), std::cos(1.0471976f), 0};
    m.normals = {tilted};
    m.normal_indices = {{0, 0, 0}};
    scene.lights.push_back(make_point_light({0, 1, 0}, {4, 4, 4}));
    RayCounters counters;
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const Vec3 l = trace_direct(scene, accel, Ray{{0, 2, 0}, {0, -1, 0}}, counters);
    EXPECT_NEAR(l.x, 4.0 / kPi * 0.5, 1e-5);
    // Without the normal on one corner the face is flat-shaded: cos = 1.
    m.normal_indices = {{0, 0, kNoNormal}};
    const Vec3 flat = trace_direct(scene, accel, Ray{{0, 2, 0}, {0, -1, 0}}, counters);
    EXPECT_NEAR(flat.x, 4.0 / kPi, 1e-5);
}

TEST(Integrator, NoSelfShadowingOnLargeOffsetGeometry) {
    // A plane far from the origin, lit at a grazing angle: the shadow ray's
    // offset must keep it from hitting its own surface (no "acne").
    const float e = 50;
    const Vec3 c{1000, 500, -700};
    TriangleMesh plane;
    add_quad(plane, c + Vec3{-e, 0, -e}, c + Vec3{e, 0.01f, -e}, c + Vec3{e, 0.02f, e}, c + Vec3{-e, 0.01f, e}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, plane, {Material{"d", MaterialType::Diffuse, Vec3{0.5f}, {}, 1, {}}});
    b.add_light(make_point_light(c + Vec3{-40, 1.5f, 3}, {100, 100, 100}));
    const Scene scene = b.finish();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    RayCounters counters;
    int dark = 0;
    for (int k = 0; k < 2000; ++k) {
        const int column = k % 50, row = k / 50;  // a 50 x 40 grid of rays
        const float u = static_cast<float>(column) / 50.0f * 60 - 30, v = static_cast<float>(row) / 40.0f * 60 - 30;
        const Vec3 l = trace_direct(scene, accel, Ray{c + Vec3{u, 10, v}, {0.01f, -1, 0.02f}}, counters);
        if (l.x == 0.0f) ++dark;
    }
    EXPECT_EQ(dark, 0);
}

}  // namespace
}  // namespace sombra
