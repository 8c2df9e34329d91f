#include "render/camera.h"

#include <gtest/gtest.h>

#include "render/ray_cone.h"

namespace sombra {
namespace {

void expect_near(Vec3 a, Vec3 b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

CameraSpec look_at_spec(Vec3 origin, Vec3 target, Vec3 up, float fov) {
    CameraSpec spec;
    spec.look_at = CameraLookAt{origin, target, up, fov};
    return spec;
}

TEST(Camera, LookAtFollowsTheSpecFormulas) {
    // Looking down −z with a 90° vertical field of view on a 2:1 image:
    // tan(45°) = 1, so |u| = 1 and |l| = aspect = 2; left is −x.
    const Camera c = make_camera(look_at_spec({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 90), 200, 100);
    expect_near(c.forward, {0, 0, -1});
    expect_near(c.left, {-2, 0, 0});
    expect_near(c.up, {0, 1, 0});
    expect_near(c.origin, {0, 0, 0});
}

TEST(Camera, LookAtAndBasisFormsGiveTheSameRays) {
    const CameraSpec look = look_at_spec({1, 2, 3}, {-2, 0.5f, -1}, {0, 1, 0}, 35);
    const Camera from_look = make_camera(look, 320, 240);
    CameraSpec basis;
    basis.basis = CameraBasis{from_look.origin, from_look.left, from_look.up, from_look.forward};
    const Camera from_basis = make_camera(basis, 320, 240);
    for (float s : {-1.0f, -0.3f, 0.0f, 0.7f, 1.0f})
        for (float t : {-1.0f, 0.2f, 1.0f}) {
            const Ray a = camera_ray(from_look, s, t), b = camera_ray(from_basis, s, t);
            expect_near(a.origin, b.origin);
            expect_near(a.dir, b.dir);
        }
}

TEST(Camera, LookAtBasisIsPerpendicularWithTheRequestedFieldOfView) {
    const Camera c = make_camera(look_at_spec({3, -1, 2}, {0, 0.3f, -4}, {0.1f, 1, 0}, 50), 640, 480);
    EXPECT_NEAR(dot(c.left, c.up), 0, 1e-6);
    EXPECT_NEAR(dot(c.left, c.forward), 0, 1e-6);
    EXPECT_NEAR(dot(c.up, c.forward), 0, 1e-6);
    EXPECT_NEAR(length(c.forward), 1, 1e-6);
    const float half = std::tan(25.0f * 3.14159265f / 180.0f);
    EXPECT_NEAR(length(c.up), half, 1e-6);
    EXPECT_NEAR(length(c.left), half * 640.0f / 480.0f, 1e-6);
    // The image's top is on the side of `up`.
    EXPECT_GT(dot(c.up, Vec3{0.1f, 1, 0}), 0);
}

TEST(Camera, PixelCentresFollowSpecMapping) {
    // s = 1 − (2i + 1)/W, t = 1 − (2j + 1)/H.
    const int w = 4, h = 2;
    EXPECT_FLOAT_EQ(image_plane_s(0 + 0.5f, w), 1.0f - 1.0f / 4.0f);
    EXPECT_FLOAT_EQ(image_plane_s(3 + 0.5f, w), 1.0f - 7.0f / 4.0f);
    EXPECT_FLOAT_EQ(image_plane_t(0 + 0.5f, h), 0.5f);
    EXPECT_FLOAT_EQ(image_plane_t(1 + 0.5f, h), -0.5f);
    // The image's edges are s, t = ±1.
    EXPECT_FLOAT_EQ(image_plane_s(0, w), 1.0f);
    EXPECT_FLOAT_EQ(image_plane_s(4, w), -1.0f);
}

TEST(Camera, CornerAndCentreRaysOfTheAssignmentBasis) {
    CameraSpec spec;
    spec.basis = CameraBasis{{0, 1, 5}, {2, 0, 0}, {0, 1.5f, 0}, {0, 0, -3}};
    const int w = 5, h = 3;
    const Camera c = make_camera(spec, w, h);
    // Centre pixel of an odd-sized image: s = t = 0, the ray is f itself.
    const Ray centre = camera_ray(c, image_plane_s(2.5f, w), image_plane_t(1.5f, h));
    expect_near(centre.origin, {0, 1, 5});
    expect_near(centre.dir, {0, 0, -3});
    // Top-left pixel: s = 1 − 1/5, t = 1 − 1/3: d = s·l + t·u + f.
    const Ray corner = camera_ray(c, image_plane_s(0.5f, w), image_plane_t(0.5f, h));
    expect_near(corner.dir, {0.8f * 2, (2.0f / 3.0f) * 1.5f, -3});
}

TEST(Camera, BasisFormIgnoresTheResolution) {
    CameraSpec spec;
    spec.basis = CameraBasis{{0, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const Camera a = make_camera(spec, 100, 100), b = make_camera(spec, 1920, 200);
    expect_near(a.left, b.left);
    expect_near(a.up, b.up);
    expect_near(a.forward, b.forward);
}

CameraSpec orthographic_spec(Vec3 origin, Vec3 target, Vec3 up, float half_height) {
    CameraSpec spec = look_at_spec(origin, target, up, 45);
    spec.projection = CameraSpec::Projection::Orthographic;
    spec.ortho_half_height = half_height;
    return spec;
}

TEST(Camera, OrthographicRaysAreParallelFromTheCamerasPlane) {
    // Spec §24: half-height ymag, half-width ymag·W/H, rays along −z of the
    // camera from its z = 0 plane; here the camera looks down −z from z = 5.
    const Camera c = make_camera(orthographic_spec({1, 2, 5}, {1, 2, 0}, {0, 1, 0}, 1.5f), 200, 100);
    EXPECT_TRUE(c.orthographic);
    EXPECT_EQ(c.lens_radius, 0.0f);
    for (float s : {-1.0f, -0.25f, 0.0f, 1.0f})
        for (float t : {-1.0f, 0.5f, 1.0f}) {
            const Ray r = camera_ray(c, s, t);
            expect_near(r.dir, {0, 0, -1});
            // s = +1 is the left edge (−x looking down −z), t = +1 the top.
            expect_near(r.origin, {1 - 3.0f * s, 2 + 1.5f * t, 5});
            // The lens path gives the same ray: there is no lens.
            const Ray l = camera_ray(c, s, t, 0.9f, 0.1f);
            expect_near(l.origin, r.origin);
            expect_near(l.dir, r.dir);
        }
}

TEST(Camera, OrthographicSeesTheImageTheWayRoundThePinholeDoes) {
    // From the same place, the ray through each image-plane point aims (for
    // the pinhole) or sits (orthographic) on the same side of the axis.
    const Vec3 origin{3, -1, 2}, target{0, 0.3f, -4}, up{0.1f, 1, 0};
    const Camera p = make_camera(look_at_spec(origin, target, up, 50), 640, 480);
    const Camera o = make_camera(orthographic_spec(origin, target, up, 2), 640, 480);
    expect_near(o.forward, normalize(p.forward));
    expect_near(normalize(o.left), normalize(p.left));
    expect_near(normalize(o.up), normalize(p.up));
    EXPECT_NEAR(length(o.left), 2.0f * 640 / 480, 1e-5);
    for (float s : {-1.0f, 1.0f})
        for (float t : {-1.0f, 1.0f}) {
            const Ray a = camera_ray(p, s, t), b = camera_ray(o, s, t);
            const Vec3 off = b.origin - origin, dir = a.dir - p.forward;
            EXPECT_GT(dot(off, p.left) * dot(dir, p.left), 0);
            EXPECT_GT(dot(off, p.up) * dot(dir, p.up), 0);
        }
}

TEST(Camera, OrthographicRayConesArePixelWideAndDoNotSpread) {
    // 200 × 100 pixels over a 6 × 3 view: each pixel 0.03 on a side.
    const Camera c = make_camera(orthographic_spec({1, 2, 5}, {1, 2, 0}, {0, 1, 0}, 1.5f), 200, 100);
    const RayCone cone =
        camera_ray_cone(camera_pixel_area(c.left, c.up, 200, 100), camera_ray(c, 0.3f, -0.2f).dir, true);
    EXPECT_NEAR(cone.width, 0.03f, 1e-6f);
    EXPECT_EQ(cone.spread, 0.0f);
    EXPECT_NEAR(cone_width(cone, 100.0f), 0.03f, 1e-6f);
}

TEST(Camera, OrthographicHasNoLensEvenWithAnAperture) {
    CameraSpec spec = orthographic_spec({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 1);
    spec.aperture_radius = 0.5f;
    const Camera c = make_camera(spec, 10, 10);
    EXPECT_EQ(c.lens_radius, 0.0f);
    expect_near(camera_ray(c, 0.5f, 0.5f, 0.2f, 0.7f).dir, {0, 0, -1});
}

}  // namespace
}  // namespace sombra
