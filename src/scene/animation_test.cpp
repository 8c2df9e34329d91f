// Keyframe interpolation (spec §22) against transforms computed by hand:
// translations and scales blend linearly, rotations by slerp along the
// shorter arc, a mirror stays in S, and the end keys hold outside the keys.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "scene/animation.h"
#include "scene/scene.h"

namespace sombra {
namespace {

void expect_near(const Transform& got, const Transform& want, float tolerance = 1e-5f) {
    for (int k = 0; k < 16; ++k) EXPECT_NEAR(got.m[k], want.m[k], tolerance) << "entry " << k;
}

TEST(Animation, TranslationAndScaleBlendLinearly) {
    const std::vector<TransformKey> keys{
        {0.0, make_translate({0, 0, 0})},
        {2.0, compose(make_scale({2, 4, 1}), make_translate({4, -2, 6}))},
    };
    // At 0.5 s, a quarter of the way: scale (1.25, 1.75, 1), translation (1, -0.5, 1.5).
    expect_near(interpolate_transform(keys, 0.5),
                compose(make_scale({1.25f, 1.75f, 1}), make_translate({1, -0.5f, 1.5f})));
    // The end keys hold, exactly.
    EXPECT_EQ(interpolate_transform(keys, -3.0).m, keys[0].transform.m);
    EXPECT_EQ(interpolate_transform(keys, 2.0).m, keys[1].transform.m);
    EXPECT_EQ(interpolate_transform(keys, 9.0).m, keys[1].transform.m);
}

TEST(Animation, RotationsFollowTheShorterArcAtConstantSpeed) {
    // 0° to 120° about y: at a quarter, 30°; a key of 350° from 0° turns back 10°, not forward 350°.
    const std::vector<TransformKey> turn{{0.0, Transform{}}, {1.0, make_rotate({0, 1, 0}, 120)}};
    expect_near(interpolate_transform(turn, 0.25), make_rotate({0, 1, 0}, 30));
    expect_near(interpolate_transform(turn, 0.5), make_rotate({0, 1, 0}, 60));
    const std::vector<TransformKey> back{{0.0, Transform{}}, {1.0, make_rotate({0, 1, 0}, 350)}};
    expect_near(interpolate_transform(back, 0.5), make_rotate({0, 1, 0}, -5));
    // A full turn needs keys less than half a turn apart: 0°, 120°, 240°, 360° passes 300° at 5/6.
    const std::vector<TransformKey> full{{0.0, Transform{}},
                                         {1.0, make_rotate({0, 0, 1}, 120)},
                                         {2.0, make_rotate({0, 0, 1}, 240)},
                                         {3.0, make_rotate({0, 0, 1}, 360)}};
    expect_near(interpolate_transform(full, 2.5), make_rotate({0, 0, 1}, 300));
}

TEST(Animation, RotationScaleAndTranslationTogether) {
    // M = T·R·S at each key; halfway is T(mid)·R(45°)·S(mid).
    const auto trs = [](Vec3 s, float degrees, Vec3 t) {
        return compose(compose(make_scale(s), make_rotate({1, 0, 0}, degrees)), make_translate(t));
    };
    const std::vector<TransformKey> keys{{1.0, trs({1, 1, 1}, 0, {0, 0, 0})}, {3.0, trs({3, 1, 2}, 90, {2, 4, 0})}};
    expect_near(interpolate_transform(keys, 2.0), trs({2, 1, 1.5f}, 45, {1, 2, 0}));
}

TEST(Animation, AMirrorStaysInTheStretchAndTheRotationIsProper) {
    const Transform mirrored = compose(make_scale({-2, 1, 1}), make_rotate({0, 0, 1}, 30));
    const PolarParts parts = polar_decompose(mirrored);
    const double* q = parts.rotation;
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-12);
    expect_near(compose_polar(parts), mirrored);
    // Two mirrored keys: every moment between is mirrored too, no flip through zero scale.
    const std::vector<TransformKey> keys{{0.0, mirrored}, {1.0, compose(mirrored, make_translate({1, 0, 0}))}};
    EXPECT_LT(determinant3(interpolate_transform(keys, 0.5)), 0.0f);
    expect_near(interpolate_transform(keys, 0.5), compose(mirrored, make_translate({0.5f, 0, 0})));
}

TEST(Animation, CameraValuesBlendLinearly) {
    std::vector<CameraKey> keys(2);
    keys[0] = CameraKey{0.0, {0, 1, 5}, {0, 0, 0}, {0, 1, 0}, 40, 0, std::nullopt};
    keys[1] = CameraKey{4.0, {4, 1, 1}, {2, 0, 0}, {0, 1, 0}, 60, 0.2f, std::nullopt};
    const CameraSpec c = interpolate_camera(keys, 1.0);
    ASSERT_TRUE(c.look_at);
    EXPECT_EQ(c.look_at->origin, (Vec3{1, 1, 4}));
    EXPECT_EQ(c.look_at->look_at, (Vec3{0.5f, 0, 0}));
    EXPECT_EQ(c.look_at->fov_degrees, 45.0f);
    EXPECT_EQ(c.aperture_radius, 0.05f);
    EXPECT_EQ(interpolate_camera(keys, 7.0).look_at->origin, (Vec3{4, 1, 1}));
}

TEST(Animation, ACameraBlendWithoutAFrameIsRefused) {
    Scene scene;
    SceneAnimation animation;
    // up turns from +y to -y: at 1 s it is zero.
    animation.camera = {CameraKey{0.0, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40, 0, std::nullopt},
                        CameraKey{2.0, {0, 0, 5}, {0, 0, 0}, {0, -1, 0}, 40, 0, std::nullopt}};
    scene.animation = animation;
    set_scene_time(scene, 0.5, "s.json");
    EXPECT_EQ(scene.camera.look_at->up, (Vec3{0, 0.5f, 0}));
    EXPECT_THROW(set_scene_time(scene, 1.0, "s.json"), Error);
}

TEST(Animation, AMovingCameraKeepsItsProjection) {
    // Keys are look-at cameras; an orthographic scene camera (a glTF
    // file's, spec §24) stays orthographic with its half-height.
    Scene scene;
    scene.camera.projection = CameraSpec::Projection::Orthographic;
    scene.camera.ortho_half_height = 2.5f;
    SceneAnimation animation;
    animation.camera = {CameraKey{0.0, {0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40, 0, std::nullopt},
                        CameraKey{2.0, {2, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40, 0, std::nullopt}};
    scene.animation = animation;
    set_scene_time(scene, 1.0, "s.json");
    EXPECT_EQ(scene.camera.look_at->origin, (Vec3{1, 0, 5}));
    EXPECT_EQ(scene.camera.projection, CameraSpec::Projection::Orthographic);
    EXPECT_EQ(scene.camera.ortho_half_height, 2.5f);
}

TEST(Animation, SetSceneTimeMovesInstancesAndRefusesASingularMoment) {
    Scene scene;
    scene.instanced_meshes.emplace_back();
    scene.instances.resize(2);
    SceneAnimation animation;
    // Scale x from 1 to -1: at the middle it passes through zero.
    animation.objects.push_back(AnimatedObject{"/objects/0",
                                               0,
                                               {{0.0, Transform{}}, {2.0, make_scale({-1, 1, 1})}},
                                               {Transform{}, Transform{}},
                                               {Transform{}, make_translate({5, 0, 0})}});
    scene.animation = animation;
    set_scene_time(scene, 2.0, "s.json");
    EXPECT_TRUE(scene.instances[0].mirrored);
    EXPECT_EQ(transform_point(scene.instances[1].object_to_world, {1, 0, 0}), (Vec3{4, 0, 0}));
    EXPECT_EQ(transform_point(scene.instances[1].world_to_object, {4, 0, 0}), (Vec3{1, 0, 0}));
    try {
        set_scene_time(scene, 1.0, "s.json");
        FAIL() << "a zero scale at 1 s";
    } catch (const Error& e) {
        EXPECT_EQ(e.where(), "s.json");
        EXPECT_NE(e.message().find("/objects/0/transform: at 1"), std::string::npos) << e.message();
    }
}

}  // namespace
}  // namespace sombra
