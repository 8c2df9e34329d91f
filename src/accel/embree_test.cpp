// The Embree yardstick against sombra's BVH: the same hits to float rounding
// (Embree's intersector rounds differently, is not watertight at edges and
// breaks ties its own way) and, through the same shading code, the same
// images. Compiled only in builds with Embree.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "accel/accel.h"
#include "accel/accel_test_util.h"
#include "accel/embree_image_compare.h"
#include "accel/embree_plugin.h"
#include "io/mesh_file.h"
#include "io/scene_json/scene_file.h"
#include "render/render.h"

namespace sombra {
namespace {

const std::filesystem::path kShared = SOMBRA_SHARED_DIR;

Ray make_ray(Vec3 o, Vec3 d, float tmax = INFINITY) {
    Ray r;
    r.origin = o;
    r.dir = d;
    r.tmax = tmax;
    return r;
}

TEST(EmbreeBackend, IsOfferedByName) {
    ASSERT_EQ(parse_accel_kind("embree"), AccelKind::Embree);
    EXPECT_EQ(accel_name(AccelKind::Embree), "embree");
    const std::vector<std::string_view> names = available_accels();
    EXPECT_NE(std::find(names.begin(), names.end(), "embree"), names.end());
}

// Embree's (u, v) are the weights of the second and third corner, as sombra's
// (b1, b2); t is in units of the (unnormalised) direction.
TEST(EmbreeBackend, BarycentricsAndTMatchTheCorners) {
    TriangleMesh mesh;
    testing::add_triangle(mesh, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
    const Accel accel = make_accel(mesh, AccelKind::Embree);
    Hit hit;
    ASSERT_TRUE(intersect(accel, make_ray({0.2f, 0.3f, 1}, {0, 0, -2}), hit));
    EXPECT_NEAR(hit.t, 0.5f, 1e-6f);
    EXPECT_NEAR(hit.b1, 0.2f, 1e-6f);
    EXPECT_NEAR(hit.b2, 0.3f, 1e-6f);
    EXPECT_EQ(hit.triangle, 0u);
    // Both faces count.
    ASSERT_TRUE(intersect(accel, make_ray({0.6f, 0.1f, -1}, {0, 0, 1}), hit));
    EXPECT_NEAR(hit.b1, 0.6f, 1e-6f);
    EXPECT_NEAR(hit.b2, 0.1f, 1e-6f);
    EXPECT_FALSE(intersect(accel, make_ray({0.6f, 0.6f, 1}, {0, 0, -1}), hit));  // outside the hypotenuse
}

// sombra's rays are open at both ends: a hit exactly at tmax does not count.
TEST(EmbreeBackend, TmaxIsExclusiveAndTZeroIsNotAHit) {
    TriangleMesh mesh;
    testing::add_triangle(mesh, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0});
    for (const AccelKind kind : {AccelKind::Bvh, AccelKind::Embree}) {
        const Accel accel = make_accel(mesh, kind);
        Hit hit;
        EXPECT_FALSE(intersect(accel, make_ray({0, 0, 1}, {0, 0, -1}, 1.0f), hit)) << accel_name(kind);
        EXPECT_FALSE(occluded(accel, make_ray({0, 0, 1}, {0, 0, -1}, 1.0f))) << accel_name(kind);
        EXPECT_TRUE(intersect(accel, make_ray({0, 0, 1}, {0, 0, -1}, std::nextafter(1.0f, 2.0f)), hit))
            << accel_name(kind);
        EXPECT_TRUE(occluded(accel, make_ray({0, 0, 1}, {0, 0, -1}, std::nextafter(1.0f, 2.0f)))) << accel_name(kind);
        EXPECT_FALSE(intersect(accel, make_ray({0, 0, 0}, {0, 0, -1}), hit)) << accel_name(kind);  // origin on it
        EXPECT_FALSE(intersect(accel, make_ray({0, 0, 1}, {0, 0, -1}, 0.0f), hit)) << accel_name(kind);
        EXPECT_FALSE(intersect(accel, make_ray({0, 0, 1}, {0, 0, -1}, -1.0f), hit)) << accel_name(kind);
    }
}

// Triangles sombra can never hit are not handed to Embree, and the indices
// Embree reports are mapped back to the mesh's.
TEST(EmbreeBackend, SkipsUnhittableTrianglesAndKeepsMeshIndices) {
    TriangleMesh mesh;
    testing::add_triangle(mesh, {-1, -1, 1}, {0, 0, 1}, {1, 1, 1});     // 0: collinear
    testing::add_triangle(mesh, {-1, -1, 2}, {1, -1, 2}, {0, 1, 2});    // 1: made out of range below
    testing::add_triangle(mesh, {-1, -1, 3}, {1, -1, NAN}, {0, 1, 3});  // 2: non-finite corner
    testing::add_triangle(mesh, {-1, -1, 4}, {1, -1, 4}, {0, 1, 4});    // 3: the one to hit
    mesh.triangles[1][2] = 1000;
    const Accel accel = make_accel(mesh, AccelKind::Embree);
    Hit hit;
    ASSERT_TRUE(intersect(accel, make_ray({0, 0, 0}, {0, 0, 1}), hit));
    EXPECT_EQ(hit.triangle, 3u);
    EXPECT_NEAR(hit.t, 4.0f, 1e-5f);
    EXPECT_TRUE(occluded(accel, make_ray({0, 0, 0}, {0, 0, 1})));
    EXPECT_FALSE(occluded(accel, make_ray({0, 0, 0}, {0, 0, 1}, 3.5f)));
}

TEST(EmbreeBackend, EmptyMeshAndUntraceableRaysHitNothing) {
    const TriangleMesh empty;
    const Accel none = make_accel(empty, AccelKind::Embree);
    Hit hit;
    EXPECT_FALSE(intersect(none, make_ray({0, 0, 0}, {0, 0, 1}), hit));
    EXPECT_FALSE(occluded(none, make_ray({0, 0, 0}, {0, 0, 1})));

    TriangleMesh mesh;
    testing::add_triangle(mesh, {-1, -1, 1}, {1, -1, 1}, {0, 1, 1});
    const Accel accel = make_accel(mesh, AccelKind::Embree);
    EXPECT_FALSE(intersect(accel, make_ray({0, 0, 0}, {0, 0, 0}), hit));
    EXPECT_FALSE(intersect(accel, make_ray({0, 0, NAN}, {0, 0, 1}), hit));
    EXPECT_FALSE(occluded(accel, make_ray({0, 0, 0}, {0, INFINITY, 1})));
}

// Memory: what Embree allocated is counted, and it grows with the mesh.
TEST(EmbreeBackend, MemoryIsCountedAndGrowsWithTheMesh) {
    const TriangleMesh small = testing::random_soup(1000, 5, 0.05f);
    const TriangleMesh large = testing::random_soup(100000, 6, 0.01f);
    const std::size_t small_bytes = accel_memory_bytes(make_accel(small, AccelKind::Embree));
    const std::size_t large_bytes = accel_memory_bytes(make_accel(large, AccelKind::Embree));
    // More than the vertex copy alone (36 bytes a triangle in a soup).
    EXPECT_GT(large_bytes, 100000u * 40u);
    EXPECT_LT(large_bytes, 100000u * 1000u);
    EXPECT_GT(large_bytes, 10 * small_bytes);
}

// How one ray's answers from the two backends compare.
struct Agreement {
    int rays = 0, hits = 0;
    int near_edge = 0;   // differ, but a hit lies within rounding of an edge (Embree is not watertight)
    int ties = 0;        // different triangles at the same t
    int mismatches = 0;  // anything else
    std::string first_mismatch;
};

float min_weight(const Hit& h) { return std::min({1.0f - h.b1 - h.b2, h.b1, h.b2}); }

// t to 1e-4 relative, or, for hits very near the origin, to float rounding of
// the origin's coordinates (t·|d| is then tiny next to |o|).
bool same_t(const Ray& ray, float a, float b) {
    const float near_origin = 1e-5f * (max_component(abs(ray.origin)) + 1.0f) / length(ray.dir);
    return std::fabs(a - b) <= 1e-4f * std::max(std::fabs(a), std::fabs(b)) + near_origin;
}

// The barycentrics of the same triangle name the same point to 1e-4 of the
// distance travelled (plus the origin's rounding, as in same_t): for grazing
// rays the weights themselves can differ far more than the point they name.
bool same_point(const TriangleMesh& mesh, const Ray& ray, const Hit& a, const Hit& b) {
    const Index3& tri = mesh.triangles[a.triangle];
    auto point = [&](const Hit& h) {
        return (1 - h.b1 - h.b2) * mesh.positions[tri[0]] + h.b1 * mesh.positions[tri[1]] +
               h.b2 * mesh.positions[tri[2]];
    };
    return length(point(a) - point(b)) <= 1e-4f * a.t * length(ray.dir) + 1e-5f * max_component(abs(ray.origin));
}

// Embree built at its default quality, or with `high_quality` at
// RTC_BUILD_QUALITY_HIGH (spatial splits: the benchmarks' other yardstick).
Agreement compare_with_bvh(const TriangleMesh& mesh, const std::vector<Ray>& rays, bool high_quality = false) {
    const Accel bvh = make_accel(mesh, AccelKind::Bvh);
    Accel embree;
    embree.kind = AccelKind::Embree;
    embree.mesh = &mesh;
    embree.embree_api = &embree_plugin();
    embree.embree = embree.embree_api->make_mesh_scene(mesh, {}, high_quality, false);
    constexpr float kEdge = 1e-4f;  // a weight this small is within rounding of an edge
    Agreement a;
    for (const Ray& ray : rays) {
        Hit hb, he;
        const bool fb = intersect(bvh, ray, hb);
        const bool fe = intersect(embree, ray, he);
        const bool oe = occluded(embree, ray);
        ++a.rays;
        a.hits += fb;
        bool ok = oe == fe;  // Embree agrees with itself
        if (fb && fe) {
            if (hb.triangle == he.triangle) {
                ok = ok && same_t(ray, hb.t, he.t) && same_point(mesh, ray, hb, he);
            } else if (same_t(ray, hb.t, he.t)) {
                ++a.ties;
            } else if (min_weight(hb) < kEdge || min_weight(he) < kEdge) {
                ++a.near_edge;  // one of them slipped past an edge onto something behind
            } else {
                ok = false;
            }
        } else if (fb != fe) {
            const Hit& h = fb ? hb : he;
            if (min_weight(h) < kEdge || same_t(ray, h.t, ray.tmax)) {
                ++a.near_edge;
            } else {
                ok = false;
            }
        }
        if (!ok && a.mismatches++ == 0) {
            a.first_mismatch = testing::describe(ray) + ": bvh " + testing::describe(fb, hb) + ", embree " +
                               testing::describe(fe, he) + (oe ? " (occluded)" : "");
        }
    }
    return a;
}

// Rays from a sphere around the model aimed into its box, and rays from
// inside the box (many start close to the surface); some stop short.
std::vector<Ray> model_rays(const TriangleMesh& mesh, int count, std::uint32_t seed) {
    Vec3 lo{INFINITY}, hi{-INFINITY};
    for (const Vec3& p : mesh.positions) {
        lo = min(lo, p);
        hi = max(hi, p);
    }
    std::vector<Ray> rays = testing::random_rays(mesh, count / 2, seed, lo, hi);
    std::mt19937 rng(seed + 1);
    std::normal_distribution<float> gauss;
    const Vec3 centre = 0.5f * (lo + hi);
    const float radius = 2.0f * length(hi - lo);
    while (static_cast<int>(rays.size()) < count) {
        const Vec3 g{gauss(rng), gauss(rng), gauss(rng)};
        if (dot(g, g) < 1e-6f) continue;
        const Vec3 o = centre + radius * normalize(g);
        rays.push_back(make_ray(o, testing::random_point(rng, lo, hi) - o));
    }
    return rays;
}

class EmbreeOnModel : public ::testing::TestWithParam<std::string> {};

TEST_P(EmbreeOnModel, HitsAgreeWithTheBvh) {
    const std::filesystem::path path = kShared / "models" / GetParam();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared/ not found at " << kShared;
    Diagnostics diag;
    const LoadedMesh loaded = load_mesh_file(path, diag);
    constexpr int kRays = 20000;
    const Agreement a = compare_with_bvh(loaded.mesh, model_rays(loaded.mesh, kRays, 17));
    std::printf("[ embree     ] %-20s %d rays, %d hits, %d ties, %d near-edge differences, %d mismatches\n",
                GetParam().c_str(), a.rays, a.hits, a.ties, a.near_edge, a.mismatches);
    EXPECT_EQ(a.mismatches, 0) << a.first_mismatch;
    EXPECT_GT(a.hits, kRays / 10);
    EXPECT_LE(a.near_edge + a.ties, kRays / 500);  // rare: at most 0.2 % of rays
}

TEST_P(EmbreeOnModel, HighQualityHitsAgreeWithTheBvh) {
    const std::filesystem::path path = kShared / "models" / GetParam();
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared/ not found at " << kShared;
    Diagnostics diag;
    const LoadedMesh loaded = load_mesh_file(path, diag);
    constexpr int kRays = 20000;
    const Agreement a = compare_with_bvh(loaded.mesh, model_rays(loaded.mesh, kRays, 18), true);
    std::printf("[ embree HQ  ] %-20s %d rays, %d hits, %d ties, %d near-edge differences, %d mismatches\n",
                GetParam().c_str(), a.rays, a.hits, a.ties, a.near_edge, a.mismatches);
    EXPECT_EQ(a.mismatches, 0) << a.first_mismatch;
    EXPECT_GT(a.hits, kRays / 10);
    EXPECT_LE(a.near_edge + a.ties, kRays / 500);
}

INSTANTIATE_TEST_SUITE_P(Models, EmbreeOnModel,
                         ::testing::Values("stanford-bunny.obj", "suzanne.obj", "teapot.obj", "dragon-res2.obj"),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                             std::string name = param_info.param.substr(0, param_info.param.find('.'));
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

// Two radiances agree when every channel does to 1e-3 relative: far below
// what an 8-bit PNG shows, far above the rounding of a slightly different t
// or barycentric. A different triangle or shadow changes a pixel by much more.
class EmbreeOnScene : public ::testing::TestWithParam<std::string> {};

TEST_P(EmbreeOnScene, ImageEqualsTheBvhImage) {
    const std::filesystem::path path = kShared / "scenes" / (GetParam() + ".json");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared/ not found at " << kShared;
    Diagnostics diag;
    const LoadedScene loaded = load_scene_file(path, diag);
    const Scene& scene = loaded.scene;
    RenderSettings settings = loaded.settings;
    settings.width = 192;
    settings.height = loaded.settings.height * 192 / loaded.settings.width;
    const testing::ImageAgreement r = testing::compare_bvh_with_embree(scene, settings);
    const std::size_t pixels = r.pixels, differing = r.differing, lit = r.lit;
    ASSERT_GT(pixels, 0u);
    std::printf("[ embree     ] %-12s %zu of %zu pixels differ\n", GetParam().c_str(), differing, pixels);
    EXPECT_GT(lit, pixels / 10);          // the picture shows something
    EXPECT_LE(differing * 1000, pixels);  // identical in at least 99.9 % of pixels
    EXPECT_EQ(r.bvh_camera_rays, r.embree_camera_rays);
}

INSTANTIATE_TEST_SUITE_P(Scenes, EmbreeOnScene, ::testing::Values("bunny", "dragon", "cornell", "phong", "manylights"));

}  // namespace
}  // namespace sombra
