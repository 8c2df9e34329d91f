// Media inside objects (spec §26): objects whose interior is a medium,
// "interface" surfaces crossed unchanged, the camera's medium, shadow rays
// through interfaces, and glass around a scattering medium (subsurface
// scattering's random walk), against closed forms as z-tests with the
// sample variance (fixed seeds; render/path_test_util.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/path_test_util.h"
#include "render/test_meshes.h"
#include "scene/light.h"
#include "scene/transform.h"

namespace sombra {
namespace {

using testing::add_box;
using testing::add_quad;
using testing::add_world_mesh;
using testing::emitter;
using testing::Estimate;
using testing::expect_agrees;
using testing::PathRun;

// Adds `mesh` as one object of material `material` (a scene index) bounding
// `boundary` when given.
void add_object(SceneBuilder& b, const TriangleMesh& mesh, std::uint32_t material,
                std::optional<MediumBoundary> boundary) {
    EXPECT_EQ(b.add_mesh(mesh, {}, {}, MeshPlacement{"object", "", std::nullopt, material, std::move(boundary)}),
              MeshProblem::None);
}

// An emitter of radiance 1 filling the plane z = 0.
void add_emitting_floor(SceneBuilder& b) {
    TriangleMesh floor;
    add_quad(floor, {-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}, 0);
    add_world_mesh(b, floor, {emitter(1.0f)});
}

TEST(PathMediaObjects, AnInterfaceBoxKeepsBeersLawAlongWhatItEncloses) {
    // The camera looks down through 1.2 units of an absorbing box's interior
    // onto the emitter: exp(−σ_a·1.2); the box's surfaces themselves are invisible.
    const Vec3 sigma_a{0.5f, 1.0f, 2.0f};
    SceneBuilder b;
    b.set_media({testing::homogeneous(sigma_a, Vec3{0.0f})}, kNoMedium);
    add_emitting_floor(b);
    TriangleMesh box;
    add_box(box, {-1, -1, 0.5f}, {1, 1, 1.7f}, 0);
    add_object(b, box, b.interface_material(), MediumBoundary{0, kNoMedium});
    const Scene scene = b.finish();
    const PathRun run{scene, 8};
    for (int c = 0; c < 3; ++c)
        expect_agrees(run.estimate({0.01f, 0.02f, 3.0f}, {0.01f, 0.02f, 0.0f}, 2000, 10 + c, c),
                      std::exp(-1.2 * static_cast<double>(sigma_a[c])), "through the box");
}

TEST(PathMediaObjects, TheCameraStartsInItsMedium) {
    // From inside the box (camera medium set), 0.6 units of it to the floor.
    const Vec3 sigma_a{0.5f, 1.0f, 2.0f};
    SceneBuilder b;
    b.set_media({testing::homogeneous(sigma_a, Vec3{0.0f})}, kNoMedium);
    b.set_camera_medium(0);
    add_emitting_floor(b);
    TriangleMesh box;
    add_box(box, {-1, -1, 0.5f}, {1, 1, 1.7f}, 0);
    add_object(b, box, b.interface_material(), MediumBoundary{0, kNoMedium});
    const Scene scene = b.finish();
    const PathRun run{scene, 8};
    for (int c = 0; c < 3; ++c)
        expect_agrees(run.estimate({0.01f, 0.02f, 1.1f}, {0.01f, 0.02f, 0.0f}, 2000, 20 + c, c),
                      std::exp(-0.6 * static_cast<double>(sigma_a[c])), "from inside");
}

TEST(PathMediaObjects, AnInterfaceWithoutInteriorKeepsTheCurrentMedium) {
    // Fog fills the scene; a box of interface surfaces without an interior
    // changes nothing: Beer's law over the whole 3 units.
    const Vec3 sigma_a{0.2f, 0.4f, 0.6f};
    SceneBuilder b;
    b.set_media({testing::homogeneous(sigma_a, Vec3{0.0f})}, 0);
    add_emitting_floor(b);
    TriangleMesh box;
    add_box(box, {-1, -1, 0.5f}, {1, 1, 1.7f}, 0);
    add_object(b, box, b.interface_material(), std::nullopt);
    const Scene scene = b.finish();
    const PathRun run{scene, 8};
    for (int c = 0; c < 3; ++c)
        expect_agrees(run.estimate({0.01f, 0.02f, 3.0f}, {0.01f, 0.02f, 0.0f}, 2000, 30 + c, c),
                      std::exp(-3.0 * static_cast<double>(sigma_a[c])), "interface without interior");
}

TEST(PathMediaObjects, ShadowRaysCrossInterfacesWithTheirTransmittance) {
    // A point light 3 above a white diffuse floor; between them 1.2 units of
    // an absorbing box. The camera sees the floor beside the box: the point
    // under the light gets I/r²·(1/π)·exp(−σ_a·1.2). Under `direct` media are
    // ignored and the box does not block: I/r²·(1/π).
    const Vec3 sigma_a{0.5f, 1.0f, 2.0f};
    const float intensity = 9.0f;
    SceneBuilder b;
    b.set_media({testing::homogeneous(sigma_a, Vec3{0.0f})}, kNoMedium);
    b.add_light(make_point_light({0, 0, 3}, Vec3{intensity}));
    TriangleMesh floor;
    add_quad(floor, {-50, -50, 0}, {50, -50, 0}, {50, 50, 0}, {-50, 50, 0}, 0);
    Material white;
    white.kd = Vec3{1.0f};
    add_world_mesh(b, floor, {white});
    TriangleMesh box;
    add_box(box, {-0.5f, -0.5f, 0.5f}, {0.5f, 0.5f, 1.7f}, 0);
    add_object(b, box, b.interface_material(), MediumBoundary{0, kNoMedium});
    const Scene scene = b.finish();
    const PathRun run{scene, 1};
    const Vec3 eye{2.0f, 0.0f, 0.3f};
    const double unblocked = intensity / 9.0 / std::numbers::pi;
    for (int c = 0; c < 3; ++c)
        expect_agrees(run.estimate(eye, {0, 0, 0}, 64, 40 + c, c), unblocked * std::exp(-1.2 * sigma_a[c]),
                      "shadow ray through the box");

    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const LightSet lights = make_light_set(scene, make_constant_environment(Vec3{0.0f}), false);
    const IntegratorContext ctx{&scene, &accel, &lights};
    RayCounters counters;
    EXPECT_NEAR(trace_direct(ctx, Ray{eye, -eye}, counters).x, unblocked, 1e-5 * unblocked);
    // Seen from above, through the box's top, `direct` sees the floor too.
    EXPECT_NEAR(trace_direct(ctx, Ray{{0.0f, 0.01f, 2.5f}, {0.0f, 0.0f, -1.0f}}, counters).x, unblocked,
                1e-3 * unblocked);
}

TEST(PathMediaObjects, AScatteringSphereUnderAWhiteSkyStaysWhite) {
    // The medium furnace of spec §26's proof: a sphere of a medium that
    // scatters and does not absorb, under a constant environment of
    // radiance 1, is radiance 1 seen from anywhere, at any g.
    std::uint64_t seed = 50;
    for (const float g : {0.0f, 0.8f, -0.6f}) {
        SceneBuilder b;
        b.set_background(Vec3{1.0f});
        b.set_media({testing::homogeneous(Vec3{0.0f}, {0.5f, 1.5f, 3.0f}, g)}, kNoMedium);
        TriangleMesh sphere;
        testing::add_sphere(sphere, Vec3{0.0f}, 1.0f, 3, 0);
        add_object(b, sphere, b.interface_material(), MediumBoundary{0, kNoMedium});
        const Scene scene = b.finish();
        PathRun run{scene, 8};
        run.max_volume_depth = 65536;
        for (int c = 0; c < 3; ++c)
            expect_agrees(run.estimate({0.0f, 0.0f, 3.0f}, {0.1f, 0.2f, 0.0f}, 4000, ++seed, c), 1.0,
                          ("interface furnace, g " + std::to_string(g)).c_str());
    }
}

TEST(PathMediaObjects, GlassAroundAScatteringMediumStaysWhiteUnderAWhiteSky) {
    // Subsurface scattering's random walk: the same furnace behind a smooth
    // dielectric boundary (ior 1.33). Refraction, total internal reflection
    // and scattering lose nothing: radiance 1, given depths enough for the
    // reflections inside (surface events count against max_depth).
    std::uint64_t seed = 60;
    for (const float g : {0.0f, 0.8f}) {
        SceneBuilder b;
        b.set_background(Vec3{1.0f});
        b.set_media({testing::homogeneous(Vec3{0.0f}, {2.0f, 4.0f, 8.0f}, g)}, kNoMedium);
        Material glass;
        glass.type = MaterialType::Dielectric;
        glass.ior = 1.33f;
        const std::uint32_t glass_index = b.add_material(glass);
        TriangleMesh sphere;
        testing::add_sphere(sphere, Vec3{0.0f}, 1.0f, 3, 0);
        add_object(b, sphere, glass_index, MediumBoundary{0, kNoMedium});
        const Scene scene = b.finish();
        PathRun run{scene, 4096};
        run.max_volume_depth = 65536;
        for (int c = 0; c < 3; ++c)
            expect_agrees(run.estimate({0.0f, 0.0f, 3.0f}, {0.1f, 0.2f, 0.0f}, 3000, ++seed, c), 1.0,
                          ("glass furnace, g " + std::to_string(g)).c_str());
    }
}

TEST(PathMediaObjects, AnAbsorbingInteriorDarkensGlassByBeersLaw) {
    // Looking straight through a smooth glass slab (box) of absorbing interior
    // at the emitter: each face lets (1 − F₀) through at normal incidence,
    // and the light travels 1.2 inside: (1 − F₀)²·exp(−σ_a·1.2), plus the
    // light reflected back and forth inside (a geometric series in F₀²·T²).
    const Vec3 sigma_a{0.5f, 1.0f, 2.0f};
    SceneBuilder b;
    b.set_media({testing::homogeneous(sigma_a, Vec3{0.0f})}, kNoMedium);
    add_emitting_floor(b);
    Material glass;
    glass.type = MaterialType::Dielectric;
    glass.ior = 1.5f;
    const std::uint32_t glass_index = b.add_material(glass);
    TriangleMesh box;
    add_box(box, {-5, -5, 0.5f}, {5, 5, 1.7f}, 0);
    add_object(b, box, glass_index, MediumBoundary{0, kNoMedium});
    const Scene scene = b.finish();
    const PathRun run{scene, 64};
    const double f0 = 0.04;  // ((1.5 − 1)/(1.5 + 1))²
    for (int c = 0; c < 3; ++c) {
        const double t = std::exp(-1.2 * static_cast<double>(sigma_a[c]));
        const double expected = (1 - f0) * (1 - f0) * t / (1 - f0 * f0 * t * t);
        expect_agrees(run.estimate({0.0f, 0.0f, 3.0f}, {0.0f, 0.0f, 0.0f}, 20000, 70 + c, c), expected,
                      "absorbing glass");
    }
}

// A grid medium of density 1 over world [−1, 1]³ (dense coordinates 1 … 10,
// padded with zeros beyond), inside an interface box of that size.
Medium constant_grid(Vec3 sigma_a, Vec3 sigma_s, float g) {
    auto grid = std::make_shared<DensityGrid>();
    grid->dims = {12, 12, 12};
    for (int k = 0; k < 12; ++k)
        for (int j = 0; j < 12; ++j)
            for (int i = 0; i < 12; ++i)
                grid->values.push_back(i > 0 && i < 11 && j > 0 && j < 11 && k > 0 && k < 11 ? 1.0f : 0.0f);
    build_majorants(*grid);
    Medium m = testing::homogeneous(sigma_a, sigma_s, g);
    m.density = grid;
    m.world_to_grid = compose(make_scale(Vec3{4.5f}), make_translate(Vec3{5.5f}));
    grid->index_to_world = inverse_affine(m.world_to_grid);
    return m;
}

TEST(PathMediaObjects, AGridMediumKeepsBeersLawAndItsFurnace) {
    {
        // An absorbing grid: 2 units of density 1 between the camera and the emitter.
        const Vec3 sigma_a{0.3f, 0.6f, 1.2f};
        SceneBuilder b;
        b.set_media({constant_grid(sigma_a, Vec3{0.0f}, 0.0f)}, kNoMedium);
        TriangleMesh floor;
        add_quad(floor, {-50, -50, -3}, {50, -50, -3}, {50, 50, -3}, {-50, 50, -3}, 0);
        add_world_mesh(b, floor, {emitter(1.0f)});
        TriangleMesh box;
        add_box(box, Vec3{-1.0f}, Vec3{1.0f}, 0);
        add_object(b, box, b.interface_material(), MediumBoundary{0, kNoMedium});
        const Scene scene = b.finish();
        const PathRun run{scene, 8};
        for (int c = 0; c < 3; ++c)
            expect_agrees(run.estimate({0.1f, 0.2f, 3.0f}, {0.1f, 0.2f, 0.0f}, 4000, 80 + c, c),
                          std::exp(-2.0 * static_cast<double>(sigma_a[c])), "through the grid");
    }
    std::uint64_t seed = 90;
    for (const float g : {0.0f, 0.7f}) {
        // A scattering grid under a white sky stays white.
        SceneBuilder b;
        b.set_background(Vec3{1.0f});
        b.set_media({constant_grid(Vec3{0.0f}, {1.0f, 2.0f, 4.0f}, g)}, kNoMedium);
        TriangleMesh box;
        add_box(box, Vec3{-1.0f}, Vec3{1.0f}, 0);
        add_object(b, box, b.interface_material(), MediumBoundary{0, kNoMedium});
        const Scene scene = b.finish();
        PathRun run{scene, 8};
        run.max_volume_depth = 65536;
        for (int c = 0; c < 3; ++c)
            expect_agrees(run.estimate({0.0f, 0.0f, 3.0f}, {0.1f, 0.2f, 0.0f}, 4000, ++seed, c), 1.0,
                          ("grid furnace, g " + std::to_string(g)).c_str());
    }
}

TEST(PathMediaObjects, EachInstanceOfAnObjectHoldsItsOwnPlacementOfAGrid) {
    // Two drawings of one interface box, the second 4 units along x, each
    // with its grid placed by its own transform: 2 units of density 1 seen
    // through either (the second would be empty with the first's placement).
    const Vec3 sigma_a{0.3f, 0.6f, 1.2f};
    const Transform moved = make_translate({4, 0, 0});
    Medium here = constant_grid(sigma_a, Vec3{0.0f}, 0.0f);
    Medium there = here;
    ASSERT_TRUE(place_grid_medium(there, moved));
    SceneBuilder b;
    b.set_media({here, there}, kNoMedium);
    TriangleMesh floor;
    add_quad(floor, {-50, -50, -3}, {50, -50, -3}, {50, 50, -3}, {-50, 50, -3}, 0);
    add_world_mesh(b, floor, {emitter(1.0f)});
    TriangleMesh box;
    add_box(box, Vec3{-1.0f}, Vec3{1.0f}, 0);
    MeshPlacement placement{"boxes", "", std::nullopt, b.interface_material(), MediumBoundary{0, kNoMedium, {0, 1}}};
    ASSERT_EQ(b.add_instanced_mesh(box, {}, {}, placement, std::vector<Transform>{Transform{}, moved}),
              MeshProblem::None);
    const Scene scene = b.finish();
    const PathRun run{scene, 8};
    for (const float x : {0.1f, 4.1f})
        for (int c = 0; c < 3; ++c)
            expect_agrees(run.estimate({x, 0.2f, 3.0f}, {x, 0.2f, 0.0f}, 4000, 100 + c, c),
                          std::exp(-2.0 * static_cast<double>(sigma_a[c])), "through each drawing's grid");
}

}  // namespace
}  // namespace sombra
