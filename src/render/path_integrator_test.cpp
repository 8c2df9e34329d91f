// The path integrator against closed forms, statistically: every estimate is
// compared with its expected value in units of its own standard error,
// computed from the sample variance (fixed seeds, so the tests are
// repeatable; the bounds are z-scores, not tuned tolerances).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "render/bsdf/pbr_test_util.h"
#include "render/integrator.h"
#include "render/path_test_util.h"
#include "render/render.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

using testing::add_quad;
using testing::add_triangle;
using testing::add_world_mesh;
using testing::Estimate;
using testing::expect_agrees;
using testing::kZ;
using testing::PathRun;

constexpr double kPi = std::numbers::pi;
Material diffuse(Vec3 kd) {
    Material m;
    m.type = MaterialType::Diffuse;
    m.kd = kd;
    return m;
}

TEST(PathIntegrator, WhiteFurnaceDiffuseSphere) {
    // Albedo 1 inside a uniform environment of radiance 1: every path
    // carries 1, so every pixel is 1 (up to MIS noise).
    SceneBuilder b;
    b.set_background(Vec3{1.0f});
    TriangleMesh sphere;
    testing::add_sphere(sphere, {0, 0, 0}, 1.0f, 3, 0);
    add_world_mesh(b, sphere, {diffuse(Vec3{1.0f})});
    const Scene scene = b.finish();
    const PathRun run{scene, 64};
    for (const Vec3 target : {Vec3{0, 0, 0}, Vec3{0.6f, 0.5f, 0}, Vec3{0.95f, 0, 0.2f}}) {
        const Estimate e = run.estimate({0.1f, 0.2f, 5}, target, 4000, 11);
        expect_agrees(e, 1.0, "diffuse furnace");
    }
}

TEST(PathIntegrator, WhiteFurnaceMirrorAndGlassSpheres) {
    for (const MaterialType type : {MaterialType::Mirror, MaterialType::Dielectric}) {
        SceneBuilder b;
        b.set_background(Vec3{1.0f});
        Material m;
        m.type = type;
        m.kr = Vec3{1.0f};
        m.kt = Vec3{1.0f};
        m.ior = 1.5f;
        TriangleMesh sphere;
        testing::add_sphere(sphere, {0, 0, 0}, 1.0f, 3, 0);
        add_world_mesh(b, sphere, {m});
        const Scene scene = b.finish();
        const PathRun run{scene, 1024};
        for (const Vec3 target : {Vec3{0, 0, 0}, Vec3{0.5f, 0.3f, 0}, Vec3{0.9f, 0.1f, 0}}) {
            const Estimate e = run.estimate({0.1f, 0.2f, 5}, target, 2000, 5);
            expect_agrees(e, 1.0, type == MaterialType::Mirror ? "mirror furnace" : "glass furnace");
        }
    }
}

TEST(PathIntegrator, PbrPlaneUnderAConstantSkyShowsItsAlbedo) {
    // Under a sky of radiance 1 a plane reflects its directional albedo
    // ∫ f cos θ_i dω_i at the view angle: next-event estimation of the sky
    // and BSDF sampling, MIS-weighted with the pbr pdf, against quadrature of
    // the glTF Appendix B formulas (render/bsdf/pbr_test_util.h).
    struct Case {
        Vec3 base;
        float metallic, roughness;
    };
    const Case cases[] = {
        {Vec3{1.0f}, 0.0f, 0.3f}, {{0.8f, 0.5f, 0.2f}, 0.5f, 0.6f}, {Vec3{0.7f}, 0.0f, 0.0f}, {Vec3{0.9f}, 1.0f, 1.0f}};
    std::uint64_t seed = 40;
    for (const Case& c : cases) {
        SceneBuilder b;
        b.set_background(Vec3{1.0f});
        Material m;
        m.type = MaterialType::Pbr;
        m.base_color = c.base;
        m.metallic = c.metallic;
        m.roughness = c.roughness;
        TriangleMesh plane;
        add_quad(plane, {-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, 0);
        add_world_mesh(b, plane, {m});
        const Scene scene = b.finish();
        const PathRun run{scene, 8};
        for (const double theta : {10.0, 50.0, 75.0}) {
            const double t = theta * kPi / 180;
            const Vec3 eye{static_cast<float>(std::sin(t)), static_cast<float>(std::cos(t)), 0};
            const Estimate e = run.estimate(eye, {0, 0, 0}, 6000, ++seed);
            const pbr_reference::Params p{c.base.x, c.metallic, c.roughness, 1.5};
            const pbr_reference::Quadrature q =
                pbr_reference::albedo_with_error(p, std::acos(static_cast<double>(normalize(eye).y)), 400);
            EXPECT_LT(std::fabs(e.mean() - q.value), kZ * e.standard_error() + q.error)
                << "r " << c.roughness << " m " << c.metallic << " at " << theta << "°: " << e.mean() << " ± "
                << e.standard_error() << ", quadrature " << q.value;
        }
    }
}

// A closed box, every wall diffuse with albedo a and emitting Le: the
// radiance seen from inside at max_depth N is Le · (1 − a^(N+1)) / (1 − a)
// (Nori's test): each scattering event adds one more generation of
// emitted light, reduced by a.
TEST(PathIntegrator, ClosedEmittingBoxSumsTheGeometricSeries) {
    const float a = 0.5f, le = 0.7f;
    Material m = diffuse(Vec3{a});
    m.ke = Vec3{le};
    const Vec3 p000{-1, -1, -1}, p100{1, -1, -1}, p110{1, 1, -1}, p010{-1, 1, -1};
    const Vec3 p001{-1, -1, 1}, p101{1, -1, 1}, p111{1, 1, 1}, p011{-1, 1, 1};
    TriangleMesh g;
    add_quad(g, p000, p010, p110, p100, 0);
    add_quad(g, p001, p101, p111, p011, 0);
    add_quad(g, p000, p100, p101, p001, 0);
    add_quad(g, p010, p011, p111, p110, 0);
    add_quad(g, p000, p001, p011, p010, 0);
    add_quad(g, p100, p110, p111, p101, 0);
    SceneBuilder b;
    add_world_mesh(b, g, {m});
    const Scene scene = b.finish();
    for (const std::uint32_t pixel_samples : {1u, 64u})
        for (const int depth : {0, 1, 2, 5, 12}) {
            const PathRun run{scene, depth, LightStrategy::Mis, pixel_samples};
            const Estimate e =
                run.estimate({0.1f, -0.2f, 0.3f}, {0.5f, 0.4f, -1}, 3000, 3 + static_cast<std::uint64_t>(depth));
            const double expected = le * (1.0 - std::pow(a, depth + 1)) / (1.0 - a);
            expect_agrees(e, expected, pixel_samples == 1 ? "closed box" : "closed box, progressive");
        }
}

// Irradiance at x (normal n) from a uniformly emitting polygon of radiance
// 1: Lambert's formula E = ½ Σ Θ_i (n · Γ_i), Θ_i the angle the i-th edge
// subtends at x and Γ_i the unit normal of the plane through x and that edge.
double polygon_irradiance(const std::vector<Vec3>& corners, Vec3 x, Vec3 n) {
    double e = 0;
    for (std::size_t i = 0; i < corners.size(); ++i) {
        const Vec3 a = normalize(corners[i] - x), b = normalize(corners[(i + 1) % corners.size()] - x);
        const double theta = std::acos(std::clamp(static_cast<double>(dot(a, b)), -1.0, 1.0));
        e += theta * dot(normalize(cross(a, b)), n);
    }
    return 0.5 * std::fabs(e);
}

TEST(PathIntegrator, PlaneUnderTriangleLightMatchesLambertsPolygonFormula) {
    // max_depth 1: only direct light. L = kd/π · Le · E/1 at each plane point.
    const Vec3 kd{0.6f}, le{5, 3, 1};
    const std::vector<Vec3> light = {{-0.5f, 1, -0.3f}, {0.4f, 1.2f, -0.4f}, {0.1f, 0.9f, 0.6f}};
    for (const LightStrategy strategy : {LightStrategy::Mis, LightStrategy::LightOnly, LightStrategy::BsdfOnly}) {
        Material emitter = diffuse(Vec3{0.0f});
        emitter.ke = le;
        TriangleMesh mesh;
        add_quad(mesh, {-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, 0);
        add_triangle(mesh, light[0], light[1], light[2], 1);
        SceneBuilder b;
        add_world_mesh(b, mesh, {diffuse(kd), emitter});
        const Scene scene = b.finish();
        for (const std::uint32_t pixel_samples : {1u, 64u}) {
            const PathRun run{scene, 1, strategy, pixel_samples};
            for (const Vec3 x : {Vec3{0, 0, 0}, Vec3{0.7f, 0, 0.2f}, Vec3{-1.5f, 0, 1}}) {
                const double expected = kd.x / kPi * le.x * polygon_irradiance(light, x, {0, 1, 0});
                // Camera rays from just above the plane (below the light), straight down.
                const Estimate e = run.estimate(x + Vec3{0.01f, 0.3f, 0.02f}, x,
                                                strategy == LightStrategy::BsdfOnly ? 40000 : 6000, 21);
                expect_agrees(e, expected,
                              pixel_samples == 1 ? "polygon irradiance" : "polygon irradiance, progressive");
            }
        }
    }
}

TEST(PathIntegrator, CutOutPartsOfAnEmitterGiveNoLight) {
    // A quad light y = 1 over x, z in [-0.6, 0.6] whose alpha (8 × 1 texels,
    // 1 1 0 0 0 0 1 1 along u = (x + 0.6)/1.2, bilinear) drops below the ½
    // cutoff exactly for |x| < 0.3: what is left are two rectangles, and the
    // plane below receives Lambert's polygon irradiance from those alone,
    // under every strategy (light samples landing on the cut strip count
    // nothing, BSDF rays pass through it).
    const Vec3 kd{0.6f}, le{4, 2, 1};
    Texture strip;
    strip.encoding = TextureEncoding::Data;
    strip.width = 8;
    strip.height = 1;
    strip.channels = 1;
    strip.texels = {1, 1, 0, 0, 0, 0, 1, 1};
    const std::vector<std::vector<Vec3>> left_and_right = {
        {{-0.6f, 1, -0.6f}, {-0.3f, 1, -0.6f}, {-0.3f, 1, 0.6f}, {-0.6f, 1, 0.6f}},
        {{0.3f, 1, -0.6f}, {0.6f, 1, -0.6f}, {0.6f, 1, 0.6f}, {0.3f, 1, 0.6f}}};
    for (const LightStrategy strategy : {LightStrategy::Mis, LightStrategy::LightOnly, LightStrategy::BsdfOnly}) {
        Material emitter = diffuse(Vec3{0.0f});
        emitter.ke = le;
        emitter.textures.alpha_test = true;
        emitter.textures.alpha.texture = 0;  // the strip
        TriangleMesh mesh;
        add_quad(mesh, {-50, 0, -50}, {-50, 0, 50}, {50, 0, 50}, {50, 0, -50}, 0);
        add_quad(mesh, {-0.6f, 1, -0.6f}, {0.6f, 1, -0.6f}, {0.6f, 1, 0.6f}, {-0.6f, 1, 0.6f}, 1);
        mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        mesh.uv_indices = {{kNoUv, kNoUv, kNoUv}, {kNoUv, kNoUv, kNoUv}, {0, 1, 2}, {0, 2, 3}};
        SceneBuilder b;
        add_world_mesh(b, mesh, {diffuse(kd), emitter}, {strip});
        const Scene scene = b.finish();
        const PathRun run{scene, 1, strategy};
        for (const Vec3 x : {Vec3{0, 0, 0}, Vec3{0.45f, 0, 0.2f}, Vec3{-1.2f, 0, 0.5f}}) {
            double expected = 0;
            for (const std::vector<Vec3>& part : left_and_right)
                expected += kd.x / kPi * le.x * polygon_irradiance(part, x, {0, 1, 0});
            const Estimate e =
                run.estimate(x + Vec3{0.01f, 0.3f, 0.02f}, x, strategy == LightStrategy::BsdfOnly ? 40000 : 6000, 23);
            expect_agrees(e, expected, "irradiance from the uncut parts");
        }
    }
}

TEST(PathIntegrator, PointLightInsideADiffuseSphereAtDepthOne) {
    // Depth 1 under a point light is deterministic: L = kd/π · I/d² · cos θ
    // at the hit point of a flat facet (no randomness, no tolerance but rounding).
    SceneBuilder b;
    TriangleMesh sphere;
    testing::add_sphere(sphere, {0, 0, 0}, 2.0f, 4, 0);
    add_world_mesh(b, sphere, {diffuse(Vec3{0.5f})});
    b.add_light(make_point_light({0, 0, 0}, {3, 3, 3}));
    const Scene scene = b.finish();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const LightSet lights = make_light_set(scene, make_constant_environment(scene.background), true);
    const IntegratorContext ctx{&scene, &accel, &lights, 1};
    RayCounters counters;
    for (const Vec3 dir : {Vec3{1, 0.2f, 0.1f}, Vec3{-0.3f, 1, 0.5f}, Vec3{0.2f, -0.4f, -1}}) {
        SampleStream stream{7, 0, 1};
        const Ray ray{{0.1f, 0.05f, 0}, dir};
        const Vec3 l = trace_path(ctx, ray, stream, counters);
        Hit hit;
        ASSERT_TRUE(intersect(accel, ray, hit));
        const Index3 t = scene.geometry.triangles[hit.triangle];
        const Vec3 p0 = scene.geometry.positions[t[0]], p1 = scene.geometry.positions[t[1]],
                   p2 = scene.geometry.positions[t[2]];
        const Vec3 x = ray.origin + hit.t * ray.dir;
        const Vec3 n = normalize(cross(p1 - p0, p2 - p0));
        const double d2 = dot(x, x);
        const double expected = 0.5 / kPi * 3.0 / d2 * std::fabs(dot(n, normalize(-x)));
        EXPECT_NEAR(l.x, expected, 1e-5 * expected);
    }
}

TEST(PathIntegrator, StrategiesAgreeUnderAnEnvironment) {
    // A diffuse and a glossy sphere on a plane under a coloured constant sky:
    // light sampling alone, BSDF sampling alone and MIS estimate the same value.
    SceneBuilder b;
    b.set_background(Vec3{0.8f, 0.9f, 1.2f});
    Material phong;
    phong.type = MaterialType::Phong;
    phong.kd = Vec3{0.3f};
    phong.ks = Vec3{0.5f};
    phong.shininess = 20;
    TriangleMesh mesh;
    add_quad(mesh, {-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}, 0);
    testing::add_sphere(mesh, {0, 1, 0}, 1.0f, 3, 1);
    add_world_mesh(b, mesh, {diffuse(Vec3{0.7f}), phong});
    const Scene scene = b.finish();
    double means[3];
    int k = 0;
    for (const LightStrategy strategy : {LightStrategy::Mis, LightStrategy::LightOnly, LightStrategy::BsdfOnly}) {
        const PathRun run{scene, 3, strategy};
        const Estimate e = run.estimate({2, 1.5f, 3}, {0.3f, 0.1f, 1.5f}, 20000, 99);
        means[k++] = e.mean();
        if (strategy != LightStrategy::Mis) {
            // Compare with MIS's estimate, both standard errors combined.
            const PathRun mis{scene, 3, LightStrategy::Mis};
            const Estimate m = mis.estimate({2, 1.5f, 3}, {0.3f, 0.1f, 1.5f}, 20000, 1234);
            const double z = (e.mean() - m.mean()) / std::hypot(e.standard_error(), m.standard_error());
            EXPECT_LT(std::fabs(z), kZ) << "strategy " << static_cast<int>(strategy) << ": " << e.mean() << " vs "
                                        << m.mean();
        }
    }
    EXPECT_GT(means[0], 0.1);
}

const std::filesystem::path kShared = SOMBRA_SHARED_DIR;

RenderOutput render_with(const Scene& scene, RenderSettings settings, int threads) {
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, settings, threads);
    RenderProgress progress;
    return render_image(job, progress);
}

TEST(PathIntegrator, DepthOneEqualsDirectOnPointLightScenes) {
    for (const char* name : {"bunny.json", "phong.json"}) {
        if (!std::filesystem::exists(kShared / "scenes" / name)) GTEST_SKIP() << "shared/ not found at " << kShared;
        Diagnostics diag;
        Scene scene = load_scene_file(kShared / "scenes" / name, diag).scene;
        // Spec §10: with a black background (which path tracing would light with).
        scene.background = Vec3{0.0f};
        RenderSettings settings{80, 45, 2, 3};
        const RenderOutput direct = render_with(scene, settings, 0);
        settings.integrator = IntegratorKind::Path;
        settings.max_depth = 1;
        const RenderOutput path = render_with(scene, settings, 0);
        // Same shading code, same order of operations: the very same floats.
        EXPECT_EQ(direct.film.rgb, path.film.rgb) << name;
        EXPECT_EQ(direct.counters.shadow_rays, path.counters.shadow_rays);
        EXPECT_GT(path.counters.bounce_rays, 0u);
    }
}

TEST(PathIntegrator, SameImageForAnyThreadCount) {
    SceneBuilder b;
    b.set_background(Vec3{0.2f, 0.3f, 0.5f});
    Material glass;
    glass.type = MaterialType::Dielectric;
    Material light = diffuse(Vec3{0.0f});
    light.ke = Vec3{8.0f};
    TriangleMesh mesh;
    add_quad(mesh, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5}, 0);
    testing::add_sphere(mesh, {0, 1, 0}, 1.0f, 2, 1);
    add_quad(mesh, {-1, 4, -1}, {1, 4, -1}, {1, 4, 1}, {-1, 4, 1}, 2);
    add_world_mesh(b, mesh, {diffuse(Vec3{0.6f, 0.5f, 0.4f}), glass, light});
    b.add_light(make_point_light({2, 3, 2}, {5, 5, 5}));
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 2, 6}, {0, 1, 0}, {0, 1, 0}, 45};
    b.set_camera(camera);
    const Scene scene = b.finish();
    RenderSettings settings{40, 30, 8, 5};
    settings.integrator = IntegratorKind::Path;
    const RenderOutput one = render_with(scene, settings, 1);
    for (const int threads : {2, 8}) {
        const RenderOutput many = render_with(scene, settings, threads);
        EXPECT_EQ(one.film.rgb, many.film.rgb) << threads << " threads";
        EXPECT_EQ(one.counters.bounce_rays, many.counters.bounce_rays);
    }
    EXPECT_EQ(one.counters.nonfinite_samples, 0u);
}

TEST(PathIntegrator, NoNonFiniteSamplesOnTheSharedScenes) {
    for (const char* name : {"cornell.json", "phong.json", "bunny.json"}) {
        if (!std::filesystem::exists(kShared / "scenes" / name)) GTEST_SKIP() << "shared/ not found at " << kShared;
        Diagnostics diag;
        const Scene scene = load_scene_file(kShared / "scenes" / name, diag).scene;
        RenderSettings settings{48, 27, 4, 1};
        settings.integrator = IntegratorKind::Path;
        const RenderOutput out = render_with(scene, settings, 0);
        EXPECT_EQ(out.counters.nonfinite_samples, 0u) << name;
        for (float v : out.film.rgb) ASSERT_TRUE(std::isfinite(v)) << name;
    }
}

}  // namespace
}  // namespace sombra
