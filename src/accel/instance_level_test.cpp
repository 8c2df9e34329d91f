// The two-level structure (spec §23) against brute force: instanced meshes
// placed by rotations, non-uniform scales and mirrors, beside world
// geometry; every ray must get the same answer, bit for bit, from the BVH's
// tree over instances as from the loop over every instance and triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_test_util.h"
#include "scene/scene_builder.h"

namespace sombra {
namespace {

using testing::random_point;
using testing::random_soup;

// A scene of `instances` drawings of two random soups (one of them
// mirrored every third time) scattered over [-4, 4]³, and a soup in the
// world geometry.
Scene instanced_soups(int instances, std::uint32_t seed) {
    SceneBuilder builder;
    const std::uint32_t grey = builder.add_material(Material{"grey", MaterialType::Diffuse, Vec3{0.5f}});
    const MeshPlacement world{"world", "", compose(make_translate(Vec3{-0.5f}), make_scale(Vec3{3.0f})), grey};
    EXPECT_EQ(builder.add_mesh(random_soup(200, seed), {}, {}, world), MeshProblem::None);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int m = 0; m < 2; ++m) {
        std::vector<Transform> placed;
        for (int i = m; i < instances; i += 2) {
            Transform t = make_translate(Vec3{-0.5f});  // the soup's centre at the origin
            const float s = 0.5f + unit(rng);
            t = compose(t, make_scale(Vec3{i % 3 == 0 ? -s : s, s * (0.5f + unit(rng)), s}));
            t = compose(t, make_rotate(random_point(rng, Vec3{-1.0f}, Vec3{1.0f}), 360.0f * unit(rng)));
            t = compose(t, make_translate(random_point(rng, Vec3{-4.0f}, Vec3{4.0f})));
            placed.push_back(t);
        }
        const MeshPlacement placement{"soup " + std::to_string(m), "", std::nullopt, grey};
        EXPECT_EQ(builder.add_instanced_mesh(random_soup(300 + 100 * m, seed + 1 + m), {}, {}, placement, placed),
                  MeshProblem::None);
    }
    return builder.finish();
}

// Rays between random points of the scene's box, a third of them short.
std::vector<Ray> rays_through(int count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Ray> rays;
    for (int i = 0; i < count; ++i) {
        Ray ray;
        ray.origin = random_point(rng, Vec3{-6.0f}, Vec3{6.0f});
        ray.dir = random_point(rng, Vec3{-4.0f}, Vec3{4.0f}) - ray.origin;
        if (i % 7 == 3) ray.dir.y = 0.0f;  // axis-parallel slabs in the top-level test
        if (i % 3 == 2) ray.tmax = unit(rng);
        rays.push_back(ray);
    }
    return rays;
}

TEST(InstanceLevel, BvhAgreesWithBruteForceBitForBitThroughInstances) {
    const Scene scene = instanced_soups(40, 7);
    ASSERT_EQ(scene.instances.size(), 40u);
    const Accel brute = make_accel(scene, AccelKind::Brute);
    const Accel bvh = make_accel(scene, AccelKind::Bvh);
    int hits = 0, in_instances = 0, mirrored = 0;
    for (const Ray& ray : rays_through(5000, 11)) {
        Hit want, got;
        const bool want_found = intersect(brute, ray, want);
        const bool got_found = intersect(bvh, ray, got);
        ASSERT_EQ(want_found, got_found) << testing::describe(ray);
        // Shadow rays: each backend's occluded() agrees with its intersect().
        ASSERT_EQ(occluded(brute, ray), want_found) << testing::describe(ray);
        ASSERT_EQ(occluded(bvh, ray), got_found) << testing::describe(ray);
        if (!want_found) continue;
        ++hits;
        ASSERT_EQ(want.instance, got.instance) << testing::describe(ray);
        ASSERT_EQ(want.triangle, got.triangle) << testing::describe(ray);
        ASSERT_EQ(want.t, got.t) << testing::describe(ray);
        ASSERT_EQ(want.b1, got.b1) << testing::describe(ray);
        ASSERT_EQ(want.b2, got.b2) << testing::describe(ray);
        if (got.instance != kNoInstance) {
            ++in_instances;
            mirrored += scene.instances[got.instance].mirrored;
            EXPECT_EQ(got.corners, triangle_corners(surface_mesh(scene, got.instance), got.triangle));
        }
    }
    // The rays must exercise what they test: hits in the world geometry, in instances, mirrored ones.
    EXPECT_GT(hits - in_instances, 200);
    EXPECT_GT(in_instances, 1000);
    EXPECT_GT(mirrored, 200);
}

TEST(InstanceLevel, AHitInAnInstanceLiesOnTheInstancesTriangleInWorldSpace) {
    const Scene scene = instanced_soups(20, 3);
    const Accel bvh = make_accel(scene, AccelKind::Bvh);
    int checked = 0;
    for (const Ray& ray : rays_through(4000, 5)) {
        Hit hit;
        if (!intersect(bvh, ray, hit) || hit.instance == kNoInstance) continue;
        const Transform& m = scene.instances[hit.instance].object_to_world;
        const auto [p0, p1, p2] = triangle_corners(surface_mesh(scene, hit.instance), hit.triangle);
        const Vec3 on_triangle = transform_point(m, (1 - hit.b1 - hit.b2) * p0 + hit.b1 * p1 + hit.b2 * p2);
        const Vec3 on_ray = ray.origin + hit.t * ray.dir;
        // The same point, reached two ways: to within float rounding of the scene's size (~10).
        EXPECT_LT(length(on_triangle - on_ray), 1e-4f) << testing::describe(ray);
        ++checked;
    }
    EXPECT_GT(checked, 500);
}

TEST(InstanceLevel, TheClosestOfWorldGeometryAndInstancesWins) {
    // A unit square at z = 0 in the world, and instances of it at z = 1 and z = -1.
    TriangleMesh square;
    square.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    square.triangles = {{0, 1, 2}, {0, 2, 3}};
    SceneBuilder builder;
    const std::uint32_t grey = builder.add_material(Material{"grey", MaterialType::Diffuse, Vec3{0.5f}});
    ASSERT_EQ(builder.add_mesh(square, {}, {}, MeshPlacement{"world", "", std::nullopt, grey}), MeshProblem::None);
    const std::vector<Transform> placed{make_translate({0, 0, 1}), make_translate({0, 0, -1})};
    ASSERT_EQ(builder.add_instanced_mesh(square, {}, {}, MeshPlacement{"pair", "", std::nullopt, grey}, placed),
              MeshProblem::None);
    const Scene scene = builder.finish();
    for (const AccelKind kind : {AccelKind::Brute, AccelKind::Bvh}) {
        const Accel accel = make_accel(scene, kind);
        Hit hit;
        ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.1f, 5}, {0, 0, -1}}, hit));
        EXPECT_EQ(hit.instance, 0u);
        EXPECT_EQ(hit.t, 4.0f);
        ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.1f, 0.5f}, {0, 0, -1}}, hit));
        EXPECT_EQ(hit.instance, kNoInstance) << "the world square at z = 0 is nearer";
        EXPECT_EQ(hit.t, 0.5f);
        ASSERT_TRUE(intersect(accel, Ray{{0.2f, 0.1f, -5}, {0, 0, 1}}, hit));
        EXPECT_EQ(hit.instance, 1u);
        EXPECT_FALSE(intersect(accel, Ray{{0.2f, 0.1f, 5}, {0, 0, -1}, 3.5f}, hit)) << "tmax stops before z = 1";
        EXPECT_FALSE(occluded(accel, Ray{{0.2f, 0.1f, 5}, {0, 0, -1}, 3.5f}));
        EXPECT_TRUE(occluded(accel, Ray{{0.2f, 0.1f, -5}, {0, 0, 1}, 4.5f}));
    }
}

TEST(InstanceLevel, UntraceableRaysAndEmptyMeshesHitNothing) {
    SceneBuilder builder;
    const std::uint32_t grey = builder.add_material(Material{"grey", MaterialType::Diffuse, Vec3{0.5f}});
    const std::vector<Transform> placed{Transform{}, make_translate({0, 0, 1})};
    ASSERT_EQ(builder.add_instanced_mesh(TriangleMesh{}, {}, {}, MeshPlacement{"empty", "", std::nullopt, grey},
                                         placed),
              MeshProblem::None);
    ASSERT_EQ(builder.add_instanced_mesh(random_soup(10, 1), {}, {}, MeshPlacement{"soup", "", std::nullopt, grey},
                                         placed),
              MeshProblem::None);
    const Scene scene = builder.finish();
    const float nan = std::nanf("");
    for (const AccelKind kind : {AccelKind::Brute, AccelKind::Bvh}) {
        const Accel accel = make_accel(scene, kind);
        Hit hit;
        EXPECT_FALSE(intersect(accel, Ray{{0.5f, 0.5f, 5}, {0, 0, 0}}, hit));
        EXPECT_FALSE(intersect(accel, Ray{{nan, 0.5f, 5}, {0, 0, -1}}, hit));
        EXPECT_FALSE(occluded(accel, Ray{{0.5f, 0.5f, 5}, {nan, 0, -1}}));
    }
}

}  // namespace
}  // namespace sombra
