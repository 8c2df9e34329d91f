// The Embree yardstick through instances (spec §23): Embree's own two-level
// instancing answers as sombra's BVH under its tree over instances, to float
// rounding (Embree inverts the instance matrices itself, in float), with the
// same instance and triangle reported, cut-outs honoured inside instances,
// and the instanced mesh stored once. Compiled only in builds with Embree.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_test_util.h"
#include "accel/embree_image_compare.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

Ray make_ray(Vec3 o, Vec3 d, float tmax = INFINITY) {
    Ray r;
    r.origin = o;
    r.dir = d;
    r.tmax = tmax;
    return r;
}

// `count` placements of a unit-box mesh inside [0, 10]³: random turns and
// sizes, every third one mirrored.
std::vector<Transform> random_instances(int count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Transform> out;
    for (int i = 0; i < count; ++i) {
        const float s = 0.5f + 1.5f * unit(rng);
        Transform t = make_scale({i % 3 == 0 ? -s : s, s * (0.7f + 0.6f * unit(rng)), s});
        t = compose(t, make_rotate(testing::random_point(rng, Vec3{-1.0f}, Vec3{1.0f}) + Vec3{0, 0, 0.01f},
                                   360.0f * unit(rng)));
        out.push_back(compose(t, make_translate(testing::random_point(rng, Vec3{0.0f}, Vec3{9.0f}))));
    }
    return out;
}

// A scene of `instances` drawings of `mesh` (its material ids index
// `materials`) and, when `world` has triangles, that world geometry.
Scene instanced_scene(const TriangleMesh& mesh, const std::vector<Material>& materials,
                      const std::vector<Transform>& instances, const TriangleMesh& world = {}) {
    SceneBuilder builder;
    MeshPlacement placement;
    placement.name = "/objects/0";
    EXPECT_EQ(builder.add_instanced_mesh(mesh, materials, {}, placement, instances), MeshProblem::None);
    if (!world.triangles.empty()) {
        MeshPlacement world_placement;
        world_placement.name = "/objects/1";
        EXPECT_EQ(builder.add_mesh(world, materials, {}, world_placement), MeshProblem::None);
    }
    return builder.finish();
}

TEST(EmbreeInstancing, ReportsTheInstanceAndTheMeshsOwnTriangle) {
    TriangleMesh mesh;
    testing::add_triangle(mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    // The second drawing is mirrored in x and twice the size.
    const Scene scene = instanced_scene(
        mesh, {Material{}}, {make_translate({0, 0, -1}), compose(make_scale({-2, 2, 2}), make_translate({0, 0, -3}))});
    const Accel accel = make_accel(scene, AccelKind::Embree);
    EXPECT_EQ(accel.instances, nullptr);  // Embree instances on its own
    Hit hit;
    ASSERT_TRUE(intersect(accel, make_ray({0.2f, 0.3f, 1}, {0, 0, -2}), hit));
    EXPECT_EQ(hit.instance, 0u);
    EXPECT_EQ(hit.triangle, 0u);
    EXPECT_NEAR(hit.t, 1.0f, 1e-6f);  // the world ray's parameter
    EXPECT_NEAR(hit.b1, 0.2f, 1e-6f);
    EXPECT_NEAR(hit.b2, 0.3f, 1e-6f);
    EXPECT_FALSE(hit.has_corners);
    // (−0.4, 0.6) in the world is the mesh's own (0.2, 0.3) in the second.
    ASSERT_TRUE(intersect(accel, make_ray({-0.4f, 0.6f, -2}, {0, 0, -1}), hit));
    EXPECT_EQ(hit.instance, 1u);
    EXPECT_NEAR(hit.t, 1.0f, 1e-6f);
    EXPECT_NEAR(hit.b1, 0.2f, 1e-6f);
    EXPECT_NEAR(hit.b2, 0.3f, 1e-6f);
    EXPECT_TRUE(occluded(accel, make_ray({-0.4f, 0.6f, -2}, {0, 0, -1}, 1.01f)));
    EXPECT_FALSE(occluded(accel, make_ray({-0.4f, 0.6f, -2}, {0, 0, -1}, 0.99f)));
    EXPECT_FALSE(intersect(accel, make_ray({0.6f, 0.6f, 1}, {0, 0, -1}), hit));  // between them both
}

// Random rays through 40 drawings of a triangle soup and a world soup
// around them: the same hits as the BVH's to float rounding.
TEST(EmbreeInstancing, HitsAndShadowsAgreeWithTheBvh) {
    TriangleMesh mesh = testing::random_soup(500, 7, 0.2f);
    TriangleMesh world = testing::random_soup(200, 8, 0.4f);
    for (Vec3& p : world.positions) p = 10.0f * p;
    const Scene scene = instanced_scene(mesh, {Material{}}, random_instances(40, 9), world);
    const Accel bvh = make_accel(scene, AccelKind::Bvh);
    const Accel embree = make_accel(scene, AccelKind::Embree);

    std::mt19937 rng(10);
    const int rays = 4000;
    int both = 0, hit_mismatch = 0, surface_mismatch = 0, shadow_mismatch = 0, world_hits = 0, instance_hits = 0;
    for (int i = 0; i < rays; ++i) {
        const Vec3 o = testing::random_point(rng, Vec3{-3.0f}, Vec3{13.0f});
        const Vec3 target = testing::random_point(rng, Vec3{0.0f}, Vec3{10.0f});
        const Ray ray = make_ray(o, target - o);
        Hit a, b;
        const bool ha = intersect(bvh, ray, a), hb = intersect(embree, ray, b);
        if (ha != hb) {
            ++hit_mismatch;
            continue;
        }
        // A shadow ray to the target point: blocked or not alike.
        if (occluded(bvh, make_ray(o, target - o, 1.0f)) != occluded(embree, make_ray(o, target - o, 1.0f)))
            ++shadow_mismatch;
        if (!ha) continue;
        ++both;
        (a.instance == kNoInstance ? world_hits : instance_hits) += 1;
        if (a.instance != b.instance || a.triangle != b.triangle) {
            ++surface_mismatch;
            EXPECT_NEAR(a.t, b.t, 1e-3f * a.t + 1e-5f) << "ray " << i;  // a neighbour at about the same t
            continue;
        }
        // Relative, plus the rounding of the origin carried into the instance.
        EXPECT_NEAR(a.t, b.t, 1e-4f * a.t + 1e-5f) << "ray " << i;
        EXPECT_NEAR(a.b1, b.b1, 1e-3f) << "ray " << i;
        EXPECT_NEAR(a.b2, b.b2, 1e-3f) << "ray " << i;
    }
    // Both kinds of geometry were met often, and disagreements are edge cases.
    EXPECT_GT(world_hits, 1000);
    EXPECT_GT(instance_hits, 400);
    EXPECT_LE(hit_mismatch, rays / 200);
    EXPECT_LE(surface_mismatch, both / 100);
    EXPECT_LE(shadow_mismatch, rays / 200);
}

// A cut-out triangle in front of an opaque one, drawn twice: rays pass the
// cut-out in either instance, for Embree's filter as for the BVH.
TEST(EmbreeInstancing, CutOutsHoldInsideInstances) {
    TriangleMesh mesh;
    testing::add_triangle(mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});     // cut out
    testing::add_triangle(mesh, {0, 0, -1}, {1, 0, -1}, {0, 1, -1});  // opaque
    mesh.material_ids = {1, 0};
    Material cut;
    cut.textures.alpha_test = true;
    cut.textures.alpha_factor = 0.2f;  // below the 0.5 cutoff everywhere
    TriangleMesh world;
    testing::add_triangle(world, {-10, -10, -20}, {10, -10, -20}, {0, 10, -20});
    world.material_ids = {0};
    const Scene scene =
        instanced_scene(mesh, {Material{}, cut}, {make_translate({0, 0, 0}), make_translate({5, 0, 0})}, world);
    for (const AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
        const Accel accel = make_accel(scene, kind);
        for (std::uint32_t instance = 0; instance < 2; ++instance) {
            const Vec3 o{0.2f + 5.0f * static_cast<float>(instance), 0.3f, 1};
            Hit hit;
            ASSERT_TRUE(intersect(accel, make_ray(o, {0, 0, -1}), hit)) << accel_name(kind);
            EXPECT_EQ(hit.instance, instance) << accel_name(kind);
            EXPECT_EQ(hit.triangle, 1u) << accel_name(kind);
            EXPECT_NEAR(hit.t, 2.0f, 1e-5f) << accel_name(kind);
            EXPECT_FALSE(occluded(accel, make_ray(o, {0, 0, -1}, 1.5f))) << accel_name(kind);
            EXPECT_TRUE(occluded(accel, make_ray(o, {0, 0, -1}, 2.5f))) << accel_name(kind);
        }
        // Past the instances, the world triangle.
        Hit hit;
        ASSERT_TRUE(intersect(accel, make_ray({2.5f, 0.3f, 1}, {0, 0, -1}), hit)) << accel_name(kind);
        EXPECT_EQ(hit.instance, kNoInstance) << accel_name(kind);
        EXPECT_NEAR(hit.t, 21.0f, 1e-4f) << accel_name(kind);
    }
}

// The mesh is built once however often it is drawn: 64 drawings cost a
// small fraction of 64 flattened copies.
TEST(EmbreeInstancing, StoresTheMeshOnce) {
    const TriangleMesh mesh = testing::random_soup(5000, 11);
    const std::vector<Transform> instances = random_instances(64, 12);
    const Scene instanced = instanced_scene(mesh, {Material{}}, instances);
    TriangleMesh flat;
    for (const Transform& t : instances) {
        const auto base = static_cast<std::uint32_t>(flat.positions.size());
        for (const Vec3& p : mesh.positions) flat.positions.push_back(transform_point(t, p));
        for (const Index3& tri : mesh.triangles)
            flat.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
    }
    const std::size_t once = accel_memory_bytes(make_accel(instanced, AccelKind::Embree));
    const std::size_t copies = accel_memory_bytes(make_accel(flat, AccelKind::Embree));
    EXPECT_GT(once, 0u);
    EXPECT_LT(once * 8, copies);
}

// A scene file's instanced bunnies (turned, scaled, one mirrored) on a
// floor, rendered through each backend: the same image but for a few
// pixels at edges (same_pixel: 1e-3 relative per channel).
TEST(EmbreeInstancing, ImageEqualsTheBvhImage) {
    const std::filesystem::path model = std::filesystem::path(SOMBRA_SHARED_DIR) / "models" / "stanford-bunny.obj";
    if (!std::filesystem::exists(model)) GTEST_SKIP() << "shared/ not found at " << SOMBRA_SHARED_DIR;
    const std::filesystem::path dir =
        std::filesystem::temp_directory_path() / ("sombra_embree_instancing_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "bunnies.json";
    std::ofstream(file) << R"({"render": {"width": 192, "height": 108, "spp": 1},
      "camera": {"origin": [0, 2.2, 5], "look_at": [0, 0.6, 0], "fov": 45},
      "materials": {"bunny": {"type": "phong", "kd": [0.6, 0.5, 0.4], "ks": [0.3, 0.3, 0.3], "shininess": 30},
                    "floor": {"type": "diffuse", "kd": [0.5, 0.5, 0.5]}},
      "lights": [{"type": "point", "position": [2, 4, 3], "intensity": [30, 30, 30]},
                 {"type": "directional", "direction": [-0.3, -1, -0.2], "irradiance": [0.5, 0.5, 0.6]}],
      "objects": [{"file": ")" +
                               model.string() + R"(", "material": "bunny",
                   "transform": [{"scale": 10}, {"translate": [0.17, -0.33, 0]}],
                   "instances": [[{"translate": [-1.6, 0, 0]}],
                                 [{"scale": [-1, 1, 1]}, {"rotate": {"axis": [0, 1, 0], "degrees": 40}}],
                                 [{"scale": 0.7}, {"rotate": {"axis": [0, 1, 0], "degrees": -70}},
                                  {"translate": [1.6, 0, 0.4]}]]},
                  {"file": ")" +
                               (model.parent_path() / "plane.obj").string() + R"(", "material": "floor",
                   "transform": [{"scale": 5}]}]})";
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(file, diag);
    std::filesystem::remove_all(dir);
    const Scene& scene = loaded.scene;
    ASSERT_EQ(scene.instances.size(), 3u);
    const testing::ImageAgreement r = testing::compare_bvh_with_embree(scene, loaded.settings);
    const std::size_t pixels = r.pixels, differing = r.differing, lit = r.lit;
    ASSERT_GT(pixels, 0u);
    std::printf("[ embree     ] instanced bunnies: %zu of %zu pixels differ\n", differing, pixels);
    EXPECT_GT(lit, pixels / 10);
    EXPECT_LE(differing * 500, pixels);  // identical in at least 99.8 % of pixels
}

}  // namespace
}  // namespace sombra
