// The thin lens of spec §17: r = 0 is the pinhole bit for bit; every lens
// sample of an image point meets the same point of the focus plane; a point
// off that plane spreads over the circle of confusion the thin-lens
// geometry predicts, in the rendered image.
#include <gtest/gtest.h>

#include <cmath>

#include "render/camera.h"
#include "render/render.h"
#include "render/test_meshes.h"

namespace sombra {
namespace {

using testing::add_quad;

CameraSpec lens_spec(float radius, float fov = 40) {
    CameraSpec spec;
    spec.look_at = CameraLookAt{{0.5f, 1, 5}, {0, 0.2f, 0}, {0, 1, 0}, fov};
    spec.aperture_radius = radius;
    return spec;
}

// The point of `ray` on the plane `distance` along the camera's unit forward axis.
Vec3d on_plane(const Camera& c, const Ray& ray, double distance) {
    const Vec3d f = to_double(c.forward), o = to_double(c.origin), ro = to_double(ray.origin), d = to_double(ray.dir);
    const double f_len = length(f);
    const Vec3d fu{f.x / f_len, f.y / f_len, f.z / f_len};
    const double tau = (distance - dot(ro - o, fu)) / dot(d, fu);
    return ro + tau * d;
}

TEST(ThinLens, ZeroApertureIsThePinholeBitForBit) {
    const Camera c = make_camera(lens_spec(0), 64, 48);
    EXPECT_EQ(c.lens_radius, 0.0f);
    for (float s : {-1.0f, 0.3f, 1.0f})
        for (float u : {0.0f, 0.25f, 0.9f}) {
            const Ray a = camera_ray(c, s, -s, u, 1 - u), b = camera_ray(c, s, -s);
            EXPECT_EQ(a.origin, b.origin);
            EXPECT_EQ(a.dir, b.dir);
        }
}

TEST(ThinLens, EveryLensSampleMeetsThePinholeRayOnTheFocusPlane) {
    const Camera c = make_camera(lens_spec(0.3f), 64, 48);
    // Default focus: |look_at − origin|.
    const double focus = length(Vec3d{0.5, 0.8, 5});
    EXPECT_NEAR(c.focus_distance, focus, 1e-6 * focus);
    for (float s : {-0.9f, 0.0f, 0.6f})
        for (float t : {-0.7f, 0.4f}) {
            const Vec3d sharp = on_plane(c, camera_ray(c, s, t), focus);
            double widest = 0;
            for (int i = 0; i < 16; ++i)
                for (int j = 0; j < 16; ++j) {
                    const Ray ray =
                        camera_ray(c, s, t, (static_cast<float>(i) + 0.5f) / 16, (static_cast<float>(j) + 0.5f) / 16);
                    // The lens point lies on the disc of radius r about o, across the forward axis.
                    const Vec3d offset = to_double(ray.origin) - to_double(c.origin);
                    EXPECT_LE(length(offset), 0.3 * (1 + 1e-6));
                    EXPECT_NEAR(dot(offset, to_double(c.forward)), 0.0, 1e-6);
                    widest = std::max(widest, length(offset));
                    EXPECT_LT(length(on_plane(c, ray, focus) - sharp), 2e-6 * focus);
                }
            EXPECT_GT(widest, 0.3 * 0.9) << "samples reach the lens's rim";
        }
}

TEST(ThinLens, AnOffFocusPointSpreadsOverTheCircleOfConfusion) {
    // A small emitter at distance z = 2.5 in front of a lens of radius r =
    // 0.5 focused at d = 5. The rays that see it pass the focus plane within
    // r·|z − d|/z = 0.5 of where the pinhole ray to it does: in image-plane
    // units s, 0.5·|f| / (d·|l|); in pixels, times W/2. Inside, a sample
    // sees the emitter with probability ~0.04 (its image's share of the
    // disc): 256 samples miss it all with probability below 1e-4.
    const int w = 96, h = 96;
    const float r = 0.5f, d = 5, z = 2.5f, half = 0.05f;
    Material light{"light", MaterialType::Diffuse, Vec3{0.0f}, {}, 1, {}};
    light.ke = Vec3{1.0f};
    TriangleMesh square;
    add_quad(square, {-half, -half, -z}, {half, -half, -z}, {half, half, -z}, {-half, half, -z}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, square, {light});
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 0, 0}, {0, 0, -d}, {0, 1, 0}, 40};
    camera.aperture_radius = r;
    b.set_camera(camera);
    Scene scene = b.finish();
    RenderSettings settings{w, h, 256, 1};
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    const RenderJob job = make_render_job(scene, accel, settings, 0);
    RenderProgress progress;
    const Film film = render_image(job, progress).film;
    const double tan_half = std::tan(20 * 3.14159265358979323846 / 180);
    const double radius_px = r * (d - z) / z / (d * tan_half) * (w / 2.0);  // |f| = 1, |l| = tan(20°)
    ASSERT_GT(radius_px, 6.0);
    // The emitter's own image (a square of half-width 0.05 at z, 0.1 on the
    // focus plane: half-diagonal 0.1·√2) and half a pixel's diagonal widen
    // the disc's edge by this much at most.
    const double edge = std::sqrt(2.0) * (half * d / z) / (d * tan_half) * (w / 2.0) + std::sqrt(0.5) + 0.05;
    int inside = 0, outside = 0;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const double dist = std::hypot(i + 0.5 - w / 2.0, j + 0.5 - h / 2.0);
            const float v = film.at(i, j).x;
            if (dist < radius_px - edge) {
                EXPECT_GT(v, 0.0f) << "pixel " << i << "," << j << " inside the circle of confusion";
                ++inside;
            } else if (dist > radius_px + edge) {
                EXPECT_EQ(v, 0.0f) << "pixel " << i << "," << j << " outside the circle of confusion";
                ++outside;
            }
        }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 8000);
    // A pinhole sees the emitter in the few pixels around the centre only.
    scene.camera.aperture_radius = 0;
    const RenderJob pinhole_job = make_render_job(scene, accel, settings, 0);
    const Film pinhole = render_image(pinhole_job, progress).film;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i)
            if (std::hypot(i + 0.5 - w / 2.0, j + 0.5 - h / 2.0) > 4) {
                EXPECT_EQ(pinhole.at(i, j).x, 0.0f);
            }
}

TEST(ThinLens, SameImageForAnyThreadCountAndSeedDependent) {
    TriangleMesh slope;
    add_quad(slope, {-3, -1, -8}, {3, -1, -8}, {3, 2, -1}, {-3, 2, -1}, 0);
    SceneBuilder b;
    testing::add_world_mesh(b, slope, {Material{"grey", MaterialType::Diffuse, Vec3{0.7f}, {}, 1, {}}});
    b.add_light(make_point_light({0, 0, -0.5f}, Vec3{5}));  // on the camera's side of the slope
    CameraSpec camera;
    camera.look_at = CameraLookAt{{0, 0, 0}, {0, 0, -3}, {0, 1, 0}, 50};
    camera.aperture_radius = 0.1f;
    b.set_camera(camera);
    Scene scene = b.finish();
    const Accel accel = make_accel(scene, AccelKind::Bvh);
    RenderProgress progress;
    const RenderSettings settings{40, 30, 8, 3};
    const Film one = render_image(make_render_job(scene, accel, settings, 1), progress).film;
    const Film many = render_image(make_render_job(scene, accel, settings, 4), progress).film;
    EXPECT_EQ(one.rgb, many.rgb);
    scene.camera.aperture_radius = 0;
    const Film sharp = render_image(make_render_job(scene, accel, settings, 1), progress).film;
    EXPECT_NE(one.rgb, sharp.rgb) << "the lens changes the image";
}

}  // namespace
}  // namespace sombra
