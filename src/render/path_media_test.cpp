// The path integrator in a homogeneous medium filling the scene (spec §26),
// against closed forms as z-tests with the sample variance (fixed seeds;
// render/path_test_util.h): light through an absorbing medium (Beer's
// law), a medium furnace (an emitting box of radiance 1 around a purely
// scattering medium stays 1 at any g), and single scattering from a point
// light against its integral along the ray in double.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>

#include "render/media/phase_function.h"
#include "render/path_test_util.h"
#include "render/test_meshes.h"
#include "scene/light.h"

namespace sombra {
namespace {

using testing::add_quad;
using testing::add_world_mesh;
using testing::emitter;
using testing::Estimate;
using testing::expect_agrees;
using testing::PathRun;

TEST(PathMedia, AnAbsorbingMediumKeepsBeersLawOfAnEmitter) {
    // An emitter of radiance 1 seen through distance d of a medium that only
    // absorbs, differently per channel: exp(−σ_a d).
    const Vec3 sigma_a{0.5f, 1.0f, 2.0f};
    const float d = 1.2f;
    SceneBuilder b;
    b.set_background(Vec3{0.0f});
    TriangleMesh mesh;
    add_quad(mesh, {-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}, 0);
    add_world_mesh(b, mesh, {emitter(1.0f)});
    b.set_media({testing::homogeneous(sigma_a, Vec3{0.0f})}, 0);
    const Scene scene = b.finish();
    const PathRun run{scene, 8};
    for (int c = 0; c < 3; ++c) {
        const Estimate e = run.estimate({0.01f, 0.02f, d}, {0.01f, 0.02f, 0}, 20000, 50 + c, c);
        expect_agrees(e, std::exp(-static_cast<double>(sigma_a[c]) * d), "absorbing medium");
    }
}

TEST(PathMedia, AMediumFurnaceStaysWhiteAtAnyG) {
    // Inside a closed box whose black walls emit radiance 1, a medium that
    // scatters and does not absorb changes nothing: radiance 1 everywhere,
    // whatever the phase function and the extinction per channel.
    std::uint64_t seed = 70;
    for (const float g : {0.0f, 0.7f, -0.5f}) {
        SceneBuilder b;
        b.set_background(Vec3{0.0f});
        TriangleMesh mesh;
        testing::add_box(mesh, Vec3{-1.0f}, Vec3{1.0f}, 0);
        add_world_mesh(b, mesh, {emitter(1.0f)});
        b.set_media({testing::homogeneous(Vec3{0.0f}, {0.5f, 1.5f, 3.0f}, g)}, 0);
        const Scene scene = b.finish();
        const PathRun run{scene, 8};
        for (int c = 0; c < 3; ++c) {
            const Estimate e = run.estimate({0.1f, 0.2f, 0.3f}, {0.6f, -0.4f, 0.9f}, 4000, ++seed, c);
            expect_agrees(e, 1.0, ("furnace, g " + std::to_string(g)).c_str());
        }
    }
}

TEST(PathMedia, SingleScatteringFromAPointLightMatchesItsIntegral) {
    // A point light of intensity I in an unbounded medium, seen along a ray
    // that passes beside it, scattering once (max_volume_depth 1):
    //   L = ∫₀^∞ e^{−σ_t s} σ_s p(d·ω(s)) I e^{−σ_t r(s)} / r(s)² ds,
    // with x(s) = o + s·d, r = |c − x|, ω = (c − x)/r, integrated in double.
    const Vec3 sigma_a{0.1f, 0.05f, 0.2f}, sigma_s{0.2f, 0.3f, 0.1f};
    const float g = 0.6f;
    const Vec3 intensity{2.0f, 3.0f, 5.0f}, light{0.5f, 1.0f, 3.0f};
    const Vec3 origin{0.0f, 0.0f, 0.0f}, towards{0.0f, 0.0f, 1.0f};
    SceneBuilder b;
    b.set_background(Vec3{0.0f});
    b.add_light(make_point_light(light, intensity));
    TriangleMesh mesh;  // a speck far away: the scene needs a surface
    testing::add_triangle(mesh, {900, 900, 900}, {901, 900, 900}, {900, 901, 900}, 0);
    add_world_mesh(b, mesh, {emitter(0.0f)});
    b.set_media({testing::homogeneous(sigma_a, sigma_s, g)}, 0);
    const Scene scene = b.finish();
    PathRun run{scene, 8};
    run.max_volume_depth = 1;
    for (int c = 0; c < 3; ++c) {
        const double st = static_cast<double>(sigma_a[c]) + sigma_s[c];
        double expected = 0;
        constexpr int steps = 400000;
        constexpr double s_max = 120.0;
        for (int i = 0; i < steps; ++i) {
            const double s = (i + 0.5) * s_max / steps;
            const double dx = light.x - origin.x, dy = light.y - origin.y, dz = light.z - (origin.z + s);
            const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
            const double cos_theta = dz / r;  // d = +z
            expected += std::exp(-st * s) * sigma_s[c] * henyey_greenstein(g, static_cast<float>(cos_theta)) *
                        intensity[c] * std::exp(-st * r) / (r * r) * (s_max / steps);
        }
        const Estimate e = run.estimate(origin, towards, 40000, 90 + c, c);
        expect_agrees(e, expected, "single scattering");
    }
}

}  // namespace
}  // namespace sombra
