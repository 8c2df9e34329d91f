#include "render/camera.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sombra
