// Emitters in instances are lights (spec §23): each (instance, emitting
// triangle) pair is one light of the set, placed in world space as its
// flattened copy would be, so the lamps of render/instanced_emitters_test_util.h
// weigh, sample and answer densities as their flattened copies do.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "render/instanced_emitters_test_util.h"
#include "render/lights/lights.h"
#include "render/path_test_util.h"
#include "render/sampler.h"
#include "scene/texture.h"

namespace sombra {
namespace {

using testing::Estimate;
using testing::flattened_triangle;
using testing::kZ;

constexpr double kPi = std::numbers::pi;

// Σ luminance(ke) · area · π · sides over the set's emitters (spec §10's power).
double emitted_power(const LightSet& lights, const Scene& scene) {
    double power = 0;
    for (std::size_t k = 0; k < lights.emitters.size(); ++k) {
        const Emitter e = lights.emitters[k];
        const Material& m = scene.materials[surface_mesh(scene, e.instance).material_ids[e.triangle]];
        power += luminance(m.ke) * lights.emitter_areas[k] * kPi * (m.emits_front_only ? 1.0 : 2.0);
    }
    return power;
}

// Irradiance at x (normal n, every emitter above its horizon) from a
// uniformly emitting triangle of radiance 1 (Lambert's formula), 0 from
// its dark side when it emits from its front only.
double triangle_irradiance(const std::array<Vec3, 3>& p, bool front_only, Vec3 x, Vec3 n) {
    if (front_only && dot(cross(p[1] - p[0], p[2] - p[0]), x - p[0]) <= 0.0f) return 0.0;
    double e = 0;
    for (std::size_t i = 0; i < 3; ++i) {
        const Vec3 a = normalize(p[i] - x), b = normalize(p[(i + 1) % 3] - x);
        const double theta = std::acos(std::clamp(static_cast<double>(dot(a, b)), -1.0, 1.0));
        e += theta * dot(normalize(cross(a, b)), n);
    }
    return 0.5 * std::fabs(e);
}

TEST(InstancedLights, EveryInstanceOfAnEmittingTriangleIsOneLight) {
    const Scene instanced = testing::instanced_lamps();
    const Scene flattened = testing::flattened_lamps();
    ASSERT_EQ(instanced.instances.size(), 12u);
    ASSERT_EQ(instanced.geometry.triangle_count(), 2u) << "the lamps are not copied";
    const LightSet li = make_light_set(instanced, make_constant_environment(Vec3{0.0f}), true);
    const LightSet lf = make_light_set(flattened, make_constant_environment(Vec3{0.0f}), true);
    // Three emitting triangles per lamp: twelve lamps, 36 lights, by tree.
    ASSERT_EQ(li.emitters.size(), 36u);
    ASSERT_EQ(lf.emitters.size(), 36u);
    EXPECT_TRUE(li.use_tree);
    EXPECT_NEAR(emitted_power(li, instanced), emitted_power(lf, flattened), 1e-6 * emitted_power(lf, flattened));
    for (std::size_t k = 0; k < li.emitters.size(); ++k) {
        const Emitter e = li.emitters[k];
        ASSERT_NE(e.instance, kNoInstance);
        // Placed as the builder places the flattened copy, corners swapped where it mirrors.
        const std::uint32_t flat = flattened_triangle(e.instance, e.triangle);
        EXPECT_EQ(world_triangle_corners(instanced, e.triangle, e.instance), triangle_corners(flattened.geometry, flat))
            << "instance " << e.instance << " triangle " << e.triangle;
        EXPECT_EQ(li.emitter_areas[k], lf.emitter_areas[k]);
        EXPECT_EQ(emitter_light(li, e.triangle, e.instance), li.first_emitter() + k);
        EXPECT_EQ(light_kind(li, instanced, li.first_emitter() + static_cast<std::uint32_t>(k)),
                  e.triangle == 2 ? LightKind::Quad : LightKind::Triangle);
    }
    EXPECT_EQ(emitter_light(li, 3, 0), kNoLight) << "the plain triangle emits nothing";
    EXPECT_EQ(emitter_light(li, 0, kNoInstance), kNoLight) << "nor does the floor";
    EXPECT_EQ(emitter_light(li, 0, 12), kNoLight) << "there is no instance 12";
}

TEST(InstancedLights, DensitiesEqualTheFlattenedCopiesUnderPowerSelection) {
    // Chosen in proportion to power, a light's density at a point is its
    // flattened copy's (the same power share, the same world triangle).
    const Scene instanced = testing::instanced_lamps();
    const Scene flattened = testing::flattened_lamps();
    const LightSet li = make_light_set(instanced, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    const LightSet lf = make_light_set(flattened, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    const Vec3 x{0.2f, 0, -0.1f}, n{0, 1, 0};
    for (const Emitter& e : li.emitters) {
        const auto p = world_triangle_corners(instanced, e.triangle, e.instance);
        for (const Vec3 b : {Vec3{0.2f, 0.3f, 0.5f}, Vec3{0.7f, 0.1f, 0.2f}}) {
            const Vec3 y = b.x * p[0] + b.y * p[1] + b.z * p[2];
            const float pi = pdf_light_triangle(li, instanced, e.triangle, e.instance, x, n, y);
            const float pf =
                pdf_light_triangle(lf, flattened, flattened_triangle(e.instance, e.triangle), kNoInstance, x, n, y);
            EXPECT_NEAR(pi, pf, 1e-5f * pf) << "instance " << e.instance << " triangle " << e.triangle;
        }
    }
}

// The unshadowed irradiance estimate Σ L_e cos θ / pdf at x from light
// samples, one channel, against Lambert's formula summed over the
// flattened copies' world triangles: unbiased only when sample_light's
// densities are those of what it samples.
void expect_irradiance_from_light_samples(const Scene& scene, const Scene& flattened, LightSelection selection, Vec3 x,
                                          Vec3 n, std::uint64_t seed, const char* what) {
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), true, selection);
    double expected = 0;
    for (std::uint32_t t = 2; t < flattened.geometry.triangle_count(); ++t) {
        const Material& m = flattened.materials[flattened.geometry.material_ids[t]];
        expected += m.ke.z * triangle_irradiance(triangle_corners(flattened.geometry, t), m.emits_front_only, x, n);
    }
    Estimate e;
    int checked = 0;
    for (std::uint32_t k = 0; k < 40000; ++k) {
        const std::uint32_t i = k + static_cast<std::uint32_t>(seed) * 100000u;
        LightSample ls;
        if (!sample_light(lights, scene, x, n, hash_to_unit(i, 1), hash_to_unit(i, 2), hash_to_unit(i, 3), ls)) {
            e.add(0.0);
            continue;
        }
        // The reported density is the one MIS asks for at the same point.
        if (++checked <= 2000) {
            EXPECT_NEAR(ls.pdf, pdf_light_triangle(lights, scene, ls.triangle, ls.instance, x, n, ls.target),
                        1e-3f * ls.pdf)
                << what;
            EXPECT_EQ(ls.light, emitter_light(lights, ls.triangle, ls.instance)) << what;
        }
        e.add(ls.radiance.z * std::max(0.0f, dot(n, ls.wi)) / ls.pdf);
    }
    ASSERT_GT(expected, 0.0);
    const double z = (e.mean() - expected) / e.standard_error();
    EXPECT_LT(std::fabs(z), kZ) << what << ": " << e.mean() << " ± " << e.standard_error() << ", Lambert " << expected;
}

TEST(InstancedLights, LightSamplingEstimatesLambertsIrradianceFromEveryLamp) {
    const Scene instanced = testing::instanced_lamps();
    const Scene flattened = testing::flattened_lamps();
    // Floor points, and one above every lamp looking down (where only the
    // upside-down lamp's one-sided triangle shines from its front).
    struct Point {
        Vec3 x, n;
    };
    const Point points[] = {{{0, 0, 0}, {0, 1, 0}},
                            {{0.5f, 0, -0.4f}, {0, 1, 0}},
                            {{-1.2f, 0, 1}, {0, 1, 0}},
                            {{0.3f, 2.6f, 1.3f}, {0, -1, 0}}};
    std::uint64_t seed = 1;
    for (const Point& p : points)
        for (const LightSelection selection : {LightSelection::Tree, LightSelection::Power}) {
            const char* what = selection == LightSelection::Tree ? "tree" : "power";
            expect_irradiance_from_light_samples(instanced, flattened, selection, p.x, p.n, ++seed, what);
            expect_irradiance_from_light_samples(flattened, flattened, selection, p.x, p.n, ++seed, what);
        }
}

// A cut-out quad lamp (alpha 1 1 0 0 0 0 1 1 along u: its middle half is
// cut) whose ke is textured by a red-to-blue ramp along u, drawn three times
// (one mirrored) as instances or as flattened copies.
Scene cut_out_textured_lamps(bool instanced) {
    Texture strip, ramp;
    strip.source = "strip";
    ramp.source = "ramp";
    strip.encoding = ramp.encoding = TextureEncoding::Data;
    strip.width = 8;
    ramp.width = 2;
    strip.height = ramp.height = 1;
    strip.channels = 1;
    ramp.channels = 3;
    strip.texels = {1, 1, 0, 0, 0, 0, 1, 1};
    ramp.texels = {1, 0.2f, 0.2f, 0.2f, 0.2f, 1};
    Material lamp;
    lamp.kd = Vec3{0.0f};
    lamp.ke = Vec3{3.0f};
    lamp.textures.alpha_test = true;
    lamp.textures.alpha.texture = 0;
    lamp.textures.ke.texture = 1;
    TriangleMesh mesh;
    testing::add_quad(mesh, {-0.6f, 0, -0.6f}, {0.6f, 0, -0.6f}, {0.6f, 0, 0.6f}, {-0.6f, 0, 0.6f}, 0);
    mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    mesh.uv_indices = {{0, 1, 2}, {0, 2, 3}};
    const std::vector<Transform> placements{
        make_translate({0, 1, 0}), compose(make_scale({-1, 1, 1}), make_translate({1.5f, 1.2f, 0.3f})),
        compose(make_rotate({0, 1, 0}, 90),
                compose(make_scale({0.7f, 1, 1.3f}), make_translate({-1.4f, 0.9f, -0.2f})))};
    SceneBuilder b;
    testing::add_floor(b);
    if (instanced) {
        EXPECT_EQ(b.add_instanced_mesh(mesh, std::vector<Material>{lamp}, std::vector<Texture>{strip, ramp},
                                       MeshPlacement{"/objects/1", "lamp.obj", std::nullopt, std::nullopt}, placements),
                  MeshProblem::None);
    } else {
        for (const Transform& t : placements)
            EXPECT_EQ(b.add_mesh(mesh, std::vector<Material>{lamp}, std::vector<Texture>{strip, ramp},
                                 MeshPlacement{"/objects/1", "lamp.obj", t, std::nullopt}),
                      MeshProblem::None);
    }
    return b.finish();
}

TEST(InstancedLights, SampledPointsReadCutOutsAndEmissionTexturesFromTheInstancesMesh) {
    // Chosen by power, the two scenes' samples land on the same world
    // points: a point on a cut-out part is no light in either, and the ke
    // texture is read at the same uv (up to the rounding of barycentrics
    // found in the mesh's coordinates rather than the world's).
    const Scene instanced = cut_out_textured_lamps(true);
    const Scene flattened = cut_out_textured_lamps(false);
    const LightSet li = make_light_set(instanced, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    const LightSet lf = make_light_set(flattened, make_constant_environment(Vec3{0.0f}), true, LightSelection::Power);
    ASSERT_EQ(li.emitters.size(), 6u);
    const Vec3 x{0.1f, 0, 0.05f}, n{0, 1, 0};
    const int samples = 20000;
    int both = 0, neither = 0, differ = 0;
    float lo = 1e9f, hi = 0;
    for (int k = 0; k < samples; ++k) {
        const auto i = static_cast<std::uint32_t>(k);
        const float u0 = hash_to_unit(i, 31), u1 = hash_to_unit(i, 32), u2 = hash_to_unit(i, 33);
        LightSample a, b;
        const bool in_a = sample_light(li, instanced, x, n, u0, u1, u2, a);
        const bool in_b = sample_light(lf, flattened, x, n, u0, u1, u2, b);
        if (in_a != in_b) {
            ++differ;
            continue;
        }
        if (!in_a) {
            ++neither;
            continue;
        }
        ++both;
        EXPECT_EQ(a.target, b.target);
        EXPECT_EQ(a.triangle, b.triangle - 2 - 2 * a.instance) << "instance " << a.instance;
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(a.radiance[c], b.radiance[c], 1e-4f * b.radiance[c] + 1e-6f);
        lo = std::min(lo, a.radiance.x);
        hi = std::max(hi, a.radiance.x);
    }
    // Half of each lamp is cut; over the rest the red of ke × ramp spans 0.6 to 3.
    EXPECT_GT(neither, samples / 4);
    EXPECT_GT(both, samples / 4);
    EXPECT_LT(hi - lo, 3.0f * 0.8f + 1e-3f);
    EXPECT_GT(hi - lo, 0.5f) << "the texture varies over the sampled points";
    // A point may fall within rounding of the cut's edge: at most a few in 20,000.
    EXPECT_LE(differ, samples / 1000);
}

}  // namespace
}  // namespace sombra
