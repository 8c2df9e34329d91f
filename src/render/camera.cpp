#include "render/camera.h"

#include <cmath>
#include <numbers>

#include "core/vec3d.h"

namespace sombra {

namespace {

Vec3d scaled_unit(Vec3d a, double length) {
    const double s = length / std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z);
    return {a.x * s, a.y * s, a.z * s};
}

}  // namespace

Camera make_camera(const CameraSpec& spec, int width, int height) {
    if (spec.basis) return Camera{spec.basis->origin, spec.basis->left, spec.basis->up, spec.basis->forward};

    // Look-at form, computed in double so that the basis is perpendicular to
    // float precision: f = normalize(c − o), l = normalize(up × f)·tan(fov/2)·aspect,
    // u = normalize(f × l)·tan(fov/2).
    const CameraLookAt& look = *spec.look_at;
    const Vec3d o = to_double(look.origin);
    const Vec3d c = to_double(look.look_at);
    const double aspect = static_cast<double>(width) / static_cast<double>(height);
    const double half_height = std::tan(static_cast<double>(look.fov_degrees) * std::numbers::pi / 360.0);
    const Vec3d f = scaled_unit(c - o, 1.0);
    const Vec3d l = scaled_unit(cross(to_double(look.up), f), half_height * aspect);
    const Vec3d u = scaled_unit(cross(f, l), half_height);
    return Camera{look.origin, to_float(l), to_float(u), to_float(f)};
}

}  // namespace sombra
