// Spot and directional lights (spec §16) against their closed forms, pixel
// by pixel, under `direct`; `path` at depth 1 gives the same floats; a glTF
// file's spot and sun render like the equivalent scene file.
#include "render/delta_lights.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "io/scene_json/scene_file.h"
#include "render/plane_view_test_util.h"
#include "render/render.h"
#include "render/test_meshes.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

using testing::add_quad;
using testing::camera_looking_down;
using testing::plane_hit;

constexpr double kPi = 3.14159265358979323846;

RenderOutput render(const Scene& scene, const Camera& camera, RenderSettings settings) {
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderJob job = make_render_job(scene, accel, settings, 0);
    job.camera = camera;
    RenderProgress progress;
    return render_image(job, progress);
}

// A diffuse plane y = 0 under `lights`, with `more` triangles (their
// material ids index `more_materials`), assembled by the SceneBuilder.
Scene plane_scene(Vec3 kd, const std::vector<PunctualLight>& lights, const TriangleMesh& more = {},
                  const std::vector<Material>& more_materials = {}) {
    TriangleMesh plane;
    // Small enough that a hit point's rounding (~6e-8 of the corners'
    // size) stays far below what moves a spot's falloff.
    const float e = 10;
    add_quad(plane, {-e, 0, -e}, {e, 0, -e}, {e, 0, e}, {-e, 0, e}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, plane, {Material{"plane", MaterialType::Diffuse, kd, {}, 1, {}}});
    if (more.triangle_count() > 0) testing::add_world_mesh(b, more, more_materials);
    for (const PunctualLight& light : lights) b.add_light(light);
    return b.finish();
}

TEST(DeltaLights, PlaneUnderASpotLightMatchesTheClosedFormInsideOnAndOutsideTheCone) {
    // L = I·s²/r² · kd/π · cos θ_x, s from the angle to the spot's axis.
    const Vec3 position{0.3f, 2.0f, -0.2f}, intensity{10, 20, 5}, kd{0.8f, 0.5f, 0.25f};
    const Scene scene = plane_scene(kd, {make_spot_light(position, {0.2f, -1, 0.1f}, intensity, 30, 12)});
    const PunctualLight& spot = scene.lights[0];
    const int w = 96, h = 72;
    const Camera camera = camera_looking_down(3.0f, 0.6f);
    const Film film = render(scene, camera, RenderSettings{w, h, 1, 0}).film;
    int inside = 0, falloff = 0, outside = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            double x, z;
            plane_hit(camera, i, j, w, h, x, z);
            const double dx = position.x - x, dy = position.y, dz = position.z - z;
            const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
            const double cos_axis = -(spot.direction.x * dx + spot.direction.y * dy + spot.direction.z * dz) / r;
            const double s = std::clamp(
                (cos_axis - spot.cos_outer) / std::max(1e-3, double(spot.cos_inner) - spot.cos_outer), 0.0, 1.0);
            const double geometric = dy / (r * r * r) / kPi;
            const Vec3 got = film.at(i, j);
            (s == 1 ? inside : s == 0 ? outside : falloff)++;
            for (int c = 0; c < 3; ++c) {
                const double full = intensity[c] * kd[c] * geometric;  // s = 1
                // Float rounding of cos θ moves s by ~1e-6 in the falloff band.
                ASSERT_NEAR(got[c], s * s * full, 1e-4 * s * s * full + 1e-5 * full)
                    << "pixel " << i << "," << j << " channel " << c << " s " << s;
                if (s == 0) {
                    ASSERT_EQ(got[c], 0.0f) << "outside the cone: exactly nothing";
                }
            }
        }
    EXPECT_GT(inside, 200);
    EXPECT_GT(falloff, 200);
    EXPECT_GT(outside, 200);
}

TEST(DeltaLights, PlaneUnderADirectionalLightIsUniformExceptInTheOccludersShadow) {
    // L = E · kd/π · cos θ everywhere the sun reaches; the shadow of a square
    // at height 1 is the square moved along d to y = 0.
    const Vec3 irradiance{2, 1, 0.5f}, kd{0.8f, 0.5f, 0.25f};
    const Vec3 d{0.3f, -1, 0.2f};
    const float x0 = -0.25f, x1 = 0.35f, z0 = -0.3f, z1 = 0.2f;
    TriangleMesh occluder;
    add_quad(occluder, {x0, 1, z0}, {x1, 1, z0}, {x1, 1, z1}, {x0, 1, z1}, 0);
    const Scene scene = plane_scene(kd, {make_directional_light(d, irradiance)}, occluder,
                                    {Material{"occluder", MaterialType::Diffuse, kd, {}, 1, {}}});
    const int w = 96, h = 96;
    const Camera camera = camera_looking_down(0.9f, 1.2f);  // below the occluder
    const Film film = render(scene, camera, RenderSettings{w, h, 1, 0}).film;
    const double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
    const double cos_theta = -d.y / len;
    const double shift_x = d.x / -d.y, shift_z = d.z / -d.y;  // from y = 1 to y = 0
    const double margin = 0.03;                               // a pixel's footprint is 0.0225
    int shadowed = 0, lit = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            double x, z;
            plane_hit(camera, i, j, w, h, x, z);
            const double sx = x - shift_x, sz = z - shift_z;  // where the shadow ray crosses y = 1
            const bool in = sx > x0 + margin && sx < x1 - margin && sz > z0 + margin && sz < z1 - margin;
            const bool out = sx < x0 - margin || sx > x1 + margin || sz < z0 - margin || sz > z1 + margin;
            const Vec3 got = film.at(i, j);
            for (int c = 0; c < 3; ++c) {
                if (in) {
                    ASSERT_EQ(got[c], 0.0f) << "pixel " << i << "," << j;
                }
                const double expected = irradiance[c] * kd[c] / kPi * cos_theta;
                if (out) {
                    ASSERT_NEAR(got[c], expected, 1e-5 * expected) << "pixel " << i << "," << j;
                }
            }
            shadowed += in;
            lit += out;
        }
    EXPECT_GT(shadowed, 300);
    EXPECT_GT(lit, 5000);
}

TEST(DeltaLights, LightsBehindTheSurfaceOrFacingAwayGiveNothingWithoutAShadowRay) {
    const Scene scene =
        plane_scene(Vec3{0.5f}, {make_directional_light({0, 1, 0}, Vec3{3}),                // shines upward: from below
                                 make_spot_light({0, 1, 0}, {0, 1, 0}, Vec3{3}, 80, 10)});  // points away
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderSettings settings{4, 4, 1, 0};
    const RenderJob job = make_render_job(scene, accel, settings, 1);
    const IntegratorContext ctx = make_integrator_context(job);
    RayCounters counters;
    EXPECT_EQ(trace_direct(ctx, Ray{{0.1f, 0.5f, 0}, {0, -1, 0}}, counters), Vec3{0.0f});
    EXPECT_EQ(counters.shadow_rays, 0u);
}

TEST(DeltaLights, PathAtDepthOneGivesTheDirectImage) {
    TriangleMesh box;
    add_quad(box, {-0.4f, 0.5f, -0.4f}, {0.4f, 0.5f, -0.4f}, {0.4f, 0.6f, 0.4f}, {-0.4f, 0.6f, 0.4f}, 0);
    Scene scene = plane_scene(Vec3{0.7f, 0.6f, 0.5f},
                              {make_spot_light({0.5f, 2, 0.3f}, {-0.2f, -1, -0.1f}, Vec3{6, 5, 4}, 40, 20),
                               make_directional_light({-0.4f, -1, 0.3f}, Vec3{1.5f, 1.2f, 1}),
                               make_point_light({-1, 1.5f, 1}, Vec3{2})},
                              box, {Material{"box", MaterialType::Phong, Vec3{0.3f, 0.4f, 0.5f}, Vec3{0.4f}, 30, {}}});
    scene.camera.look_at = CameraLookAt{{0, 2.5f, 2.5f}, {0, 0, 0}, {0, 1, 0}, 50};
    RenderSettings settings{64, 48, 2, 7};
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderProgress progress;
    const RenderOutput direct = render_image(make_render_job(scene, accel, settings, 0), progress);
    settings.integrator = IntegratorKind::Path;
    settings.max_depth = 1;
    const RenderOutput path = render_image(make_render_job(scene, accel, settings, 0), progress);
    // Same shading code, same order of operations: the very same floats.
    EXPECT_EQ(direct.film.rgb, path.film.rgb);
    EXPECT_EQ(direct.counters.shadow_rays, path.counters.shadow_rays);
    double sum = 0;
    for (float v : direct.film.rgb) sum += v;
    EXPECT_GT(sum, 100.0) << "the lights light the scene";
}

// The same spot and sun from a glTF file (KHR_lights_punctual: candela and
// lux, the node's −z axis) and from a scene file (W/sr and W/m²).
TEST(DeltaLights, GltfSpotAndSunRenderLikeTheEquivalentSceneFile) {
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("sombra_delta_lights_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    // A 4 × 4 quad at y = 0 (two triangles, float positions, uint16 indices),
    // a spot 3 above it looking down (rotated −90° about x: −z → −y), and a
    // sun whose node turns −z by 90° toward (0.6, −0.8, 0).
    const std::string positions =
        "AAAAwAAAAAAAAADAAAAAQAAAAAAAAADAAAAAQAAAAAAAAABAAAAAwAAAAAAAAABA";  // (-2,0,-2) (2,0,-2) (2,0,2) (-2,0,2)
    const std::string indices = "AAACAAEAAAADAAIA";                          // 0 2 1, 0 3 2
    // The rotation taking −z to (0.6, −0.8, 0), perpendicular to it: 90°
    // about the axis (−z) × target.
    const double angle = kPi / 2;
    const Vec3 axis = normalize(cross(Vec3{0, 0, -1}, Vec3{0.6f, -0.8f, 0}));
    const double sh = std::sin(angle / 2), ch = std::cos(angle / 2);
    std::ofstream(dir / "lit.gltf") << R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2]}],
      "extensionsUsed": ["KHR_lights_punctual"],
      "extensions": {"KHR_lights_punctual": {"lights": [
        {"type": "spot", "color": [1, 0.5, 0.25], "intensity": 4098, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.6}},
        {"type": "directional", "color": [0.5, 1, 1], "intensity": 683}]}},
      "nodes": [{"mesh": 0},
                {"translation": [0.2, 3, 0.1], "rotation": [-0.7071067811865476, 0, 0, 0.7071067811865476],
                 "extensions": {"KHR_lights_punctual": {"light": 0}}},
                {"rotation": [)" << axis.x * sh
                                    << ", " << axis.y * sh << ", " << axis.z * sh << ", " << ch
                                    << R"(], "extensions": {"KHR_lights_punctual": {"light": 1}}}],
      "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
      "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-2, 0, -2], "max": [2, 0, 2]},
                    {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
      "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)"
                                    << positions << indices << R"("}]})";
    std::ofstream(dir / "quad.obj") << "v -2 0 -2\nv 2 0 -2\nv 2 0 2\nv -2 0 2\nf 1 3 2\nf 1 4 3\n";
    const std::string camera =
        R"("camera": {"origin": [0, 4, 3], "look_at": [0, 0, 0]}, "render": {"width": 48, "height": 36})";
    std::ofstream(dir / "gltf.json") << "{" << camera << R"(, "objects": [{"file": "lit.gltf"}]})";
    std::ofstream(dir / "json.json") << "{" << camera << R"(, "objects": [{"file": "quad.obj"}], "lights": [
        {"type": "spot", "position": [0.2, 3, 0.1], "direction": [0, -1, 0], "intensity": [6, 3, 1.5],
         "inner_angle": 11.459155902616464, "outer_angle": 34.37746770784939},
        {"type": "directional", "direction": [0.6, -0.8, 0], "irradiance": [0.5, 1, 1]}]})";
    Diagnostics diag;
    const Scene from_gltf = load_scene_file(dir / "gltf.json", diag).scene;
    const LoadedScene json = load_scene_file(dir / "json.json", diag);
    const Scene& from_json = json.scene;
    std::filesystem::remove_all(dir);
    ASSERT_EQ(from_gltf.lights.size(), 2u);
    const RenderSettings settings = json.settings;
    const Accel accel_a = make_accel(from_gltf, AccelKind::Bvh), accel_b = make_accel(from_json, AccelKind::Bvh);
    RenderProgress progress;
    const Film a = render_image(make_render_job(from_gltf, accel_a, settings, 0), progress).film;
    const Film b = render_image(make_render_job(from_json, accel_b, settings, 0), progress).film;
    float peak = 0;
    for (float v : b.rgb) peak = std::max(peak, v);
    EXPECT_GT(peak, 0.1f);
    for (std::size_t k = 0; k < a.rgb.size(); ++k) {
        // The two differ by the float rounding of unit conversions and
        // rotations, which moves a spot's falloff by ~1e-6 near its edge.
        ASSERT_NEAR(a.rgb[k], b.rgb[k], 1e-4 * b.rgb[k] + 1e-5 * peak) << "value " << k;
    }
}

}  // namespace
}  // namespace sombra
