// Affine transforms of spec §8 as 4x4 row-major matrices.
#pragma once

#include <array>

#include "core/vec3.h"

namespace sombra {

struct Transform {
    // Row-major; the last row is always [0 0 0 1].
    std::array<float, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
};

Transform make_scale(Vec3 s);
Transform make_translate(Vec3 t);
// Right-handed rotation about the (non-zero) axis through the origin.
Transform make_rotate(Vec3 axis, float degrees);
// Applies `first`, then `then`.
Transform compose(const Transform& first, const Transform& then);

Vec3 transform_point(const Transform& t, Vec3 p);
Vec3 transform_vector(const Transform& t, Vec3 v);
// The matrix that carries normals: the inverse transpose of t's linear part
// (use with transform_vector, then normalise). t must be invertible.
Transform normal_transform(const Transform& t);
// The inverse of an invertible affine t (computed in double, rounded once).
Transform inverse_affine(const Transform& t);
// Determinant of the linear 3x3 part; 0 means not invertible.
float determinant3(const Transform& t);

}  // namespace sombra
