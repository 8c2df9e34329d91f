// The path integrator with the pbr material's KHR_materials_transmission
// and KHR_materials_volume: white furnaces (a transmissive sphere under a
// uniform sky is invisible when it conserves energy) and Beer–Lambert
// attenuation through a slab against its closed form, as z-tests with the
// sample variance (fixed seeds; render/path_test_util.h).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/path_test_util.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

using testing::add_quad;
using testing::add_world_mesh;
using testing::Estimate;
using testing::expect_agrees;
using testing::PathRun;

Material transmissive(float roughness, float thickness) {
    Material m;
    m.type = MaterialType::Pbr;
    m.base_color = Vec3{1.0f};
    m.metallic = 0.0f;
    m.roughness = roughness;
    m.transmission = 1.0f;
    m.thickness = thickness;
    m.ior = 1.5f;
    return m;
}

TEST(PathVolume, WhiteFurnaceSmoothTransmissiveSpheres) {
    // As the dielectric's furnace: every path carries 1 (Fresnel reflection
    // plus transmission, refracted in a volume or straight through a thin wall).
    for (const float thickness : {1.0f, 0.0f}) {
        SceneBuilder b;
        b.set_background(Vec3{1.0f});
        TriangleMesh sphere;
        testing::add_sphere(sphere, {0, 0, 0}, 1.0f, 3, 0);
        add_world_mesh(b, sphere, {transmissive(0.0f, thickness)});
        const Scene scene = b.finish();
        const PathRun run{scene, 1024};
        for (const Vec3 target : {Vec3{0, 0, 0}, Vec3{0.5f, 0.3f, 0}, Vec3{0.9f, 0.1f, 0}}) {
            const Estimate e = run.estimate({0.1f, 0.2f, 5}, target, 2000, 6);
            expect_agrees(e, 1.0, thickness > 0 ? "volume furnace" : "thin-wall furnace");
        }
    }
}

// A closed box [-s, s]² × [0, d], faces wound counter-clockwise seen from outside.
void add_slab(TriangleMesh& mesh, float s, float d, std::uint32_t material) {
    const Vec3 a{-s, -s, 0}, b{s, -s, 0}, c{s, s, 0}, e{-s, s, 0};
    const Vec3 up{0, 0, d};
    add_quad(mesh, a + up, b + up, c + up, e + up, material);  // top, +z
    add_quad(mesh, a, e, c, b, material);                      // bottom, −z
    add_quad(mesh, a, b, b + up, a + up, material);            // −y
    add_quad(mesh, b, c, c + up, b + up, material);            // +x
    add_quad(mesh, c, e, e + up, c + up, material);            // +y
    add_quad(mesh, e, a, a + up, e + up, material);            // −x
}

TEST(PathVolume, SlabTransmitsBeerLambert) {
    // A slab of thickness d over an emitter of radiance 1 under a black sky,
    // seen at normal incidence: with σ = −ln(colour)/distance,
    //   ior 1 (no Fresnel at normal incidence): T = exp(−σd);
    //   ior 1.5 (F = 0.04 at each face, every internal bounce summed):
    //   T = (1 − F)² exp(−σd) / (1 − F² exp(−2σd)).
    const float d = 1.0f;
    const Vec3 colour{0.5f, 0.8f, 0.2f};
    const float distance = 2.0f;
    for (const float ior : {1.0f, 1.5f}) {
        Material glass = transmissive(0.0f, 1.0f);
        glass.ior = ior;
        glass.attenuation_color = colour;
        glass.attenuation_distance = distance;
        Material light;
        light.type = MaterialType::Diffuse;
        light.kd = Vec3{0.0f};
        light.ke = Vec3{1.0f};
        SceneBuilder b;
        b.set_background(Vec3{0.0f});
        TriangleMesh mesh;
        add_slab(mesh, 50.0f, d, 0);
        add_quad(mesh, {-100, -100, -1}, {100, -100, -1}, {100, 100, -1}, {-100, 100, -1}, 1);
        add_world_mesh(b, mesh, {glass, light});
        const Scene scene = b.finish();
        const PathRun run{scene, 64};
        for (int c = 0; c < 3; ++c) {
            const double sigma = -std::log(static_cast<double>(colour[c])) / distance;
            const double t = std::exp(-sigma * d);
            const double f = ior == 1.0f ? 0.0 : 0.04;
            const double expected = (1 - f) * (1 - f) * t / (1 - f * f * t * t);
            // Straight down through the slab's middle.
            const Estimate e = run.estimate({0.01f, 0.02f, 5}, {0.01f, 0.02f, 0}, 4000, 30 + c, c);
            expect_agrees(e, expected, ior == 1.0f ? "slab, ior 1" : "slab, ior 1.5");
        }
    }
}

}  // namespace
}  // namespace sombra
