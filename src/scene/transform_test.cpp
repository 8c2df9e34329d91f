#include "scene/transform.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sombra {
namespace {

void expect_near(Vec3 actual, Vec3 expected, float tolerance = 1e-6f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(Transform, DefaultIsIdentity) {
    const Transform t;
    EXPECT_EQ(transform_point(t, {1.5f, -2, 3}), Vec3(1.5f, -2, 3));
    EXPECT_EQ(determinant3(t), 1.0f);
}

TEST(Transform, ComposeAppliesFirstThenSecond) {
    const Transform scale = make_scale(Vec3(2));
    const Transform move = make_translate({1, 0, 0});
    // Scale, then translate: 1 → 2 → 3. Translate, then scale: 1 → 2 → 4.
    expect_near(transform_point(compose(scale, move), {1, 0, 0}), {3, 0, 0});
    expect_near(transform_point(compose(move, scale), {1, 0, 0}), {4, 0, 0});
}

TEST(Transform, ComposeIsAssociative) {
    const Transform a = make_rotate({1, 2, 3}, 33), b = make_scale({2, 0.5f, 3}), c = make_translate({4, -5, 6});
    const Vec3 p{0.3f, -1.2f, 2.5f};
    const Vec3 step_by_step = transform_point(c, transform_point(b, transform_point(a, p)));
    expect_near(transform_point(compose(compose(a, b), c), p), step_by_step, 1e-5f);
    expect_near(transform_point(compose(a, compose(b, c)), p), step_by_step, 1e-5f);
}

TEST(Transform, TranslateMovesPointsNotVectors) {
    const Transform t = make_translate({1, 2, 3});
    EXPECT_EQ(transform_point(t, {1, 1, 1}), Vec3(2, 3, 4));
    EXPECT_EQ(transform_vector(t, {1, 1, 1}), Vec3(1, 1, 1));
}

TEST(Transform, RotateIsRightHandedAndExactAtQuarterTurns) {
    // Right-handed about +y: +x goes to -z, +z goes to +x, exactly.
    const Transform r = make_rotate({0, 1, 0}, 90);
    EXPECT_EQ(transform_point(r, {1, 0, 0}), Vec3(0, 0, -1));
    EXPECT_EQ(transform_point(r, {0, 0, 1}), Vec3(1, 0, 0));
    EXPECT_EQ(transform_point(r, {0, 1, 0}), Vec3(0, 1, 0));
    // About +z: +x goes to +y; the axis length does not matter.
    EXPECT_EQ(transform_point(make_rotate({0, 0, 5}, 90), {1, 0, 0}), Vec3(0, 1, 0));
    EXPECT_EQ(transform_point(make_rotate({0, 0, 1}, -270), {1, 0, 0}), Vec3(0, 1, 0));
    EXPECT_EQ(transform_point(make_rotate({0, 0, 1}, 180), {1, 0, 0}), Vec3(-1, 0, 0));
}

TEST(Transform, RotateAboutDiagonalCyclesAxes) {
    // A third of a turn about (1, 1, 1) maps x → y → z → x.
    const Transform r = make_rotate({1, 1, 1}, 120);
    expect_near(transform_point(r, {1, 0, 0}), {0, 1, 0});
    expect_near(transform_point(r, {0, 1, 0}), {0, 0, 1});
    expect_near(transform_point(r, {0, 0, 1}), {1, 0, 0});
}

TEST(Transform, RotationPreservesLengthsAndOrientation) {
    const Transform r = make_rotate({0.3f, -1, 2}, 47);
    const Vec3 v{1.5f, -0.25f, 3};
    EXPECT_NEAR(length(transform_vector(r, v)), length(v), 1e-5f);
    EXPECT_NEAR(determinant3(r), 1.0f, 1e-6f);
}

TEST(Transform, DeterminantOfScaleMirrorAndFlattening) {
    EXPECT_FLOAT_EQ(determinant3(make_scale({2, 3, 4})), 24.0f);
    EXPECT_FLOAT_EQ(determinant3(make_scale({-1, 1, 1})), -1.0f);
    EXPECT_FLOAT_EQ(determinant3(compose(make_scale(Vec3(2)), make_translate({5, 5, 5}))), 8.0f);
    Transform rank2;  // third row = first + second
    rank2.m = {1, 2, 3, 0, 4, 5, 6, 0, 5, 7, 9, 0, 0, 0, 0, 1};
    EXPECT_EQ(determinant3(rank2), 0.0f);
}

TEST(Transform, NormalsStayPerpendicularUnderNonUniformScale) {
    // The plane x + y = 1 has normal (1, 1, 0); squash y by 4 and the surface tilts.
    const Transform t = compose(make_scale({1, 4, 1}), make_rotate({1, 0, 0}, 30));
    const Vec3 normal = normalize(Vec3{1, 1, 0});
    const Vec3 tangents[] = {{1, -1, 0}, {0, 0, 1}, {1, -1, 2}};
    const Vec3 world_normal = normalize(transform_vector(normal_transform(t), normal));
    for (const Vec3 tangent : tangents) {
        const Vec3 world_tangent = transform_vector(t, tangent);
        EXPECT_NEAR(dot(world_normal, world_tangent) / length(world_tangent), 0.0f, 1e-6f);
    }
    // Carrying the normal like a vector would be wrong: the check above must be able to fail.
    const Vec3 naive = normalize(transform_vector(t, normal));
    EXPECT_GT(std::fabs(dot(naive, normalize(transform_vector(t, {1, -1, 0})))), 0.1f);
}

TEST(Transform, NormalTransformKeepsTheOutsideOutUnderMirror) {
    // A mirror flips x: the outward normal of the face x = 1 becomes that of x = -1.
    const Transform mirror = make_scale({-1, 1, 1});
    expect_near(normalize(transform_vector(normal_transform(mirror), {1, 0, 0})), {-1, 0, 0});
    // Rotations carry normals like vectors.
    const Transform r = make_rotate({0, 1, 0}, 90);
    expect_near(transform_vector(normal_transform(r), {1, 0, 0}), {0, 0, -1});
    // Uniform scale: same direction, length 1/s.
    expect_near(transform_vector(normal_transform(make_scale(Vec3(4))), {0, 1, 0}), {0, 0.25f, 0});
}

TEST(Transform, NormalTransformIgnoresTranslation) {
    const Transform t = compose(make_scale({2, 1, 1}), make_translate({7, 8, 9}));
    const Transform n = normal_transform(t);
    EXPECT_EQ(n.m[3], 0.0f);
    EXPECT_EQ(n.m[7], 0.0f);
    EXPECT_EQ(n.m[11], 0.0f);
    expect_near(transform_vector(n, {1, 0, 0}), {0.5f, 0, 0});
}

}  // namespace
}  // namespace sombra
