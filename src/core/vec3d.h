// Three-component double vector, for the few computations where float is not
// precise enough: the look-at camera basis, polygon triangulation far from the
// origin, the scene file's perpendicularity and determinant checks, and
// spherical triangles (render/lights/spherical_triangle.cpp).
#pragma once

#include <cmath>

#include "core/vec3.h"

namespace sombra {

struct Vec3d {
    double x, y, z;
};

inline Vec3d to_double(Vec3 v) { return {v.x, v.y, v.z}; }
inline Vec3 to_float(Vec3d v) { return {static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)}; }
constexpr Vec3d operator+(Vec3d a, Vec3d b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
constexpr Vec3d operator-(Vec3d a, Vec3d b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
constexpr Vec3d operator*(double s, Vec3d a) { return {s * a.x, s * a.y, s * a.z}; }
constexpr double dot(Vec3d a, Vec3d b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
constexpr Vec3d cross(Vec3d a, Vec3d b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3d a) { return std::sqrt(dot(a, a)); }

}  // namespace sombra
