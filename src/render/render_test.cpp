// Whole images: brute force against the BVH, one thread against many.
#include "render/render.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "io/scene_json/scene_file.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

const std::filesystem::path kShared = SOMBRA_SHARED_DIR;

struct Rendered {
    Film film;
    RayCounters counters;
};

Rendered render_scene(const Scene& scene, AccelKind kind, RenderSettings settings, int threads) {
    const Accel accel = make_accel(scene, kind);
    const RenderJob job = make_render_job(scene, accel, settings, threads);
    RenderProgress progress;
    RenderOutput out = render_image(job, progress);
    EXPECT_FALSE(out.cancelled);
    EXPECT_EQ(progress.samples_done.load(),
              static_cast<std::uint64_t>(settings.width * settings.height * settings.spp));
    return {std::move(out.film), out.counters};
}

Scene load_shared_scene(const char* name) {
    Diagnostics diag;
    return load_scene_file(kShared / "scenes" / name, diag).scene;
}

#define SKIP_WITHOUT_SHARED() \
    if (!std::filesystem::exists(kShared / "scenes")) GTEST_SKIP() << "shared/ not found at " << kShared

// Brute force is the reference; the BVH must give the very same floats.
void expect_brute_equals_bvh(const char* scene_name, int w, int h) {
    const Scene scene = load_shared_scene(scene_name);
    const RenderSettings settings{w, h, 1, 0};
    const Rendered brute = render_scene(scene, AccelKind::Brute, settings, 0);
    const Rendered bvh = render_scene(scene, AccelKind::Bvh, settings, 0);
    EXPECT_EQ(brute.counters.camera_rays, bvh.counters.camera_rays);
    EXPECT_EQ(brute.counters.shadow_rays, bvh.counters.shadow_rays);
    std::size_t differing = 0;
    for (std::size_t k = 0; k < brute.film.rgb.size(); ++k) differing += brute.film.rgb[k] != bvh.film.rgb[k];
    EXPECT_EQ(differing, 0u) << scene_name;
}

TEST(Render, BruteForceAndBvhGiveTheSameImageOnBunny) {
    SKIP_WITHOUT_SHARED();
    expect_brute_equals_bvh("bunny.json", 64, 36);
}

TEST(Render, BruteForceAndBvhGiveTheSameImageOnPhongModels) {
    SKIP_WITHOUT_SHARED();
    expect_brute_equals_bvh("phong.json", 128, 72);
}

TEST(Render, BruteForceAndBvhGiveTheSameImageOnCornellBox) {
    SKIP_WITHOUT_SHARED();
    expect_brute_equals_bvh("cornell.json", 96, 96);
}

TEST(Render, SameBytesForOneAndManyThreads) {
    SKIP_WITHOUT_SHARED();
    const Scene scene = load_shared_scene("phong.json");
    const RenderSettings settings{96, 54, 5, 1234};
    const Rendered one = render_scene(scene, AccelKind::Bvh, settings, 1);
    for (int threads : {2, 3, 8}) {
        const Rendered many = render_scene(scene, AccelKind::Bvh, settings, threads);
        EXPECT_EQ(one.film.rgb, many.film.rgb) << threads << " threads";
        EXPECT_EQ(one.counters.shadow_rays, many.counters.shadow_rays);
    }
}

TEST(Render, SeedChangesTheSamplesButNotTheExpectation) {
    SKIP_WITHOUT_SHARED();
    const Scene scene = load_shared_scene("phong.json");
    const Rendered a = render_scene(scene, AccelKind::Bvh, RenderSettings{64, 36, 16, 1}, 0);
    const Rendered b = render_scene(scene, AccelKind::Bvh, RenderSettings{64, 36, 16, 2}, 0);
    EXPECT_NE(a.film.rgb, b.film.rgb);
    double mean_a = 0, mean_b = 0;
    for (std::size_t k = 0; k < a.film.rgb.size(); ++k) {
        mean_a += a.film.rgb[k];
        mean_b += b.film.rgb[k];
    }
    EXPECT_NEAR(mean_a / mean_b, 1.0, 0.01);
    EXPECT_EQ(a.counters.camera_rays, 64u * 36u * 16u);
}

TEST(Render, CancelStopsEarly) {
    TriangleMesh triangle;
    triangle.positions = {{-1, -1, -5}, {1, -1, -5}, {0, 1, -5}};
    triangle.triangles = {{0, 1, 2}};
    triangle.material_ids = {0};
    SceneBuilder b;
    testing::add_world_mesh(b, triangle, {default_material()});
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 45};
    b.set_camera(camera);
    const Scene scene = b.finish();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, RenderSettings{256, 256, 1, 0});
    RenderProgress progress;
    progress.cancel = true;
    const RenderOutput out = render_image(job, progress);
    EXPECT_TRUE(out.cancelled);
    EXPECT_EQ(progress.samples_done.load(), 0u);
}

}  // namespace
}  // namespace sombra
