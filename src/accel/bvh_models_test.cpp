// BVH against brute force on real meshes from shared/models.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <string>

#include "accel/accel.h"
#include "accel/accel_test_util.h"
#include "io/mesh_file.h"

namespace sombra {
namespace {

using testing::compare_with_brute;
using testing::Comparison;

const std::filesystem::path kModels = std::filesystem::path(SOMBRA_SHARED_DIR) / "models";

// Rays from a sphere twice the bounding box's diagonal around its centre,
// aimed at random points of the box; some with a tmax that stops them short.
std::vector<Ray> rays_from_outside(const TriangleMesh& mesh, int count, std::uint32_t seed) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    for (const Vec3& p : mesh.positions) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    const Vec3 centre = 0.5f * (lo + hi);
    const float radius = 2.0f * length(hi - lo);
    std::mt19937 rng(seed);
    std::normal_distribution<float> gauss;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<Ray> rays;
    while (static_cast<int>(rays.size()) < count) {
        const Vec3 g{gauss(rng), gauss(rng), gauss(rng)};
        if (dot(g, g) < 1e-6f) continue;
        Ray ray;
        ray.origin = centre + radius * normalize(g);
        ray.dir = testing::random_point(rng, lo, hi) - ray.origin;
        if (rays.size() % 4 == 3) ray.tmax = 0.9f + 0.2f * unit(rng);  // ends near the target point
        rays.push_back(ray);
    }
    return rays;
}

class SharedModel : public ::testing::TestWithParam<std::string> {};

TEST_P(SharedModel, BvhEqualsBruteForce) {
    const std::filesystem::path path = kModels / GetParam();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared/ not found at " << kModels;
    Diagnostics diag;
    const LoadedMesh loaded = load_obj(path, diag);
    ASSERT_GT(loaded.mesh.triangles.size(), 900u);
    const int ray_count = loaded.mesh.triangles.size() > 10000 ? 1500 : 4000;
    const Comparison c = compare_with_brute(loaded.mesh, rays_from_outside(loaded.mesh, ray_count, 31));
    EXPECT_EQ(c.mismatches, 0) << c.first_mismatch;
    EXPECT_GT(c.hits, ray_count / 10);
    EXPECT_LT(c.hits, ray_count);

    const Bvh bvh = make_bvh(loaded.mesh);
    EXPECT_EQ(testing::bvh_triangles(bvh).size(), loaded.mesh.triangles.size());  // no degenerate triangles in these
}

INSTANTIATE_TEST_SUITE_P(Models, SharedModel, ::testing::Values("stanford-bunny.obj", "suzanne.obj"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                             return param_info.param == "suzanne.obj" ? std::string("suzanne") : std::string("bunny");
                         });

}  // namespace
}  // namespace sombra
